"""`python -m server` processes for the cluster tests: started with cluster settings in the
environment, waited for, stopped, killed, paused and resumed by pid."""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import httpx

from tests.support.ports import free_port
from tests.support.tiers import needs
from tests.support.waiting import until

# Every clock short, the per-client limits off (one test address plays every seat).
BASE: dict[str, object] = {
    "grace": 60,
    "send_timeout": 2.0,
    "presence_interval": 0,
    "max_rooms_per_client": 100_000,
    "room_create_rate": "100000/minute",
    "join_rate": "100000/minute",
    "watch_rate": "100000/minute",
    "playnow_same_address": True,  # every test's players ask from one address
    "lease_ttl": 3.0,
    "heartbeat": 0.5,
    "rpc_timeout": 3.0,
}
ROOT = Path(__file__).resolve().parents[2]


@dataclass
class Server:
    port: int
    proc: subprocess.Popen
    log: Path
    stopped: bool = field(default=False)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def address(self) -> str:
        return f"127.0.0.1:{self.port}"

    def http(self) -> httpx.Client:
        return httpx.Client(base_url=self.url, timeout=20)

    def kill(self) -> None:
        """kill -9: no drain, no last write."""
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(10)
        self.stopped = True

    def terminate(self, timeout: float = 30.0) -> int:
        """SIGTERM (what a deploy sends), waits for the exit; returns the exit code. A
        process still running after `timeout` fails the test with its log and the stacks
        of its threads (SIGUSR1), then is killed."""
        self.proc.send_signal(signal.SIGTERM)
        try:
            code = self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.send_signal(signal.SIGUSR1)
            with contextlib.suppress(AssertionError):
                self.wait_for_output("most recent call first", within=5.0)
            self.kill()
            raise AssertionError(
                f"still running {timeout} s after SIGTERM:\n{self.output()[-6000:]}"
            ) from None
        self.stopped = True
        return code

    def pause(self) -> None:
        self.proc.send_signal(signal.SIGSTOP)

    def resume(self) -> None:
        self.proc.send_signal(signal.SIGCONT)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGCONT)
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(30)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.stopped = True

    def output(self) -> str:
        return self.log.read_text(errors="replace")

    def wait_for_output(self, *lines: str, within: float) -> None:
        """Wait until every one of `lines` is in the log. Lines logged by different tasks or
        threads come in no fixed order, so each is waited for, not one after the other."""

        def logged() -> bool:
            text = self.output()  # the file read once a look
            return all(line in text for line in lines)

        until(
            logged,
            within,
            lambda: f"not all logged: {lines}\n{self.output()[-3000:]}",
        )


@dataclass
class ServerSet:
    all: list[Server]

    @classmethod
    def start(cls, n: int, redis_url: str, folder: Path, settings: dict[str, object]) -> ServerSet:
        """n processes in parallel, each waited for until it answers /health."""
        needs("slow")
        merged = {**BASE, **settings}
        if "db_path" not in merged:
            merged["db_path"] = folder / "pool.db"
        servers = []
        for _ in range(n):
            port = free_port()
            env = {
                **os.environ,
                **{f"POOL_{k.upper()}": str(v) for k, v in merged.items()},
                "POOL_REDIS_URL": redis_url,
                "POOL_PUBLIC_URL": f"http://127.0.0.1:{port}",
            }
            log = folder / f"server-{port}.log"
            proc = subprocess.Popen(
                [sys.executable, "-m", "server", "--port", str(port), "--log-level", "info"],
                cwd=ROOT,
                env=env,
                stdout=log.open("w"),
                stderr=subprocess.STDOUT,
            )
            servers.append(Server(port, proc, log))
        group = cls(servers)
        for server in servers:
            group.wait_healthy(server)
        return group

    @staticmethod
    def wait_healthy(server: Server, timeout: float = 180.0) -> None:
        deadline = time.monotonic() + timeout
        while True:
            if server.proc.poll() is not None:
                raise RuntimeError(f"server exited at start:\n{server.output()[-3000:]}")
            try:
                if httpx.get(f"{server.url}/health", timeout=2).status_code == 200:
                    return
            except httpx.TransportError:
                pass
            if time.monotonic() > deadline:
                raise RuntimeError(f"server did not start:\n{server.output()[-3000:]}")
            time.sleep(0.2)

    def by_url(self, url: str) -> Server:
        """The server whose WebSocket URL (`ws_url`) or address `url` names."""
        return next(s for s in self.all if s.address in url)

    def others(self, *not_these: Server) -> list[Server]:
        return [s for s in self.all if s not in not_these and not s.stopped]
