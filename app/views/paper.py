"""Scene "Paper" — the paper's 17 figures (fpucore.paper's registry), each with its thumbnail,
its caption and a button that sets the explorer's state (law, mode, w₊, V, N, tab, held curves;
the Simulation scene's initial data) to the scene that shows it (app.paper_figures); the URL
follows the state as for any other change, and its ``fig`` names the figure.

The full reproduction of each figure with the comparison table is ``fpu paper --out report.html``
(and docs/paper_comparison.md).  The thumbnails are the committed assets/figures/<label>.png
of this package (package data: the wheel serves them too, read through importlib.resources;
written by ``fpu paper`` with the command in ASSETS_COMMAND), embedded in the page
(no request to another host).  Under each figure, its comparison row — the paper's numbers beside
ours with error bar and verdict — is read from fpucore.paper's result cache when a ``fpu paper``
run has computed it for the current fpucore source (nothing is computed here); otherwise it is the
committed row of assets/paper_comparison.json, labelled as such with the fpucore version that
wrote it.
"""

from __future__ import annotations

import functools
import json
from importlib.resources import files

import panel as pn

from fpucore.paper import FIGURES, report
from fpucore.paper.plot import THUMB_WIDTH

from ..paper_figures import FIGURE_STATE, W_PLUS_5_2
from .formatting import comparison_parts
from .report import Info
from .scene import Scene
from .untrusted import LiteralMarkdown, md_literal

# the state each figure sets (FIGURE_STATE), its held curves and simulation: app.paper_figures
__all__ = ["FIGURE_STATE", "W_PLUS_5_2", "PaperScene", "comparison_markdown"]

# the explorer's package (``app`` in a checkout, ``fpu_explorer_app`` installed) holds them
ASSETS = files(__package__.rpartition(".")[0]) / "assets"
FIGURES_DIR = ASSETS / "figures"
DOCS_TABLE = ASSETS / "paper_comparison.json"
#: the command that rewrites them (from a checkout's root)
ASSETS_COMMAND = (
    "fpu paper --table docs/paper_comparison.md --table-json app/assets/paper_comparison.json "
    "--thumbnails app/assets/figures"
)
#: width at which a thumbnail is shown (px; the file is THUMB_WIDTH wide: sharp on HiDPI screens)
SHOWN_WIDTH = THUMB_WIDTH // 2


