"""Free loopback ports for the servers tests and benchmarks start.

The kernel only promises that a port is free while something holds it: a port asked for
and released can be handed out again before the server it was meant for binds it. Two
servers started together then got the same port and one failed with "address already in
use". So a port handed out here is never handed out again by this process.
"""

from __future__ import annotations

import socket

_handed_out: set[int] = set()


def free_port() -> int:
    """A loopback port free now and not handed out before by this process."""
    while True:
        with socket.socket() as sock:
            sock.bind(("127.0.0.1", 0))
            port = int(sock.getsockname()[1])
        if port not in _handed_out:
            _handed_out.add(port)
            return port
