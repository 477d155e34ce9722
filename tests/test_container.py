"""The Docker image, without a container engine: run the Dockerfile's CMD the way the image
would, from what the Dockerfile says rather than a restatement of it.

A sandbox stands in for the image's file system: the files the Dockerfile COPYs (filtered
by .dockerignore) under the WORKDIR, read-only; each VOLUME a writable directory; ENV
values that are absolute paths moved into the sandbox (`/data/billiards.db` becomes
`<sandbox>/data/billiards.db`). The CMD runs there, on a free loopback port instead of
0.0.0.0:8000, with this virtualenv's python, as a non-root user standing in for USER when
the tests run as root (`nobody`), else as the current user. What is not exercised: the
build's RUN steps (pip installs, the numba compile), so the server compiles its kernels on
start, into a fresh cache.
"""

from __future__ import annotations

import importlib
import json
import os
import pwd
import re
import shlex
import shutil
import signal
import sqlite3
import stat
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

import pytest

from tests.support.ports import free_port

REPO = Path(__file__).resolve().parent.parent
STARTUP_TIMEOUT = 90.0  # a cold numba compile of every kernel takes ~25 s on 2 idle cores
STOP_TIMEOUT = 30.0

pytestmark = [pytest.mark.timeout(240), pytest.mark.slow]


# --- the Dockerfile, as the builder reads it ----------------------------------------------


@dataclass
class Image:
    """What the Dockerfile says about the running container (the final stage)."""

    env: dict[str, str] = field(default_factory=dict)
    workdir: str = "/"
    user: str = "root"
    volumes: list[str] = field(default_factory=list)
    copies: list[tuple[list[str], str]] = field(default_factory=list)  # (sources, dest)
    cmd: list[str] = field(default_factory=list)
    healthcheck: list[str] = field(default_factory=list)
    steps: list[tuple[str, str]] = field(default_factory=list)  # (instruction, arguments)


def instructions(text: str) -> list[tuple[str, str]]:
    """(INSTRUCTION, arguments) with line continuations joined and comments dropped."""
    out: list[tuple[str, str]] = []
    pending = ""
    for line in text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#") or (pending and not stripped):
            continue  # comment lines (also inside a continuation), empty continued lines
        if not pending and not stripped:
            continue
        if line.rstrip().endswith("\\"):
            pending += line.rstrip()[:-1]
            continue
        keyword, _, rest = (pending + line).strip().partition(" ")
        out.append((keyword.upper(), rest.strip()))
        pending = ""
    assert not pending, "the Dockerfile ends inside a line continuation"
    return out


def parse_dockerfile(path: Path) -> Image:
    image = Image()
    for keyword, rest in instructions(path.read_text()):
        image.steps.append((keyword, rest))
        if keyword == "FROM":
            image = Image(steps=image.steps)  # a new stage starts afresh
        elif keyword == "ENV":
            tokens = shlex.split(rest)
            if all("=" in token for token in tokens):
                image.env.update(token.split("=", 1) for token in tokens)
            else:  # the old `ENV KEY value` form
                key, value = rest.split(None, 1)
                image.env[key] = value
        elif keyword == "WORKDIR":
            image.workdir = str(PurePosixPath(image.workdir) / rest)
        elif keyword == "USER":
            image.user = rest
        elif keyword == "VOLUME":
            image.volumes += json.loads(rest) if rest.startswith("[") else rest.split()
        elif keyword in ("COPY", "ADD"):
            args = shlex.split(rest)
            flags = [a for a in args if a.startswith("--")]
            assert all(f.startswith(("--chown", "--chmod")) for f in flags), flags
            *sources, dest = [a for a in args if not a.startswith("--")]
            dest_path = PurePosixPath(image.workdir) / dest
            directory = dest.endswith("/") or len(sources) > 1
            image.copies.append((sources, str(dest_path) + ("/" if directory else "")))
        elif keyword == "CMD":
            assert rest.startswith("["), "CMD in exec form (a JSON list): signals reach python"
            image.cmd = json.loads(rest)
        elif keyword == "HEALTHCHECK":
            match = re.search(r"(?:^|\s)CMD\s+(.*)$", rest, re.S)
            assert match, rest
            command = match.group(1)
            image.healthcheck = (
                json.loads(command) if command.startswith("[") else ["/bin/sh", "-c", command]
            )
    return image


