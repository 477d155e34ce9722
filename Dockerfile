# Pool online: the game server and the static web client, one process (rooms live in it).
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    NUMBA_CACHE_DIR=/tmp/numba-cache \
    POOL_WEB_DIR=/app/web

WORKDIR /app

# Dependencies first, so code changes do not reinstall them.
COPY pyproject.toml README.md ./
COPY server ./server
COPY bench ./bench
RUN pip install . \
    && useradd --system --create-home --uid 10001 pool

COPY web ./web

# Compile the engine's numba kernels once at build time (as root, into the shared cache),
# so the first shot does not pause for ~15 s.
RUN python -c "from server.engine import Table, rack, simulate, Shot; \
t = Table.pool('9ft'); simulate(t, rack('eight_ball', t, seed=0), Shot(0.0, 9.0))" \
    && chown -R pool /tmp/numba-cache

USER pool
EXPOSE 8000

HEALTHCHECK --interval=30s --timeout=3s --start-period=30s --retries=3 \
    CMD python -c "import urllib.request, sys; \
sys.exit(0 if urllib.request.urlopen('http://127.0.0.1:8000/health', timeout=2).status == 200 else 1)"

CMD ["python", "-m", "server", "--host", "0.0.0.0", "--port", "8000"]
