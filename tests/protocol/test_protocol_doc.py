"""docs/protocol.md against the protocol's models, so the two cannot drift apart.

Conventions of the doc that these tests rely on:

- Every ```json block is validated, value by value (a block may hold several JSON values,
  e.g. one message a line), against the models of the section it is in:
  - under the `### Client → server messages` heading: `parse_client_message`;
  - an object with a `type` under the replay route's heading (`.../replay`): `replay_messages`;
  - any other object with a `type`: `server_messages`;
  - any other value: the request body, the response model or `ErrorResponse` of the HTTP
    route named by the nearest heading in backticks, e.g. ``### `POST /api/rooms` ``
    (path parameters may be named differently: `{id}` matches `{match_id}`).
  A value must also survive the round trip through its model unchanged (no unknown keys
  silently dropped). A block that is not a message nor a body says so with
  `<!-- not-validated -->` on the line before it.
- Each WebSocket message type has a section: a heading naming the type in backticks (server
  messages under `### Server → client messages`, the replay's `shot_result` under the replay
  route), or, for client messages, a row of the table under `### Client → server messages`
  whose first cell is the type in backticks. Every field of the model, and of the models
  nested in it (the first time a nested model appears), is named in backticks in the prose
  of that section (not only in an example). `type` and `seq` are explained once, in the
  introduction and in `### Sequence numbers`.
- Every HTTP route of the API routers has a heading naming it in backticks; every field of its
  request and response bodies (and of the models nested in them) is named in backticks or is
  a key of a validated example in that section.
- Wherever the prose names a limit as `` `max_speed` (12) ``, the number is `Limits()`'s, and
  the `GET /api/limits` example and `welcome.limits` are exactly `Limits()`.
"""

from __future__ import annotations

import dataclasses
import json
import re
import typing
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path
from typing import Any

import pytest
from fastapi.routing import APIRoute
from pydantic import BaseModel, TypeAdapter, ValidationError

from server.api.accounts import router as accounts_router
from server.api.analysis import router as analysis_router
from server.api.drills import router as drills_router
from server.api.matches import router as matches_router
from server.api.meta import router as meta_router
from server.api.passkeys import router as passkeys_router
from server.api.players import router as players_router
from server.api.rooms import router as rooms_router
from server.api.schemas import ErrorResponse
from server.config import Settings
from server.engine import TICK_HZ
from server.protocol import AnyClientMessage, BadMessage, Limits, parse_client_message
from server.protocol.limits import FRAMES_PER_MESSAGE
from server.protocol.outbound import (
    AnyReplayMessage,
    AnyServerMessage,
    replay_messages,
    server_messages,
)

DOC = Path(__file__).resolve().parents[2] / "docs" / "protocol.md"
NOT_VALIDATED = "<!-- not-validated -->"
SERVER_HEADING = "Server → client messages"
CLIENT_HEADING = "Client → server messages"
REPLAY_HEADING = "/replay`"  # the replay route's heading ends so
COMMON_FIELDS = {"type", "seq"}  # explained once for every message


# ---- the doc, parsed -------------------------------------------------------------------


@dataclass
class Heading:
    level: int
    title: str
    start: int  # line index of the heading
    end: int = 0  # line index where its section ends (exclusive)


@dataclass
class Block:
    line: int  # 1-based line of the opening fence
    text: str
    marked: bool  # preceded by NOT_VALIDATED
    path: list[Heading] = field(default_factory=list)  # enclosing headings, outermost first

    def under(self, needle: str) -> Heading | None:
        return next((h for h in reversed(self.path) if needle in h.title), None)


@dataclass
class Doc:
    lines: list[str]
    headings: list[Heading]
    blocks: list[Block]

    def section(self, heading: Heading) -> list[str]:
        return self.lines[heading.start + 1 : heading.end]

    def find(self, needle: str, within: Heading | None = None) -> list[Heading]:
        return [
            h
            for h in self.headings
            if needle in h.title and (within is None or within.start < h.start < within.end)
        ]

    def one(self, needle: str, within: Heading | None = None) -> Heading:
        found = self.find(needle, within)
        assert len(found) == 1, f"expected one heading with {needle!r}, found {len(found)}"
        return found[0]


