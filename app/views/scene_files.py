"""What a user takes away from a scene: "Download data", the figure as drawn (SVG, PNG) and a
notebook of the view, plus the view's URL query (what a link to it carries).

:class:`SceneFiles` is mixed into :class:`.scene.Scene` and uses only its public surface (key,
title, caption, state, status, last_info, python_code, download_data, figure_models,
notebook_plot) and its parameter stamp.  Kept apart from the render machinery: nothing here
computes; a file is built from the last render, and a failure becomes a one-line text file.
"""

from __future__ import annotations

import io
import logging
import urllib.parse

import panel as pn

import fpucore
from fpucore.errors import ParameterError

from ..data_dir import hide_server_paths
from ..state import URL_PARAMS
from ..url_state import url_query
from . import export
from .report import SceneMessage
from .untrusted import md_code_block, md_plain

log = logging.getLogger("fpu-explorer")


class SceneFiles:
    """The scene's download buttons and the files behind them (a mixin of Scene)."""

    def _make_file_widgets(self) -> None:
        """The "Download data" button; "Figure SVG/PNG" and "Notebook" if the scene draws."""
        self.download = pn.widgets.FileDownload(
            callback=self._download,
            filename=f"{self.key}.csv",
            label="Download data",
            color="light",
            css_classes=["scene-download"],
        )
        # the scene as drawn (its last render, nothing recomputed) and a notebook of its code
        self.exporters = []
        if self.exports:
            self.fig_svg, self.fig_png, self.notebook = (
                pn.widgets.FileDownload(
                    callback=lambda kind=kind: self._export(kind),
                    filename=f"{self.key}.{ext}",
                    label=label,
                    color="light",
                    css_classes=[f"scene-export-{kind}"],
                )
                for kind, ext, label in (
                    ("svg", "svg", "Figure SVG"),
                    ("png", "png", "Figure PNG"),
                    ("notebook", "ipynb", "Notebook"),
                )
            )
            self.exporters = [self.fig_svg, self.fig_png, self.notebook]

    def _download(self):
        try:
            name, buf = self.download_data()
        except (SceneMessage, ParameterError) as exc:
            said = "".join(f"# {line}\n" for line in str(exc).splitlines())
            buf, name = io.StringIO(said), f"{self.key}-unavailable.txt"
        self.download.filename = name
        return buf

    # ------------------------------------------------------------------ export
    def figure_models(self) -> list:
        """The Bokeh models the scene draws (BokehScene: its figures); [] for none."""
        return []

    def notebook_plot(self) -> str:
        """The notebook's last cell: Matplotlib code drawing what the code cells computed."""
        return ""

    def url_query(self) -> str:
        """The state as the URL's query string (what a link to this view carries)."""
        q = url_query(self.state) | {"tab": self.key}
        # percent-encoded as a link carries it (a notebook shows it: no "$", "\\" or "`" of a
        # store's name or a law reaches Markdown)
        return urllib.parse.urlencode([(name, q[name]) for name in URL_PARAMS if name in q])

    def export_figure(self, fmt: str) -> bytes:
        """The scene's figures as drawn (the models of the last render), SVG or PNG bytes."""
        if self.last_info is None:
            raise SceneMessage("nothing drawn yet")
        try:
            return export.figure_bytes(
                self.figure_models(), fmt, f"fpu-explorer {self.title}: {self._stamp}"
            )
        except LookupError as exc:
            raise SceneMessage(f"no figure: {exc}") from None

    def export_notebook(self) -> str:
        """A notebook of the current view: the state, the code of "Copy as Python" (one cell
        per computation) and a plot cell (JSON text)."""
        if self.last_info is None:
            raise SceneMessage("nothing shown yet")
        # what the status showed, as plain text in a code block: it repeats user text (a store's
        # name, a law), which Jupyter would otherwise render as Markdown and typeset as math
        shown = md_plain(self.status.object.split("<small>")[0])
        intro = (
            f"{self.caption}\n\nThe fpu-explorer view **{self.title}** with `?{self.url_query()}`"
            f" (fpucore {fpucore.__version__}). On screen when exported:\n\n"
            f"{md_code_block(shown)}\n\n"
            "Run all cells: they compute the same numbers with fpucore and draw them."
        )
        return export.notebook_json(
            f"fpu-explorer: {self.title}", intro, self.python_code(), self.notebook_plot()
        )

    def _export(self, kind: str):
        widget = {"svg": self.fig_svg, "png": self.fig_png, "notebook": self.notebook}[kind]
        try:
            if kind == "notebook":
                buf, name = io.StringIO(self.export_notebook()), f"{self.key}.ipynb"
            else:
                buf, name = io.BytesIO(self.export_figure(kind)), f"{self.key}.{kind}"
        except (SceneMessage, ParameterError) as exc:
            said = "".join(f"# {line}\n" for line in str(exc).splitlines())
            buf, name = io.StringIO(said), f"{self.key}-unavailable.txt"
        except Exception as exc:  # the server keeps serving; the log keeps the traceback
            log.exception("scene %s: export %s failed", self.key, kind)
            text = f"export failed: {type(exc).__name__}: {hide_server_paths(exc)}"
            buf = io.StringIO("".join(f"# {line}\n" for line in text.splitlines()))
            name = f"{self.key}-unavailable.txt"
        widget.filename = name
        return buf
