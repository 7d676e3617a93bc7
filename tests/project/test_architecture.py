"""The package layout is the flow of the paper, and stays clean (checked with the standard
library's ``ast``, nothing imported):

* the import graph of fpucore's and app's modules has no cycles.  An import of ``a.b.c`` runs
  ``a/__init__`` and ``a/b/__init__`` first, so it is an edge to each of those packages too —
  except the importer's own enclosing packages, which are already being imported when it runs;
* the stages (fpucore's subpackages, :data:`STAGES`) form no cycle either: a module of one stage
  that imports another stage makes the whole first stage depend on the second (importing any
  module of it may run the other's ``__init__``), so a stage cycle is an import cycle waiting for
  the right first import;
* ``parallel`` (the execution layer) depends on no stage above ``law``;
* no import inside a function, except the allow-listed optional dependencies and the CLI's
  commands' ``# heavy:`` ones;
* no private name (``_x``) of one module is used by another, in fpucore, app or the tests;
* fpucore never imports a UI package.
"""

from __future__ import annotations

import ast
import functools
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "fpucore"
STAGES = (
    "law",
    "qc",
    "tableaux",
    "wave",
    "floquet",
    "simulate",
    "parallel",
    "atlas",
    "paper",
    "cli",
)
# imports inside functions allowed only to keep a real optional dependency optional
LATE_OK: set[tuple[str, str]] = {
    # distributed's ~1 s import kept out of every `import fpucore` (only the dask backend needs it)
    ("fpucore/parallel/executor.py", "from fpucore.parallel.dask_backend import DaskBackend"),
    # ... and out of every atlas run without a --scheduler (its probe's identity request)
    ("fpucore/parallel/scheduler.py", "from distributed.comm import connect"),
    # SymPy (~0.3 s) only when a law is typed; xarray + zarr (~0.4 s) only when a store is
    # written: not paid by every CLI call, server start and worker pool
    ("fpucore/law/expression.py", "import sympy"),
    (
        "fpucore/law/expression.py",
        "from sympy.parsing.sympy_parser import convert_xor, implicit_multiplication, "
        "parse_expr, standard_transformations",
    ),
    # its exact expansion (mpmath at module level) with SymPy, only when a law is typed
    ("fpucore/law/expression.py", "from fpucore.law.expansion import expand"),
    ("fpucore/atlas/store.py", "import xarray"),
    # smooth laws (typed text): SymPy for the exact derivatives and the expression tree, mpmath
    # for the 30-digit checks of the representation, SciPy's brentq for the convex ends: only
    # when a smooth law is built, not by `import fpucore` nor by polynomial/PL laws
    ("fpucore/law/smooth_parse.py", "import sympy as sp"),
    ("fpucore/law/smooth.py", "import sympy as sp"),
    ("fpucore/law/smooth.py", "from fpucore.law.smooth_eval import UnsupportedNode, derivative"),
    (
        "fpucore/law/smooth.py",
        "from fpucore.law.smooth_eval import UnsupportedNode, diagnose, to_node",
    ),
    ("fpucore/law/smooth_build.py", "import mpmath"),
    ("fpucore/law/chebyshev.py", "import mpmath"),
    ("fpucore/law/smooth_class.py", "import mpmath"),
    ("fpucore/law/smooth_class.py", "from scipy.optimize import brentq"),
    ("fpucore/law/smooth_tree.py", "import mpmath"),
    ("fpucore/atlas/store.py", "import zarr"),
    # the one place fpucore draws (fpu paper, Jupyter): HoloViews / Bokeh only when a figure is
    # plotted, never by `import fpucore` (test_fpucore_is_headless allows exactly these)
    ("fpucore/paper/plot.py", "import holoviews as hv"),
    ("fpucore/paper/plot.py", "from bokeh import models"),
    ("fpucore/paper/plot.py", "from bokeh.embed import file_html"),
    ("fpucore/paper/plot.py", "from bokeh.resources import Resources"),
    # Pillow (a Matplotlib dependency) only when a thumbnail is written (fpu paper --thumbnails)
    ("fpucore/paper/plot.py", "from PIL import Image"),
    # the explorer's law worker imports SymPy before its time budget starts; the server
    # process never imports it (a typed law is built in that worker)
    ("app/compute/laws.py", "import sympy"),
    # nbformat only when a notebook is written (fpu paper --out x.ipynb)
    ("fpucore/paper/notebook.py", "import nbformat"),
    # the explorer's "Download figure / notebook": Matplotlib (~0.4 s) and nbformat (~0.1 s)
    # when a file is built, not at every server start
    ("app/views/export.py", "from matplotlib import rc_context"),
    ("app/views/export.py", "from matplotlib.figure import Figure"),
    ("app/views/export.py", "from matplotlib.colors import ListedColormap"),
    ("app/views/export.py", "import nbformat"),
}
PLOTTING = {key for key in LATE_OK if key[0] == "fpucore/paper/plot.py"}
# the CLI's commands import the scientific stack when they run: `fpu ... --help` stays < 0.3 s
# (tests/cli/test_cli_startup.py checks that NumPy, SciPy and Numba stay out of it); each such
# import says what it loads, ``# heavy: ...`` (the rule: fpucore/cli/__init__.py)
LATE_OK_DIR = "fpucore/cli/"
HEAVY_TAG = "# heavy:"


