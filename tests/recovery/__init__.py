"""Storage, restart recovery and fault tests."""
