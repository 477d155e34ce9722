"""The import graph: layers point one way (`api → ladder, accounts → cluster → rooms →
protocol, store, rules → engine`) and no module imports itself back through others; `server/api` is
transport only. Read from the source with `ast`."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SERVER = Path(__file__).resolve().parents[2] / "server"

# What each layer may import besides itself. `codec` and `config` are leaves everyone may
# use (`priority` too, for the rooms); `app` and `__main__` wire the layers
# together and may import anything.
ALLOWED: dict[str, set[str]] = {
    "codec": set(),
    "config": set(),
    "priority": set(),
    "engine": {"codec"},
    "rules": {"engine", "codec"},
    "ai": {"rules", "engine", "codec"},
    "protocol": {"rules", "engine", "codec"},
    "store": {"codec"},
    "rooms": {"protocol", "store", "ai", "rules", "engine", "codec", "config", "priority"},
    # cluster: rooms shared among processes over Redis; used by api, uses rooms and store.
    "cluster": {"rooms", "store", "codec", "config"},
    # ladder: Play now, ranked results, the players' records; used by api, uses players.
    "ladder": {"players", "cluster", "rooms", "store"},
    # accounts: passwords, passkeys, sessions; used by api, uses store and players.
    "accounts": {"players", "store", "codec", "config"},
    "api": {
        *("cluster", "rooms", "protocol", "store", "ai", "rules", "engine", "codec", "config"),
        *("ladder", "players", "accounts"),
    },
    "players": set(),  # pure: profiles, Glicko-2, the Play now queue; used by ladder and api
}
WIRING = {"app", "__main__", "__init__"}


def module_name(path: Path) -> str:
    parts = path.relative_to(SERVER.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports_of(path: Path) -> set[str]:
    """Modules of `server` imported at run time (imports under `if TYPE_CHECKING:` are for
    the type checker only)."""
    tree = ast.parse(path.read_text())
    package = (
        module_name(path) if path.name == "__init__.py" else module_name(path).rpartition(".")[0]
    )
    found: set[str] = set()

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            return
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.startswith("server"))
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")
                anchor = anchor[: len(anchor) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            if base.startswith("server"):
                found.add(base)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    return found


def layer(module: str) -> str:
    return module.split(".")[1] if module.count(".") else "__init__"


MODULES = {module_name(p): imports_of(p) for p in SERVER.rglob("*.py")}


def upward_imports(modules: dict[str, set[str]]) -> list[str]:
    upward = []
    for module, imported in modules.items():
        own = layer(module)
        if own in WIRING:
            continue
        for target in imported:
            other = layer(target)
            if other != own and other not in ALLOWED[own]:
                upward.append(f"{module} -> {target}")
    return upward


def test_every_layer_imports_only_the_layers_below_it():
    assert upward_imports(MODULES) == []


PACKAGES = {module_name(p) for p in SERVER.rglob("__init__.py")}


def cycles_in(modules: dict[str, set[str]], packages: set[str]) -> list[list[str]]:
    """Every cycle met by a depth-first walk, except those through a package's `__init__`
    (re-exporting its own modules is not a cycle of the design)."""

    def resolve(target: str) -> str | None:
        while target and target not in modules:
            target = target.rpartition(".")[0]
        return target or None

    graph = {
        m: sorted({t for i in imported if (t := resolve(i)) and t != m})
        for m, imported in modules.items()
    }
    state: dict[str, int] = {}
    cycles: list[list[str]] = []

    def walk(node: str, path: list[str]) -> None:
        state[node] = 1
        for nxt in graph[node]:
            if state.get(nxt) == 1 and nxt in path:
                cycles.append([*path[path.index(nxt) :], nxt])
            elif nxt not in state:
                walk(nxt, [*path, nxt])
        state[node] = 2

    for start in sorted(graph):
        if start not in state:
            walk(start, [start])
    return [c for c in cycles if not packages.intersection(c)]


def test_the_module_graph_has_no_cycle():
    assert cycles_in(MODULES, PACKAGES) == []


def test_the_check_sees_a_cycle():
    modules = {"server.a": {"server.b"}, "server.b": {"server.c"}, "server.c": {"server.a"}}
    assert cycles_in(modules, set()) == [["server.a", "server.b", "server.c", "server.a"]]


@pytest.mark.parametrize(
    ("module", "target"),
    [
        ("server.rooms.live", "server.api.messages"),
        ("server.store.restore", "server.rooms"),
        ("server.engine.table", "server.rules"),
        ("server.protocol.plan", "server.rooms.room"),
    ],
)
def test_the_check_sees_an_upward_import(module: str, target: str):
    assert upward_imports({module: {target}}) == [f"{module} -> {target}"]


def test_relative_imports_resolve_and_type_checking_imports_are_left_out():
    observer = imports_of(SERVER / "rooms" / "observer.py")
    assert "server.protocol" in observer and "server.engine" in observer
    assert "server.rooms.room" not in observer  # under `if TYPE_CHECKING:`
    assert "server.rooms.room" in imports_of(SERVER / "rooms" / "live.py")  # `from .room`


TESTS = SERVER.parent / "tests"


def bench_imports(path: Path) -> list[str]:
    """The `bench` modules `path` imports (relative imports stay inside its package)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text())):
        names = []
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom) and not node.level:
            names = [node.module or ""]
        found += [n for n in names if n == "bench" or n.startswith("bench.")]
    return found


