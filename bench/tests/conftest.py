"""The benchmarks' own tests share the server tests' fixtures (a fresh database per test,
the engine compiled once before any test)."""

from tests.conftest import _own_database, _warm_engine  # noqa: F401
