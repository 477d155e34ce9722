"""How `server.rules` is put together: imports point one way, and `Game` never asks its
kind (what differs between kinds of game lives in the strategies)."""

from __future__ import annotations

import ast
from graphlib import CycleError, TopologicalSorter
from pathlib import Path

import server.rules

PACKAGE = Path(server.rules.__file__).parent
MODULES = {p.stem: ast.parse(p.read_text()) for p in PACKAGE.glob("*.py")}


def imported(tree: ast.Module) -> set[str]:
    """Modules of this package that `tree` imports, at any depth (TYPE_CHECKING too)."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level == 1 and node.module:
                out.add(node.module.split(".")[0])
            elif node.level == 1:
                out.update(a.name for a in node.names)
            elif node.module and node.module.startswith("server.rules."):
                out.add(node.module.split(".")[2])
    return out & set(MODULES)


def test_the_package_has_no_import_cycles() -> None:
    graph = {name: imported(tree) for name, tree in MODULES.items()}
    try:
        order = list(TopologicalSorter(graph).static_order())
    except CycleError as err:  # pragma: no cover - the failure message
        raise AssertionError(f"import cycle: {err.args[1]}") from None
    assert order.index("kinds") < order.index("game") < order.index("match")
    for strategy in ("eight_ball", "nine_ball", "practice"):
        assert order.index(strategy) < order.index("kinds")
        assert not graph[strategy] & {"game", "match", "kinds"}


def test_game_never_tests_its_kind() -> None:
    for node in ast.walk(MODULES["game"]):
        if isinstance(node, ast.Compare):
            names = [node.left, *node.comparators]
            assert not any(
                (isinstance(n, ast.Attribute | ast.Name) and getattr(n, "attr", None) == "kind")
                or getattr(n, "id", None) == "kind"
                for n in names
            ), ast.unparse(node)