def _modname(path: Path) -> str:
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _modules(root: Path) -> dict[str, Path]:
    return {_modname(p): p for p in sorted(root.rglob("*.py")) if "__pycache__" not in p.parts}


MODULES = _modules(PKG) | _modules(ROOT / "app")


def _resolve(mod: str, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    pkg = mod.split(".")
    is_pkg = MODULES.get(mod, Path()).name == "__init__.py"
    base = pkg if is_pkg else pkg[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def _imports(mod: str, tree: ast.AST):
    """(target module, imported name or None, node) for every import in the tree."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield a.name, None, node
        elif isinstance(node, ast.ImportFrom):
            base = _resolve(mod, node)
            for a in node.names:
                yield base, a.name, node


def _parents(mod: str) -> list[str]:
    """The packages whose ``__init__`` runs before ``mod``: a.b.c → [a, a.b]."""
    parts = mod.split(".")
    return [".".join(parts[:k]) for k in range(1, len(parts))]


@functools.cache
def _source(path: Path) -> tuple[str, ast.Module]:
    """(text, syntax tree) of one file, read and parsed once per test run."""
    text = path.read_text()
    return text, ast.parse(text)


def _edges() -> dict[str, set[str]]:
    g: dict[str, set[str]] = {m: set() for m in MODULES}
    for mod, path in MODULES.items():
        own = set(_parents(mod))  # already in sys.modules while mod runs
        for base, name, _ in _imports(mod, _source(path)[1]):
            if name and f"{base}.{name}" in MODULES:
                target = f"{base}.{name}"  # from pkg import submodule
            elif base in MODULES:
                target = base
            else:
                continue
            g[mod].add(target)
            g[mod] |= {p for p in _parents(target) if p in MODULES and p not in own and p != mod}
    return g


def _stage(mod: str) -> str | None:
    """The stage of an fpucore module (its subpackage; a top-level module is its own stage)."""
    parts = mod.split(".")
    if parts[0] != "fpucore" or len(parts) == 1:
        return None
    return parts[1]


def _stage_edges(edges: dict[str, set[str]]) -> dict[str, set[str]]:
    g: dict[str, set[str]] = {}
    for mod, targets in edges.items():
        s = _stage(mod)
        if s is None:
            continue
        g.setdefault(s, set())
        for t in targets:
            st = _stage(t)
            if st is not None and st != s:
                g[s].add(st)
    return g


def _first_cycle(g: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(m: str) -> list[str] | None:
        state[m] = 1
        stack.append(m)
        for n in sorted(g.get(m, ())):
            if state.get(n) == 1:
                return stack[stack.index(n) :] + [n]
            if n not in state and (c := visit(n)):
                return c
        stack.pop()
        state[m] = 2
        return None

    for m in sorted(g):
        if m not in state and (c := visit(m)):
            return c
    return None


def test_the_folder_reads_as_the_flow_of_the_paper():
    subpackages = {p.parent.name for p in PKG.glob("*/__init__.py")}
    assert set(STAGES) <= subpackages
    for stage in STAGES:
        doc = ast.get_docstring(ast.parse((PKG / stage / "__init__.py").read_text()))
        assert doc and "→" in doc, f"{stage}/__init__ should state its flow"
    flat = sorted(p.name for p in PKG.glob("*.py"))
    assert flat == [
        "__init__.py",
        "__main__.py",
        "budget.py",
        "errors.py",
        "jit_cache.py",
        "result.py",
        "warm.py",
    ]


@pytest.fixture(scope="module")
def graph() -> dict[str, set[str]]:
    """The module import graph, built once for every test of this file (one build parses every
    file of fpucore and app: the cost of this file)."""
    return _edges()


@pytest.fixture(scope="module")
def stages(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    """The stage graph, from the one module graph."""
    return _stage_edges(graph)


def test_import_graph_has_no_cycles(graph):
    cycle = _first_cycle(graph)
    assert cycle is None, "import cycle: " + " -> ".join(cycle or [])


def test_an_import_runs_its_parent_packages(graph):
    """The graph has the edges Python takes: atlas/point.py's ``from fpucore.floquet.multipliers
    import spectrum`` runs ``fpucore/floquet/__init__`` first; its own package is no edge."""
    g = graph["fpucore.atlas.point"]
    assert {"fpucore.floquet.multipliers", "fpucore.floquet"} <= g
    assert "fpucore.atlas" not in g and "fpucore" not in g


def test_stages_form_no_cycle(stages):
    assert set(STAGES) <= set(stages), sorted(stages)
    cycle = _first_cycle(stages)
    assert cycle is None, "stage cycle: " + " -> ".join(cycle or [])


def test_the_execution_layer_sits_on_the_force_law_only(stages):
    """parallel/ runs any job; it knows no wave, spectrum or atlas (test support lives in
    tests/, not in the stage)."""
    allowed = {"law", "errors", "budget", "result", "jit_cache"}
    assert stages["parallel"] <= allowed, stages["parallel"]


def test_common_modules_import_nothing_back(graph):
    g = graph
    assert not g["fpucore.errors"], g["fpucore.errors"]
    assert not g["fpucore.jit_cache"], g["fpucore.jit_cache"]
    assert g["fpucore.result"] <= {"fpucore.errors"}, g["fpucore.result"]


def test_budget_imports_only_errors(graph):
    """fpucore.budget is shared by every stage: it may import fpucore.errors and nothing else."""
    assert graph["fpucore.budget"] <= {"fpucore.errors"}


def _files(*roots: str) -> list[Path]:
    out: list[Path] = []
    for r in roots:
        out += [p for p in sorted((ROOT / r).rglob("*.py")) if "__pycache__" not in p.parts]
    return out


def test_no_imports_inside_functions():
    bad = []
    for path in _files("fpucore", "app"):
        text, tree = _source(path)
        lines = text.splitlines()
        for fn in ast.walk(tree):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    key = (path.relative_to(ROOT).as_posix(), ast.unparse(node))
                    tagged = HEAVY_TAG in lines[node.end_lineno - 1]
                    if key not in LATE_OK and not (key[0].startswith(LATE_OK_DIR) and tagged):
                        bad.append(f"{key[0]}:{node.lineno}: {key[1]}")
    assert not bad, "imports inside functions:\n" + "\n".join(bad)


def test_no_private_name_crosses_a_module():
    bad = []
    for path in _files("fpucore", "app", "tests", "benchmarks"):
        mod = _modname(path)
        tree = _source(path)[1]
        aliases: set[str] = set()
        for base, name, node in _imports(mod, tree):
            target = base if name is None else f"{base}.{name}"
            if not (target.startswith(("fpucore", "app")) or base.startswith(("fpucore", "app"))):
                continue
            if name and name.startswith("_") and not name.startswith("__"):
                bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: imports {base}.{name}")
            if name is None or target in MODULES or (ROOT / target.replace(".", "/")).exists():
                for a in node.names:
                    aliases.add(a.asname or a.name.split(".")[0])
        for node in ast.walk(tree):
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.value.id in aliases
                and node.attr.startswith("_")
                and not node.attr.startswith("__")
            ):
                bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.value.id}.{node.attr}")
    assert not bad, "private names used across modules:\n" + "\n".join(bad)


def test_fpucore_is_headless():
    """No UI package in fpucore, except the lazy imports inside fpucore/paper/plot.py's ui()."""
    ui = ("panel", "holoviews", "bokeh", "hvplot", "matplotlib")
    for path in _files("fpucore"):
        rel = path.relative_to(ROOT).as_posix()
        for base, _, node in _imports(_modname(path), _source(path)[1]):
            if (rel, ast.unparse(node)) in PLOTTING:
                continue
            assert base.split(".")[0] not in ui, f"{path}:{node.lineno} imports {base}"


def test_import_fpucore_and_its_cli_load_no_ui_package():
    """The lazy plotting imports stay lazy: `import fpucore` and the CLI's parser (with the
    paper command) load neither HoloViews nor Bokeh (fresh interpreter)."""
    code = (
        "import sys, fpucore, fpucore.paper, fpucore.cli.dispatch as d; d.build_parser(); "
        "ui = ('holoviews', 'bokeh', 'panel', 'matplotlib'); "
        "print(sorted(m for m in ui if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                         cwd=ROOT)  # fmt: skip
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"
