"""Sphinx configuration of the fpu-explorer documentation site (``make docs``).

Built offline with warnings as errors (``-W -n``): a broken cross-reference, a docstring that does
not parse, or a gallery figure whose computation raises fails the build.  The theme (alabaster)
and every asset are local; no page loads anything from another host (tests/docs/).
"""

import os
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT))  # this checkout's fpucore first
sys.path.insert(0, str(DOCS / "_ext"))

project = "fpu-explorer"
author = "fpu-explorer developers"
copyright = "fpu-explorer developers"  # noqa: A001
release = version = "0.1.0"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "paper_gallery",
    "law_gallery",
]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
root_doc = "index"
exclude_patterns = ["_build", "figures", "*.html", "_ext"]
myst_enable_extensions = ["colon_fence", "deflist"]
myst_heading_anchors = 3
# A page's heading levels are its own (the notes in docs/ skip levels); an ambiguous short name
# in a signature (``w``, ``width``: attributes of several results) links to none of them.
suppress_warnings = ["myst.header", "ref.python"]

# Docstrings carry units, shapes and the paper's equation labels in prose ("name : meaning"
# lines, not NumPy sections: no napoleon, which read those prose lines as types); signatures
# keep their annotations as written.
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_member_order = "bysource"
autodoc_typehints = "signature"
autodoc_preserve_defaults = True
autosummary_generate = False

# Nitpicky: every cross-reference must resolve — except to libraries whose inventories would
# have to be fetched from another host (no intersphinx: the build is offline).
nitpicky = True
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|scipy|numba|xarray|xr|zarr|dask|distributed)(\..*)?"),
    (r"py:.*", r"(holoviews|hv|bokeh|pandas|queue)(\..*)?"),
    (r"py:.*", r"(collections\.abc|typing|types|concurrent\.futures|pathlib|os|multiprocessing)\..*"),
    (r"py:class", r"(NDArray|ArrayLike|Path|Callable|Sequence|Iterable|Iterator|Mapping|Any)"),
    (r"py:class", r"(TypeGuard|Self|IO|Protocol|ClassVar|Literal|NoReturn)"),
    (r"py:class", r"(optional|array|array_like|ndarray|float|int|str|bool|tuple|list|dict)"),
]

html_theme = "alabaster"
html_static_path: list[str] = []
html_title = "fpu-explorer"
html_show_sourcelink = False
html_copy_source = False
# Math in these pages is written in Unicode (w₊, V_SK, √): no MathJax, which would load from a
# CDN.  Should a page ever hold a math node, the build fails (paper_gallery.check_no_remote).
html_theme_options = {"show_powered_by": False, "github_button": False, "github_banner": False}

# The gallery (paper_gallery): each of the 17 figures computed when the docs are built, cached
# in $FPU_CACHE_DIR (default ./.fpu_cache) keyed by fpucore's source hash.
paper_gallery_reduced = os.environ.get("FPU_DOCS_REDUCED", "0") == "1"
paper_gallery_workers = int(os.environ.get("FPU_DOCS_WORKERS", "0")) or None


def setup(app):
    from fpu_docs_refs import escape_bars, resolve_fpucore

    app.connect("autodoc-process-docstring", escape_bars)
    app.connect("missing-reference", resolve_fpucore)
