# The two commands of the README:  `make serve`  and  `make test`.
# Both build the virtual environment first (idempotent): the project with its extras from
# pyproject.toml (ranges), at the exact tested versions of requirements/lock.txt, so they work
# and reproduce on a fresh machine with only Python 3.11, make and (for the browser tests) apt.
PY      ?= python3
VENV    := .venv
BIN     := $(VENV)/bin
STAMP   := $(VENV)/.installed-stamp
LOCK    := requirements/lock.txt
PORT    ?= 5006
export NUMBA_CACHE_DIR ?= $(CURDIR)/.numba_cache

.PHONY: setup browser serve test lint typecheck docs bench workprecision clean

$(STAMP): pyproject.toml $(LOCK)
	$(PY) -m venv $(VENV)
	$(BIN)/pip install -q --upgrade pip
	$(BIN)/pip install -q -c $(LOCK) -e ".[app,test,docs]"
	touch $(STAMP)

setup: $(STAMP)

# Debian's chromium for the Playwright tests (Playwright's own browser download does not work here).
browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  echo "installing Debian chromium (apt)"; \
	  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; }

# Same command as the Dockerfile (which also runs `fpu warm` at build time).  fpu serve is panel
# serve of app/main.py (fpucore/cli/serve.py) with the
# app's warm-up (--setup: the essential Numba kernels compiled or loaded in the server process,
# filling NUMBA_CACHE_DIR; default scenes into the result cache; --warm: one page).  The
# simulation's integrators compile in the background once the server is up.  No separate
# `fpu warm` here: its process start and import cost 3.7 s of a first start, and its parallel
# compile took 2.7x longer than one process (benchmarks/README.md "First start").
serve: setup
	$(BIN)/fpu serve --port $(PORT) --address 0.0.0.0

test: setup browser
	$(BIN)/ruff check fpucore app tests benchmarks
	$(BIN)/mypy
	$(BIN)/python -m pytest -q

lint: setup
	$(BIN)/ruff check fpucore app tests benchmarks && $(BIN)/ruff format --check fpucore app tests benchmarks

# The type checker alone (config: [tool.mypy] in pyproject.toml; cache in .mypy_cache).
typecheck: setup
	$(BIN)/mypy

# The documentation site (Sphinx + MyST, offline): build/docs/html/index.html.  Warnings are errors
# (-W, nitpicky -n): a broken cross-reference, a docstring that does not parse or a gallery figure
# that raises fails the build.  The gallery's 17 figures are computed (full size; FPU_DOCS_REDUCED=1
# for reduced grids) and cached in $FPU_CACHE_DIR (default .fpu_cache) keyed by fpucore's source:
# a rebuild with the same fpucore reads them back.  So are the worked-example pages of the smooth
# preset laws (docs/_ext/law_gallery.py: docs/laws/, a few seconds a law).
docs: setup
	$(BIN)/sphinx-build -W --keep-going -n -q -b html docs build/docs/html -d build/docs/doctrees
	@echo "docs: build/docs/html/index.html"

bench: setup
	$(BIN)/python -m benchmarks.run

workprecision: setup
	$(BIN)/python -m benchmarks.work_precision

clean:
	rm -rf $(VENV) .numba_cache .pytest_cache .mypy_cache build/docs build/docs-test docs/gallery
