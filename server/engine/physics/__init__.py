"""The compiled core: per-ball motion, event detection, event resolution and the tick loop.

Everything here is numba-compiled (cache on) and works on the raw arrays of a `BallSet`.
The Python API in `server.engine.simulate` wraps it.
"""
