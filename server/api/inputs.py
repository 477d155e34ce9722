"""What an HTTP request must be before a route sees it, by the socket's rules: bodies strict
(no coercion: `"3"`, `3.0` or `true` is not an integer, `"yes"` not a boolean), finite numbers
only, ids within what the store's columns hold, names of printable characters. A refusal is a
`422` whose body can always be written: the default handler echoes the input, and a NaN or a
lone surrogate in it made that echo fail with a 500.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

from fastapi import Path, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse
from pydantic import AfterValidator, BaseModel, BeforeValidator, ConfigDict, Field
from pydantic_core import PydanticCustomError

from server.protocol.limits import MAX_NAME

# The history's ids are PostgreSQL `INTEGER` columns (SQLite's hold 64 bits): a larger one
# is refused before the query, which would otherwise fail with an OverflowError.
MAX_ROW_ID = 2**31 - 1
RowId = Annotated[int, Path(ge=0, le=MAX_ROW_ID, description=f"0 to {MAX_ROW_ID}")]


class StrictBody(BaseModel):
    """A request body validated as the socket's messages are: unknown fields, coercions and
    NaN or infinite numbers are refused."""

    model_config = ConfigDict(extra="forbid", allow_inf_nan=False, strict=True)


def _is_surrogate(ch: str) -> bool:
    return 0xD800 <= ord(ch) <= 0xDFFF


def no_lone_surrogates(value: Any) -> Any:
    """Checked before the type (whose own refusal of them says less): JSON's `"\\ud800"`
    is not text in any encoding."""
    if isinstance(value, str) and any(_is_surrogate(ch) for ch in value):
        raise PydanticCustomError(
            "bad_name", "A name cannot hold a lone surrogate (it is not valid Unicode text)."
        )
    return value


def printable_name(value: str) -> str:
    """`value`, if it can be shown to everyone: no control characters (tabs, newlines,
    NUL...)."""
    if not value.isprintable():
        raise PydanticCustomError(
            "bad_name", "A name holds printable characters only (no tabs, newlines or controls)."
        )
    return value


Name = Annotated[
    str,
    Field(min_length=1, max_length=MAX_NAME, description=f"1-{MAX_NAME} printable characters"),
    AfterValidator(printable_name),
    BeforeValidator(no_lone_surrogates),
]


def json_safe(value: Any) -> Any:
    """`value` with what JSON cannot carry made readable: NaN and infinities as their names,
    lone surrogates and undecodable bytes as `\\udxxx` / `\\xNN` escapes."""
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)
    if isinstance(value, bytes):
        return value.decode("utf-8", "backslashreplace")
    if isinstance(value, str):
        if any(_is_surrogate(ch) for ch in value):
            return value.encode("utf-8", "backslashreplace").decode("utf-8")
        return value
    if isinstance(value, dict):
        return {json_safe(k): json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_safe(v) for v in value]
    return value


async def validation_error(request: Request, exc: Exception) -> JSONResponse:  # noqa: ARG001
    """FastAPI's `422` body (`{"detail": [{"type", "loc", "msg", "input"}, ...]}`), always
    serialisable."""
    errors = exc.errors() if isinstance(exc, RequestValidationError) else []
    detail = json_safe(jsonable_encoder(json_safe(errors)))  # again: `ctx` may hold objects
    return JSONResponse(status_code=422, content={"detail": detail})
