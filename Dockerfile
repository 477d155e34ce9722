# Pool online: the game server and the static web client, one process (rooms live in it).
# tests/test_container.py reads this file and runs its CMD the way the image would (no
# container engine needed): keep CMD, ENV, USER, WORKDIR and VOLUME in the forms used here.
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    NUMBA_CACHE_DIR=/tmp/numba-cache \
    POOL_WEB_DIR=/app/web \
    POOL_DB_PATH=/data/billiards.db

# The server's user, and the only place it writes: the SQLite database (POOL_DB_PATH) on a
# volume it owns. Made before VOLUME, so a new volume starts with this owner.
RUN useradd --system --create-home --uid 10001 pool \
    && mkdir /data \
    && chown pool:pool /data
VOLUME /data

WORKDIR /app

# Dependencies from pyproject.toml alone (the project's and the build backend's), so a
# code change does not reinstall them.
COPY pyproject.toml ./
RUN python -c "import tomllib; p = tomllib.load(open('pyproject.toml', 'rb')); \
print('\n'.join(p['build-system']['requires'] + p['project']['dependencies']))" \
        > /tmp/requirements.txt \
    && pip install -r /tmp/requirements.txt \
    && rm /tmp/requirements.txt

# The code, then the project itself without dependencies. bench/ is not shipped: setuptools'
# package search simply finds only server/.
COPY README.md ./
COPY server ./server
RUN pip install --no-deps --no-build-isolation . \
    && rm -rf build *.egg-info

# Compile the numba kernels (engine and frame encoder) once at build time, into the shared
# cache, with the warm-up the server runs at start: a container then starts in seconds, not
# after a ~20 s compile. `python -c` here and `python -m server` below both import
# /app/server (the working directory), the source paths the cache is keyed on.
RUN python -c "from server.rooms.prepare import warm_up; warm_up()" \
    && chown -R pool:pool /tmp/numba-cache

# Last: the web client changes most often and needs no compile.
COPY web ./web

USER pool
EXPOSE 8000

HEALTHCHECK --interval=30s --timeout=3s --start-period=30s --retries=3 \
    CMD python -c "import urllib.request, sys; \
sys.exit(0 if urllib.request.urlopen('http://127.0.0.1:8000/health', timeout=2).status == 200 else 1)"

CMD ["python", "-m", "server", "--host", "0.0.0.0", "--port", "8000"]
