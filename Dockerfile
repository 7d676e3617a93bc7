# fpu-explorer dashboard — Panel's deployment conventions:
# slim Python base, non-root user, writable NUMBA_CACHE_DIR, JIT warmed at build time and again
# (from the cache) at start, EXPOSE 5006, panel serve on 0.0.0.0 with an allowed websocket
# origin, --liveness and a HEALTHCHECK on it.
# The steps are the README's (`make serve`): `pip install -e .[app]`, then the same
# `panel serve` flags as the Makefile's serve target, which the browser tests run
# (tests/test_browser.py checks that the flags agree).
FROM python:3.11-slim

ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    NUMBA_CACHE_DIR=/home/app/.numba_cache \
    BOKEH_ALLOW_WS_ORIGIN=* \
    PORT=5006

RUN useradd --create-home --uid 1000 app
WORKDIR /home/app/fpu-explorer

COPY --chown=app:app pyproject.toml README.md ./
COPY --chown=app:app fpucore ./fpucore
COPY --chown=app:app app ./app
# the Paper tab's thumbnails and committed comparison table (app/views/paper.py)
COPY --chown=app:app docs/figures ./docs/figures
COPY --chown=app:app docs/paper_comparison.json ./docs/
RUN pip install --upgrade pip && pip install -e ".[app]"

USER app
# compile every Numba kernel into NUMBA_CACHE_DIR at build time (cache=True kernels)
RUN mkdir -p "$NUMBA_CACHE_DIR" && fpu warm

EXPOSE 5006
HEALTHCHECK --interval=30s --timeout=5s --start-period=120s --retries=3 \
    CMD python -c "import urllib.request,sys; sys.exit(urllib.request.urlopen('http://127.0.0.1:5006/liveness', timeout=4).status != 200)"

CMD ["panel", "serve", "app/main.py", "--port", "5006", "--address", "0.0.0.0", \
     "--allow-websocket-origin=*", "--liveness", "--num-threads", "2", \
     "--setup", "app/warm.py", "--warm"]
