# fpu-explorer dashboard — Panel's deployment conventions: slim Python base, non-root user,
# writable NUMBA_CACHE_DIR, JIT warmed at build time and again (from the cache) at start,
# EXPOSE 5006, `fpu serve` (panel serve on 0.0.0.0, any websocket origin, --liveness, the app's
# warm-up) and a HEALTHCHECK on /liveness.  The same command as `make serve`
# (tests/browser/test_harness.py checks that they agree).
#
# Two stages: the first installs the project (not editable) with the `app` extra at the tested
# versions of requirements/lock.txt into /opt/venv; the second copies only that venv — no
# source tree, build tools, pip cache or the packages' own test suites.  The build context is
# limited by .dockerignore (no .venv, caches, stores or .git).
FROM python:3.11-slim AS build

ENV PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1
RUN python -m venv /opt/venv
WORKDIR /src
COPY pyproject.toml setup.py README.md ./
COPY requirements/lock.txt ./requirements/
COPY fpucore ./fpucore
COPY app ./app
# then the biggest packages' own test suites (never run here, none imported at run time) and pip
RUN /opt/venv/bin/pip install -c requirements/lock.txt ".[app]" \
    && cd /opt/venv/lib/python3.11/site-packages \
    && find pandas scipy numpy sympy -depth -type d -name tests -exec rm -rf {} + \
    && /opt/venv/bin/pip uninstall -y pip

FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PATH=/opt/venv/bin:$PATH \
    NUMBA_CACHE_DIR=/home/app/.numba_cache \
    PORT=5006

RUN useradd --create-home --uid 1000 app
COPY --from=build /opt/venv /opt/venv
USER app
WORKDIR /home/app
# compile every Numba kernel into NUMBA_CACHE_DIR at build time (cache=True kernels)
RUN mkdir -p "$NUMBA_CACHE_DIR" && fpu warm

EXPOSE 5006
HEALTHCHECK --interval=30s --timeout=5s --start-period=120s --retries=3 \
    CMD python -c "import urllib.request,sys; sys.exit(urllib.request.urlopen('http://127.0.0.1:5006/liveness', timeout=4).status != 200)"

CMD ["fpu", "serve", "--port", "5006", "--address", "0.0.0.0"]