@cache
def doc() -> Doc:
    lines = DOC.read_text(encoding="utf-8").splitlines()
    headings: list[Heading] = []
    blocks: list[Block] = []
    fence: int | None = None
    for i, line in enumerate(lines):
        if line.startswith("```"):
            if fence is None:
                fence = i
            else:
                if lines[fence].strip() == "```json":
                    previous = next((x for x in reversed(lines[:fence]) if x.strip()), "")
                    blocks.append(
                        Block(
                            fence + 1,
                            "\n".join(lines[fence + 1 : i]),
                            previous.strip() == NOT_VALIDATED,
                        )
                    )
                fence = None
            continue
        if fence is None and (m := re.match(r"(#{1,6})\s+(.*)", line)):
            headings.append(Heading(len(m.group(1)), m.group(2).strip(), i))
    assert fence is None, "a code fence is not closed"
    for k, h in enumerate(headings):
        h.end = next((g.start for g in headings[k + 1 :] if g.level <= h.level), len(lines))
    for block in blocks:
        block.path = [h for h in headings if h.start < block.line - 1 < h.end]
    return Doc(lines, headings, blocks)


def prose_names(lines: list[str]) -> set[str]:
    """Identifiers inside inline code spans, outside fenced blocks."""
    names: set[str] = set()
    fenced = False
    for line in lines:
        if line.startswith("```"):
            fenced = not fenced
            continue
        if not fenced:
            for span in re.findall(r"`([^`]+)`", line):
                names.update(re.findall(r"[A-Za-z_][A-Za-z0-9_]*", span))
    return names


def json_values(text: str) -> list[Any]:
    """Every JSON value of a block, in order (one or many, e.g. one message a line)."""
    decoder = json.JSONDecoder()
    values: list[Any] = []
    i = 0
    while True:
        while i < len(text) and text[i].isspace():
            i += 1
        if i == len(text):
            return values
        value, i = decoder.raw_decode(text, i)
        values.append(value)


# ---- the models ------------------------------------------------------------------------


def union_members(union: Any) -> list[type[BaseModel]]:
    inner = typing.get_args(union)[0]  # Annotated[A | B | ..., Field(...)]
    return list(typing.get_args(inner))


def type_of(model: type[BaseModel]) -> str:
    return typing.get_args(model.model_fields["type"].annotation)[0]


def field_names(cls: Any) -> list[str]:
    if isinstance(cls, type) and issubclass(cls, BaseModel):
        return list(cls.model_fields)
    return [f.name for f in dataclasses.fields(cls)]


def field_types(cls: Any) -> list[Any]:
    if isinstance(cls, type) and issubclass(cls, BaseModel):
        return [f.annotation for f in cls.model_fields.values()]
    hints = typing.get_type_hints(cls)
    return [hints[f.name] for f in dataclasses.fields(cls)]


def nested(annotation: Any) -> list[Any]:
    """Models and dataclasses inside an annotation (through lists, tuples, unions)."""
    if isinstance(annotation, type) and (
        issubclass(annotation, BaseModel) or dataclasses.is_dataclass(annotation)
    ):
        return [annotation]
    return [m for arg in typing.get_args(annotation) for m in nested(arg)]


def required_names(cls: Any, seen: set[Any]) -> dict[str, str]:
    """Field name -> the model it belongs to, for `cls` and the models nested in it that
    were not documented before (`seen` is updated)."""
    names = {name: cls.__name__ for name in field_names(cls)}
    for annotation in field_types(cls):
        for inner in nested(annotation):
            if inner not in seen:
                seen.add(inner)
                for name, owner in required_names(inner, seen).items():
                    names.setdefault(name, owner)
    return names


ROUTERS = (
    meta_router,
    rooms_router,
    matches_router,
    analysis_router,
    drills_router,
    players_router,
    accounts_router,
    passkeys_router,
)


def api_routes() -> list[APIRoute]:
    return [r for router in ROUTERS for r in router.routes if isinstance(r, APIRoute)]


def route_key(method: str, path: str) -> str:
    return f"{method} {re.sub(r'{[^}]*}', '{}', path)}"


def route_models(route: APIRoute) -> list[type[BaseModel]]:
    models: list[type[BaseModel]] = [ErrorResponse]
    if isinstance(route.response_model, type) and issubclass(route.response_model, BaseModel):
        models.append(route.response_model)
    for answer in route.responses.values():  # another status's own body (e.g. a 202)
        model = answer.get("model")
        if isinstance(model, type) and issubclass(model, BaseModel) and model not in models:
            models.append(model)
    for param in route.dependant.body_params:
        models.extend(nested(param.field_info.annotation))
    return models