def dockerignore_rules(path: Path) -> list[tuple[bool, re.Pattern[str]]]:
    """(exclude?, regex) per line, in order: the last rule that matches a path decides."""
    rules = []
    for line in path.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        include = line.startswith("!")
        pattern = line.lstrip("!").strip("/")
        regex = ""
        i = 0
        while i < len(pattern):
            if pattern.startswith("**/", i):
                regex, i = regex + "(?:.*/)?", i + 3
            elif pattern.startswith("**", i):
                regex, i = regex + ".*", i + 2
            elif pattern[i] == "*":
                regex, i = regex + "[^/]*", i + 1
            elif pattern[i] == "?":
                regex, i = regex + "[^/]", i + 1
            else:
                regex, i = regex + re.escape(pattern[i]), i + 1
        rules.append((not include, re.compile(regex)))
    return rules


def ignored(relative: str, rules: list[tuple[bool, re.Pattern[str]]]) -> bool:
    """Whether the build context leaves `relative` out (it or a directory above it matches)."""
    parts = relative.split("/")
    prefixes = ["/".join(parts[:n]) for n in range(1, len(parts) + 1)]
    verdict = False
    for exclude, regex in rules:
        if any(regex.fullmatch(prefix) for prefix in prefixes):
            verdict = exclude
    return verdict


# --- a sandbox standing in for the image's file system ------------------------------------


@dataclass
class Runner:
    """How the server's process is started: as whom, and with what it may read."""

    uid: int
    gid: int
    prefix: list[str]  # e.g. setpriv ...; empty when Popen's user/group do it
    popen: dict  # user/group/extra_groups for Popen, or nothing
    description: str

    def run(self, argv: list[str], **kwargs) -> subprocess.CompletedProcess:
        return subprocess.run(self.prefix + argv, **self.popen, **kwargs)

    def start(self, argv: list[str], **kwargs) -> subprocess.Popen:
        return subprocess.Popen(self.prefix + argv, **self.popen, **kwargs)


class Sandbox:
    """`root` plays the image's `/`: `inside("/app/web")` is where the image's /app/web is."""

    def __init__(self, image: Image) -> None:
        self.image = image
        # not pytest's tmp_path: its directories are private to the user running the tests
        self.root = Path(tempfile.mkdtemp(prefix="pool-image-"))
        self.root.chmod(0o755)

    def inside(self, image_path: str) -> Path:
        return self.root / PurePosixPath(image_path).relative_to("/")

    def map_env(self, value: str) -> str:
        return str(self.inside(value)) if value.startswith("/") else value

    def copy_context(self) -> None:
        """Every COPY of the Dockerfile, from the repository, as .dockerignore filters it."""
        rules = dockerignore_rules(REPO / ".dockerignore")
        for sources, dest in self.image.copies:
            for source in sources:
                target = self.inside(dest.rstrip("/"))
                if dest.endswith("/"):
                    target = target / Path(source).name
                origin = REPO / source
                if ignored(source, rules):
                    continue
                if origin.is_dir():
                    self._copy_tree(origin, target, rules)
                else:
                    target.parent.mkdir(parents=True, exist_ok=True)
                    shutil.copy2(origin, target)

    def _copy_tree(self, origin: Path, target: Path, rules) -> None:
        for directory, subdirs, files in os.walk(origin):
            here = Path(directory)
            relative = here.relative_to(REPO).as_posix()
            subdirs[:] = [d for d in subdirs if not ignored(f"{relative}/{d}", rules)]
            (target / here.relative_to(origin)).mkdir(parents=True, exist_ok=True)
            for name in files:
                if not ignored(f"{relative}/{name}", rules):
                    shutil.copy2(here / name, target / here.relative_to(origin) / name)

    def make_read_only(self, top: Path) -> None:
        """As the image's COPYed files are to USER: root's, not writable by anyone else."""
        for directory, _, files in os.walk(top):
            for name in files:
                (Path(directory) / name).chmod(0o444)
            Path(directory).chmod(0o555)

    def writable_dir(self, image_path: str, runner: Runner, mode: int = 0o755) -> Path:
        path = self.inside(image_path)
        path.mkdir(parents=True, exist_ok=True)
        if os.geteuid() == 0:
            os.chown(path, runner.uid, runner.gid)
        path.chmod(mode)
        return path

    def remove(self) -> None:
        for directory, _, _ in os.walk(self.root):
            Path(directory).chmod(stat.S_IRWXU)
        shutil.rmtree(self.root, ignore_errors=True)


