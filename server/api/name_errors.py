"""A refused name in one plain sentence. The schemas bound a name's length (1 to
`MAX_NAME`); pydantic's own words for that ("String should have at least 1 character")
are not for players, so a request refused only for its `name` is answered like every other
refusal of a name: 422 `{"detail": {"code": "bad_name", "message": ...}}`."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from fastapi import Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response

from server.protocol.limits import MAX_NAME

from .inputs import validation_error

EMPTY = "Type a name: it cannot be empty."
TOO_LONG = f"That name is too long: at most {MAX_NAME} characters."
NOT_TEXT = f"A name is 1 to {MAX_NAME} printable characters."


def name_sentence(errors: Sequence[Any]) -> str | None:
    """The sentence for `errors` (pydantic's) when they are all about the body's `name`,
    else None (the usual answer then)."""
    if not errors or any(tuple(e.get("loc", ()))[-2:] != ("body", "name") for e in errors):
        return None
    kind = errors[0].get("type", "")
    if kind == "bad_name":  # `inputs.Name`'s own sentence (a lone surrogate, a control)
        return str(errors[0].get("msg", NOT_TEXT))
    if kind == "string_too_short":
        return EMPTY
    if kind == "string_too_long":
        return TOO_LONG
    return NOT_TEXT


async def validation_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, RequestValidationError)
    sentence = name_sentence(exc.errors())
    if sentence is None:
        return await validation_error(request, exc)  # the usual body, always serialisable
    return JSONResponse({"detail": {"code": "bad_name", "message": sentence}}, status_code=422)