def routes_by_key() -> dict[str, APIRoute]:
    return {
        route_key(method, r.path): r
        for r in api_routes()
        for method in r.methods or ()
        if method != "HEAD"
    }


def heading_route(heading: Heading) -> str | None:
    m = re.search(r"`(GET|POST|PUT|PATCH|DELETE) (/[^`\s?]*)[^`]*`", heading.title)
    return route_key(m.group(1), m.group(2)) if m else None


# ---- validation of the examples --------------------------------------------------------


def unchanged(model: BaseModel, value: Any) -> bool:
    return json.loads(model.model_dump_json(exclude_unset=True)) == value


def check_value(block: Block, value: Any) -> str:
    """Validate one JSON value of a block; returns what validated it, raises otherwise."""
    where = f"docs/protocol.md:{block.line}"
    if isinstance(value, dict) and "type" in value:
        if block.under(CLIENT_HEADING):
            try:
                message = parse_client_message(json.dumps(value))
            except BadMessage as exc:
                raise AssertionError(f"{where}: client message {value}: {exc.message}") from None
            assert unchanged(message, value), f"{where}: {value} changes when parsed"
            return f"client {value['type']}"
        adapter: TypeAdapter = replay_messages if block.under(REPLAY_HEADING) else server_messages
        kind = "replay" if adapter is replay_messages else "server"
        try:
            message = adapter.validate_python(value)
        except ValidationError as exc:
            raise AssertionError(f"{where}: not a valid {kind} message:\n{exc}") from None
        assert unchanged(message, value), f"{where}: {value['type']} changes when validated"
        return f"{kind} {value['type']}"
    route = next((key for h in reversed(block.path) if (key := heading_route(h))), None)
    routes = routes_by_key()
    assert route in routes, (
        f"{where}: a JSON block that is no message and under no API "
        f"route heading (mark it {NOT_VALIDATED} if it is neither)"
    )
    failures = []
    for model in route_models(routes[route]):
        try:
            parsed = model.model_validate(value)
        except ValidationError as exc:
            failures.append(f"{model.__name__}: {exc}")
            continue
        if unchanged(parsed, value):
            return model.__name__
        failures.append(f"{model.__name__}: keys dropped or values changed")
    raise AssertionError(f"{where}: matches no model of {route}:\n" + "\n".join(failures))


@cache
def checked_examples() -> tuple[list[tuple[Block, Any, str]], list[str]]:
    """(block, value, what validated it) for every value of every block, and the failures."""
    ok, failures = [], []
    for block in doc().blocks:
        if block.marked:
            continue
        for value in json_values(block.text):
            try:
                ok.append((block, value, check_value(block, value)))
            except AssertionError as exc:
                failures.append(str(exc))
    return ok, failures


def validated_examples() -> list[tuple[Block, Any, str]]:
    return checked_examples()[0]


def test_every_json_block_parses():
    blocks = doc().blocks
    assert len(blocks) > 20
    for block in blocks:
        try:
            json_values(block.text)
        except ValueError as exc:
            raise AssertionError(f"docs/protocol.md:{block.line}: not JSON: {exc}") from None


def test_every_example_validates_against_its_model():
    examples, failures = checked_examples()
    assert not failures, "\n\n".join(failures)
    marked = [b for b in doc().blocks if b.marked]
    assert len(marked) <= 2, "use the not-validated mark sparingly"
    checked = {what for _, _, what in examples}
    # every message type has a real example
    for model in union_members(AnyServerMessage):
        assert f"server {type_of(model)}" in checked, f"no example of `{type_of(model)}`"
    for model in union_members(AnyReplayMessage):
        assert f"replay {type_of(model)}" in checked, f"no replay example of {model.__name__}"
    for model in union_members(AnyClientMessage):
        assert f"client {type_of(model)}" in checked, f"no example of `{type_of(model)}`"


# ---- every message and field documented -------------------------------------------------


def message_section(type_name: str, parent: Heading) -> list[str]:
    d = doc()
    found = d.find(f"`{type_name}`", within=parent)
    if found:
        assert len(found) == 1, f"several sections for `{type_name}` under {parent.title}"
        return d.section(found[0])
    rows = [
        line for line in d.section(parent) if re.match(rf"\|\s*`{re.escape(type_name)}`\s*\|", line)
    ]
    assert len(rows) == 1, (
        f"`{type_name}` has no section (heading or table row) under {parent.title!r}"
    )
    return rows