def choose_runner(sandbox: Sandbox, env: dict[str, str]) -> Runner:
    """As root: `nobody`, with Popen's user/group if it can run this python; if the
    interpreter lives where `nobody` cannot read (e.g. under /root/.pyenv), `nobody` with
    one capability, CAP_DAC_READ_SEARCH (read any file; write nothing more than `nobody`
    may), via util-linux's setpriv. Not root: the current user."""
    if os.geteuid() != 0:
        return Runner(os.getuid(), os.getgid(), [], {}, f"the current user (uid {os.getuid()})")
    nobody = pwd.getpwnam("nobody")
    plain = Runner(
        nobody.pw_uid,
        nobody.pw_gid,
        [],
        {"user": nobody.pw_uid, "group": nobody.pw_gid, "extra_groups": []},
        "nobody",
    )
    try:
        probe = plain.run(
            [sys.executable, "-c", "import server, uvicorn, numba"],
            cwd=sandbox.inside(sandbox.image.workdir),
            env=env,
            capture_output=True,
            timeout=60,
        )
        if probe.returncode == 0:
            return plain
    except PermissionError:
        pass  # the interpreter itself is out of reach
    setpriv = shutil.which("setpriv")
    assert setpriv, (
        "running as root, and `nobody` cannot read this python: setpriv "
        "(util-linux) is needed to run the server as nobody"
    )
    return Runner(
        nobody.pw_uid,
        nobody.pw_gid,
        [
            setpriv,
            f"--reuid={nobody.pw_uid}",
            f"--regid={nobody.pw_gid}",
            "--clear-groups",
            "--inh-caps=+dac_read_search",
            "--ambient-caps=+dac_read_search",
            "--",
        ],
        {},
        "nobody (+CAP_DAC_READ_SEARCH, to read this python)",
    )


def http(method: str, url: str, body: dict | None = None) -> tuple[int, bytes]:
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(
        url, data=data, method=method, headers={"Content-Type": "application/json"}
    )
    try:
        with urllib.request.urlopen(request, timeout=5) as response:
            return response.status, response.read()
    except urllib.error.HTTPError as error:
        return error.code, error.read()


def swap_option(argv: list[str], option: str, value: str) -> list[str]:
    assert option in argv, f"the CMD has no {option}: {argv}"
    i = argv.index(option)
    return [*argv[: i + 1], value, *argv[i + 2 :]]


@pytest.fixture
def image() -> Image:
    return parse_dockerfile(REPO / "Dockerfile")


@pytest.fixture
def sandbox(image: Image) -> Iterator[Sandbox]:
    box = Sandbox(image)
    try:
        yield box
    finally:
        box.remove()


# --- the tests ----------------------------------------------------------------------------


def test_dockerfile_layout(image: Image) -> None:
    """What the image must get right and no test of the running server would show."""
    steps = image.steps
    first_install = next(i for i, (k, a) in enumerate(steps) if k == "RUN" and "pip install" in a)
    copied_before = [s for k, a in steps[:first_install] if k == "COPY" for s in shlex.split(a)]
    assert "server" not in copied_before, "dependencies are installed before the code is copied"
    installs_project = re.compile(r"pip install .*\s\.(\s|$)")
    project_install = [a for k, a in steps if k == "RUN" and installs_project.search(a)]
    assert project_install and all("--no-deps" in a for a in project_install)
    assert all("bench" not in s for sources, _ in image.copies for s in sources)
    assert ignored("bench", dockerignore_rules(REPO / ".dockerignore"))

    assert image.user not in ("", "root", "0")
    db_dir = str(PurePosixPath(image.env["POOL_DB_PATH"]).parent)
    assert db_dir in image.volumes, "the database lives on a volume"
    volume_at = next(i for i, (k, a) in enumerate(steps) if k == "VOLUME" and db_dir in a)
    chown = re.compile(rf"chown\s+(-\S+\s+)*{re.escape(image.user)}(:\S+)?\s+.*{re.escape(db_dir)}")
    assert any(k == "RUN" and chown.search(a) for k, a in steps[:volume_at]), (
        "the volume is made and given to USER before VOLUME (later changes are discarded)"
    )

    # the build's warm-up imports what the server's start runs (the RUN cannot run here)
    warm = [re.search(r"from ([\w.]+) import warm_up", a) for k, a in steps if k == "RUN"]
    modules = [m.group(1) for m in warm if m]
    assert modules, "the numba kernels are compiled at build time"
    for module in modules:
        assert hasattr(importlib.import_module(module), "warm_up")