@functools.cache
def docs_table() -> dict:
    """assets/paper_comparison.json (written with the Markdown table by ``fpu paper --table``);
    {} when absent or unreadable (the rows then name the command)."""
    try:
        doc = json.loads(DOCS_TABLE.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return doc if isinstance(doc, dict) and isinstance(doc.get("figures"), dict) else {}


def thumbnail(label: str):
    """The figure's committed thumbnail, embedded (pn.pane.PNG reads a local file into the
    page), or a line naming the command that writes it."""
    path = FIGURES_DIR / f"{label}.png"
    if path.is_file():
        return pn.pane.PNG(
            path.read_bytes(),
            width=SHOWN_WIDTH,
            css_classes=["paper-thumb", f"paper-thumb-{label}"],
        )
    return LiteralMarkdown(
        "<small>_no thumbnail: `fpu paper --thumbnails app/assets/figures` draws it_</small>",
        width=SHOWN_WIDTH,
    )


#: every scrolled element of the page (light DOM and shadow roots) back to its top
SCROLL_TO_TOP_JS = """
const top = (root) => {
  for (const el of root.querySelectorAll('*')) {
    if (el.scrollTop > 0) { el.scrollTop = 0; }
    if (el.shadowRoot) { top(el.shadowRoot); }
  }
};
top(document);
window.scrollTo(0, 0);
"""


class PaperScene(Scene):
    title = "Paper"
    caption = (
        "_The paper's figures: a button opens the scene that shows the figure with its "
        "parameters. Every figure reproduced, with our numbers beside the printed ones: "
        "`fpu paper --out report.html`; the table: docs/paper_comparison.md._"
    )
    cheap = True
    exports = False  # a list of buttons, no figure

    def make_plot(self):
        rows = []
        self.buttons: dict[str, pn.widgets.Button] = {}
        self.cmp_panes: dict[str, LiteralMarkdown] = {}
        self._cmp_version, self._cmp_results = None, {}
        for label, fig in FIGURES.items():
            btn = pn.widgets.Button(
                name=f"Show Fig. {fig.number}",
                button_type="primary",
                width=130,
                css_classes=["paper-open", f"paper-open-{label}"],
            )
            btn.on_click(lambda _e, lab=label: self.open(lab))
            # the figure's scene opens at its top: the list was scrolled down to this button,
            # and the scrolled page kept that offset over the (shorter) scene — a blank view
            btn.js_on_click(code=SCROLL_TO_TOP_JS)
            self.buttons[label] = btn
            text = f"**Fig. {fig.number}** `{label}` ({fig.section}) — {md_literal(fig.caption)}"
            cmp = LiteralMarkdown(
                "", sizing_mode="stretch_width", css_classes=[f"paper-cmp-{label}"], margin=(0, 10)
            )
            self.cmp_panes[label] = cmp
            rows.append(
                pn.Row(
                    pn.Column(btn, thumbnail(label)),
                    pn.Column(LiteralMarkdown(text), cmp, sizing_mode="stretch_width"),
                )
            )
        return pn.Column(*rows, sizing_mode="stretch_width", css_classes=["paper-list"])

    def comparison_rows(self) -> dict[str, str]:
        """Per figure, its comparisons from fpucore.paper's cache (full size first, else the
        reduced run), else the committed row of docs/ (labelled so), else the command that computes
        them.  A result read once is kept for this
        fpucore source; a missing one is looked for again at every render (a run in another
        terminal fills the cache)."""
        version = report.code_version()
        if self._cmp_version != version:
            self._cmp_version, self._cmp_results = version, {}
        out = {}
        for label in FIGURES:
            r = self._cmp_results.get(label)
            if r is None:
                r = report.load_cached(label, False, version) or report.load_cached(
                    label, True, version
                )
                if r is not None:
                    self._cmp_results[label] = r
            out[label] = comparison_markdown(label, r, docs_table())
        return out

    def open(self, label: str) -> None:
        """Show figure ``label``: the state's tab, law, mode, w₊, V, N, held curves and the
        Simulation scene's initial data (ExplorerState.show_figure, in the steps it explains);
        the URL's ``fig`` names the figure until the state moves off it."""
        self.state.show_figure(label)

    def render(self, info: Info):
        """The list does not change; an invalid current state is named above it (the buttons
        set valid parameters)."""
        rows = self.comparison_rows()
        n = len(self._cmp_results)
        docs = docs_table().get("figures", {})
        n_docs = sum(1 for lab in FIGURES if lab not in self._cmp_results and lab in docs)
        info.shown = (
            f"{len(FIGURES)} figures of the paper; compared with our numbers: {n} computed here "
            f"(fpu paper's cache), {n_docs} from docs/ (fpucore "
            f"{docs_table().get('fpucore_version', '?')})"
        )
        if n < len(FIGURES):
            info.notes.append(
                "to compare with this fpucore source: `fpu paper --out report.html` computes all "
                "(cached; the rows appear at the next render)"
            )
        problem = self.state.problem()
        if problem is not None:
            info.warning = (
                f"The current parameters show no wave: {problem} A figure sets valid ones."
            )
        return rows

    def publish(self, rows) -> None:
        """The comparison rows (the list itself is static)."""
        for label, text in rows.items():
            if self.cmp_panes[label].object != text:
                self.cmp_panes[label].object = text


def comparison_markdown(label: str, r, docs: dict | None = None) -> str:
    """One figure's comparison row: each printed number beside ours ± error and the verdict —
    from a result computed with this fpucore source (``r``), else from the committed docs table
    (``docs``, labelled with the fpucore version that wrote it), else the command."""
    cmd = f"`fpu paper --figure {label}`"
    if r is None:
        row = (docs or {}).get("figures", {}).get(label)
        if not row:
            return f"<small>_not compared yet: {cmd} computes it_</small>"
        comps = row.get("comparisons", [])
        ok = sum(bool(c.get("agrees")) for c in comps)
        size = ", reduced" if row.get("reduced") else ""
        head = (
            f"**{ok}/{len(comps)} agree** (from docs/, fpucore {docs.get('fpucore_version', '?')}"
            f"{size}; {cmd} computes it here)"
        )
        return "<small>" + " · ".join([head, *comparison_parts(comps)]) + "</small>"
    size = " (reduced)" if r.reduced else ""
    head = (
        f"**{r.n_agree}/{len(r.comparisons)} agree**{size}, computed here (fpu paper's cache) in "
        f"{r.elapsed_s:.1f} s"
    )
    return "<small>" + " · ".join([head, *comparison_parts(r.comparisons)]) + "</small>"