def test_every_message_type_and_field_is_documented():
    d = doc()
    server = d.one(SERVER_HEADING)
    client = d.one(CLIENT_HEADING)
    replay = d.one(REPLAY_HEADING)
    seen: set[Any] = set()
    sections = [(m, server) for m in union_members(AnyServerMessage)]
    sections += [
        (m, replay)
        for m in union_members(AnyReplayMessage)
        if m not in union_members(AnyServerMessage)
    ]
    sections += [(m, client) for m in union_members(AnyClientMessage)]
    missing = []
    for model, parent in sections:
        type_name = type_of(model)
        seen.add(model)
        documented = prose_names(message_section(type_name, parent))
        for name, owner in required_names(model, seen).items():
            if name not in COMMON_FIELDS and name not in documented:
                missing.append(f"`{type_name}` ({parent.title}): field `{name}` of {owner}")
    assert not missing, "undocumented fields:\n" + "\n".join(missing)
    assert "type" in prose_names(d.lines[: d.headings[1].start])
    assert "seq" in prose_names(d.section(d.one("Sequence numbers")))


def test_every_http_route_and_response_field_is_documented():
    d = doc()
    keyed = {}
    for heading in d.headings:
        for m in re.finditer(r"`(GET|POST|PUT|PATCH|DELETE) (/[^`\s?]*)[^`]*`", heading.title):
            keyed[route_key(m.group(1), m.group(2))] = heading
    examples = validated_examples()
    missing = []
    for key, route in routes_by_key().items():
        assert key in keyed, f"no heading for `{key}`"
        heading = keyed[key]
        documented = prose_names(d.section(heading))
        for block, value, _ in examples:
            if heading.start < block.line - 1 < heading.end:
                documented |= _keys(value)
        for model in route_models(route)[1:]:  # request and response bodies
            for name, owner in required_names(model, set()).items():
                if name not in documented:
                    missing.append(f"{key}: field `{name}` of {owner}")
    assert not missing, "undocumented response fields:\n" + "\n".join(missing)


def _keys(value: Any) -> set[str]:
    if isinstance(value, dict):
        return set(value) | {k for v in value.values() for k in _keys(v)}
    if isinstance(value, list):
        return {k for v in value for k in _keys(v)}
    return set()


# ---- the numbers ------------------------------------------------------------------------


def test_limits_in_the_doc_are_the_current_ones():
    limits = Limits().model_dump()
    text = DOC.read_text(encoding="utf-8")
    for name, value in limits.items():
        quoted = re.findall(rf"`{name}`\s*\(([-0-9.]+)\)", text)
        assert quoted, f"the doc never gives `{name}` with its value, as `{name}` ({value})"
        for number in quoted:
            assert float(number) == value, f"the doc says `{name}` ({number}); it is {value}"
    examples = validated_examples()
    d = doc()
    limits_route = d.one("`GET /api/limits`")
    bodies = [v for b, v, _ in examples if limits_route.start < b.line - 1 < limits_route.end]
    assert bodies == [limits], "the `GET /api/limits` example is not `Limits()`"
    welcomes = [v for _, v, what in examples if what == "server welcome"]
    assert welcomes and all(w["limits"] == limits for w in welcomes)


def test_stream_rates_in_the_doc_are_the_defaults():
    settings = Settings()
    welcomes = [v for _, v, what in validated_examples() if what == "server welcome"]
    for welcome in welcomes:
        assert welcome["tick_hz"] == TICK_HZ
        assert welcome["frame_every"] == settings.frame_every
        assert welcome["frames_per_message"] == FRAMES_PER_MESSAGE
    details = [v["stream"] for _, v, what in validated_examples() if what == "MatchDetail"]
    assert details and all(
        s
        == {
            "tick_hz": TICK_HZ,
            "frame_every": settings.frame_every,
            "frames_per_message": FRAMES_PER_MESSAGE,
        }
        for s in details
    )


@pytest.mark.parametrize("pattern", [r"\bissue\s*#?\d+", r"\bround\s*\d+"])
def test_no_references_to_issues_or_rounds(pattern):
    assert not re.search(pattern, DOC.read_text(encoding="utf-8"), re.IGNORECASE)