def test_image_command_serves_as_non_root_user(image: Image, sandbox: Sandbox) -> None:
    sandbox.copy_context()
    app = sandbox.inside(image.workdir)
    assert (app / "server" / "__main__.py").is_file()
    assert not (app / "bench").exists()
    web = Path(sandbox.map_env(image.env["POOL_WEB_DIR"]))
    assert (web / "index.html").is_file()
    assert not (web / "tests").exists()

    db_path = Path(sandbox.map_env(image.env["POOL_DB_PATH"]))
    home = f"/home/{image.user}"  # useradd --create-home
    env = {
        # the base image's: python on PATH (this virtualenv's), a UTF-8 locale, USER's home
        "PATH": f"{Path(sys.executable).parent}:/usr/local/bin:/usr/bin:/bin",
        "LANG": "C.UTF-8",
        "HOME": str(sandbox.inside(home)),
        **{key: sandbox.map_env(value) for key, value in image.env.items()},
    }

    sandbox.make_read_only(app)
    runner = choose_runner(sandbox, env)
    for volume in image.volumes:
        sandbox.writable_dir(volume, runner)
    sandbox.writable_dir(home, runner)
    sandbox.writable_dir("/tmp", runner, mode=0o1777)  # NUMBA_CACHE_DIR: compiled here
    assert db_path.parent.is_dir()

    # the working directory is read-only to the server's user, as /app is to USER
    probe = runner.run(
        [sys.executable, "-c", "open('probe', 'x')"],
        cwd=app,
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert probe.returncode != 0 and "PermissionError" in probe.stderr, (
        f"{runner.description} can write {app}: {probe.stdout}{probe.stderr}"
    )

    port = free_port()
    cmd = swap_option(swap_option(image.cmd, "--host", "127.0.0.1"), "--port", str(port))
    assert cmd[0] == "python", cmd
    log_path = sandbox.root / "server.log"
    base = f"http://127.0.0.1:{port}"
    with open(log_path, "wb") as log:
        process = runner.start(
            [sys.executable, *cmd[1:]], cwd=app, env=env, stdout=log, stderr=subprocess.STDOUT
        )

    def output() -> str:
        log = log_path.read_text(errors="replace")[-6000:]
        return f"\n--- server ({runner.description}) ---\n{log}"

    try:
        deadline = time.monotonic() + STARTUP_TIMEOUT
        while True:
            assert process.poll() is None, f"the server exited ({process.returncode})" + output()
            try:
                status, _ = http("GET", f"{base}/health")
                if status == 200:
                    break
            except OSError:
                pass
            assert time.monotonic() < deadline, "no /health within the timeout" + output()
            time.sleep(0.25)

        status, body = http("POST", f"{base}/api/rooms", {"game": "eight_ball"})
        assert status == 201, body.decode(errors="replace") + output()
        room_id = json.loads(body)["room_id"]
        status, body = http("GET", f"{base}/")
        assert status == 200 and b"<html" in body.lower(), "the web client from POOL_WEB_DIR"

        # the image's HEALTHCHECK, pointed at this port, as the image's user
        image_port = image.cmd[image.cmd.index("--port") + 1]
        check = image.healthcheck[-1]
        assert f":{image_port}/" in check, "the HEALTHCHECK asks the port the CMD listens on"
        healthcheck = [*image.healthcheck[:-1], check.replace(f":{image_port}/", f":{port}/")]
        result = runner.run(
            healthcheck, cwd=app, env=env, capture_output=True, text=True, timeout=30
        )
        assert result.returncode == 0, result.stdout + result.stderr

        process.send_signal(signal.SIGTERM)
        try:
            code = process.wait(STOP_TIMEOUT)
        except subprocess.TimeoutExpired:
            pytest.fail("the server did not stop on SIGTERM" + output())
        # uvicorn shuts down, then re-raises the signal it caught: -SIGTERM (docker: 143)
        assert code in (0, -signal.SIGTERM), f"exit {code}" + output()
        text = log_path.read_text(errors="replace")
        assert "Application shutdown complete" in text and "Traceback" not in text, output()
    finally:
        if process.poll() is None:
            process.kill()
            process.wait(10)

    # the database is on the volume, written by the server's user, with the room in it
    assert db_path.is_file(), f"no database at {db_path}: " + str(list(db_path.parent.iterdir()))
    assert db_path.stat().st_uid == runner.uid
    assert not [p.name for p in app.iterdir() if ".db" in p.name]
    with sqlite3.connect(f"file:{db_path}?mode=ro", uri=True) as db:
        rooms = [row[0] for row in db.execute("SELECT room_id FROM rooms")]
    assert room_id in rooms
