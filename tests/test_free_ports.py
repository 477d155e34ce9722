"""The ports handed to the servers tests start are never handed out twice: two servers
started together once got the same port from the kernel and one could not bind it."""

from __future__ import annotations

import socket

from tests.support.ports import free_port


def test_free_ports_are_never_handed_out_twice() -> None:
    # 2,000 draws from the ~28,000 ephemeral ports repeat dozens of times by chance alone
    ports = [free_port() for _ in range(2000)]
    assert len(set(ports)) == len(ports)


def test_a_free_port_can_be_bound() -> None:
    port = free_port()
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", port))
        assert sock.getsockname()[1] == port
