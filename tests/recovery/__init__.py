"""Storage, restart recovery and fault tests (issue 7)."""