def test_the_product_tests_never_import_the_benchmarks():
    """`bench/` is the lab (its own tests live in `bench/tests`); a product test that read
    a constant from a benchmark would break when the benchmark changes."""
    importing = {
        str(p.relative_to(TESTS)): found for p in TESTS.rglob("*.py") if (found := bench_imports(p))
    }
    assert importing == {}


def test_the_bench_check_sees_an_import(tmp_path: Path):
    probe = tmp_path / "probe.py"
    probe.write_text("import bench.load\nfrom bench import ai\nfrom .bench import x\n")
    assert bench_imports(probe) == ["bench.load", "bench"]


API = SERVER / "api"
# The bodies of requests and answers: pydantic models, the transport's too, with no route.
BODIES = {"schemas.py", "player_schemas.py", "account_schemas.py"}


def third_party_imports(path: Path) -> set[str]:
    """The top-level packages outside `server` a module imports (at run time or not)."""
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(a.name.split(".")[0] for a in node.names)
        elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
            found.add(node.module.split(".")[0])
    return found


@pytest.mark.parametrize(
    "path", sorted(p for p in API.glob("*.py") if p.name != "__init__.py"), ids=lambda p: p.name
)
def test_every_api_module_is_transport(path: Path):
    """Matchmaking, ratings and other services live below (`server.ladder`, ...): a module
    of `server/api` handles HTTP or the WebSocket (FastAPI, Starlette), or is a module of
    bodies (pydantic models only)."""
    imported = third_party_imports(path)
    if path.name in BODIES:
        tree = ast.parse(path.read_text())
        assert "pydantic" in imported
        assert not [
            n.name for n in tree.body if isinstance(n, ast.FunctionDef | ast.AsyncFunctionDef)
        ]
    else:
        assert imported & {"fastapi", "starlette"}, f"{path.name} imports neither"


def test_only_deps_reads_the_app_state():
    """Routes name what they need (`server.api.deps` aliases) instead of reading
    `app.state` in their bodies."""
    readers = [p.name for p in API.glob("*.py") if "app.state" in p.read_text()]
    assert readers == ["deps.py"]


def reaches_into_physics(modules: dict[str, set[str]]) -> list[str]:
    """Imports of the engine's compiled core (`server.engine.physics`) from outside the
    engine: the rest of the server goes through `server.engine`'s public names, so a change
    to the physics is made in one place."""
    return sorted(
        f"{module} -> {target}"
        for module, imported in modules.items()
        if layer(module) != "engine"
        for target in imported
        if target == "server.engine.physics" or target.startswith("server.engine.physics.")
    )


def test_only_the_engine_imports_its_physics():
    assert reaches_into_physics(MODULES) == []


def test_the_check_sees_a_reach_into_the_physics():
    modules = {
        "server.protocol.motion": {"server.engine.physics.tick", "server.engine"},
        "server.engine.simulate": {"server.engine.physics.tick"},
    }
    assert reaches_into_physics(modules) == ["server.protocol.motion -> server.engine.physics.tick"]
