"""Alembic migrations of the store, one set for SQLite and PostgreSQL (run by `..migrate`)."""
