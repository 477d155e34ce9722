"""Field types of the stored games that also read what the code before the codec wrote.

Saved rooms in existing databases hold tables as their constructor fields in a list and
8-ball groups as `[[seat, group], ...]`; these validators turn both into what the fields
hold now, before the codec's own validation.
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BeforeValidator

from server.engine import Table


def _table(value: Any) -> Any:
    """`[length, width, ball_radius, corner_mouth, side_mouth]` as the table it describes."""
    return Table(*value) if isinstance(value, list | tuple) else value


def _groups(value: Any) -> Any:
    """`[[seat, group], ...]` as the mapping it lists."""
    return dict(value) if isinstance(value, list) else value


StoredTable = Annotated[Table, BeforeValidator(_table)]
Groups = Annotated[dict[int, str], BeforeValidator(_groups)]
