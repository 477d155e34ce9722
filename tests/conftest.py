"""Shared fixtures for the server tests: fast settings, an app, a TestClient, helpers."""

from __future__ import annotations

import warnings

# Starlette 1.10 asks for `httpx2` under its TestClient; plain httpx works the same here.
warnings.filterwarnings("ignore", message=".*httpx2.*")
