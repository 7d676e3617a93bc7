"""Scene "Paper" — the paper's 17 figures (fpucore.paper's registry), each with its caption and
a button that sets the explorer's state (law, mode, w₊, V, N, tab) to the scene that shows it;
the URL follows the state as for any other change.

The full reproduction of each figure with the comparison table is ``fpu paper --out report.html``
(and docs/paper_comparison.md).  Under each figure, its comparison row — the paper's numbers
beside ours with error bar and verdict — is read from fpucore.paper's result cache when a
``fpu paper`` run has computed it for the current fpucore source (nothing is computed here);
otherwise the row says which command fills it.
"""

from __future__ import annotations

import panel as pn

from fpucore.paper import FIGURES, report

from .formatting import fmt_num
from .report import Info
from .scene import Scene
from .untrusted import md_literal

#: w₊ ahead of the superkink V = 5.2 (the paper's example, Figs. Floquet_example, stabSK (b)):
#: qc.superkink_from_V(CubicLaw(-1, 10), 5.2).w_plus — the state sets V = V_SK(w₊) from it
W_PLUS_5_2 = 0.6327161199294542
#: the state that shows each figure: (tab, mode, w_plus, V, N); in superkink mode V follows
#: w_plus (V = V_SK(w_plus), eq. cubic_cond2), so V is None there.  a = −1, b = 10 throughout.
FIGURE_STATE: dict[str, tuple[str, str, float, float | None, int]] = {
    "superkink": ("force", "superkink", 1.0, None, 500),
    "pplane": ("phase", "solitary", 1.0, 5.373838498865699, 500),  # V_SK − 0.001
    "cubic": ("profiles", "superkink", 1.0, None, 500),
    "SWvelocities_cubic": ("diagram", "solitary", 1.0, 5.0, 500),
    "SWs_cubic": ("profiles", "solitary", 1.0, 5.0, 500),
    "SWamp_energy_QCcubic": ("diagram", "solitary", 1.0, 5.0, 500),
    "TWcubic": ("profiles", "superkink", W_PLUS_5_2, None, 500),
    "SWs_cubic_DvsQC": ("profiles", "solitary", 1.0, 5.2, 500),
    "SWamp_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, 500),
    "SWenergy_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, 500),
    "floquet_SK": ("floquet", "superkink", W_PLUS_5_2, None, 500),
    "Floquet_example": ("floquet", "superkink", W_PLUS_5_2, None, 500),
    "stabSK": ("simulation", "superkink", W_PLUS_5_2, None, 500),
    "Riemann1": ("simulation", "superkink", 20.0 / 3.0 - 4.6, None, 500),  # V = 5.7209
    "floquet_cubicSW": ("floquet", "solitary", 1.0, 5.38, 500),
    "stabSW": ("simulation", "solitary", 6.0, 5.2174919476, 500),
    "SWdyn": ("simulation", "solitary", 1.0, 5.2494, 500),
}


class PaperScene(Scene):
    key = "paper"
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
        self.cmp_panes: dict[str, pn.pane.Markdown] = {}
        self._cmp_version, self._cmp_results = None, {}
        for label, fig in FIGURES.items():
            btn = pn.widgets.Button(
                name=f"Show Fig. {fig.number}",
                button_type="primary",
                width=130,
                css_classes=["paper-open", f"paper-open-{label}"],
            )
            btn.on_click(lambda _e, lab=label: self.open(lab))
            self.buttons[label] = btn
            text = f"**Fig. {fig.number}** `{label}` ({fig.section}) — {md_literal(fig.caption)}"
            cmp = pn.pane.Markdown(
                "", sizing_mode="stretch_width", css_classes=[f"paper-cmp-{label}"], margin=(0, 10)
            )
            self.cmp_panes[label] = cmp
            rows.append(pn.Row(btn, pn.Column(pn.pane.Markdown(text), cmp,
                                              sizing_mode="stretch_width")))  # fmt: skip
        return pn.Column(*rows, sizing_mode="stretch_width", css_classes=["paper-list"])

    def comparison_rows(self) -> dict[str, str]:
        """Per figure, its comparisons from fpucore.paper's cache (full size first, else the
        reduced run), or the command that computes them.  A result read once is kept for this
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
            out[label] = comparison_markdown(label, r)
        return out

    def open(self, label: str) -> None:
        """Set the state to the scene of figure ``label`` in three updates: the tab first, alone,
        so that a scene not built yet is built and sent to the browser exactly as on a tab
        click, before any render of it (a render of a scene built in the same update as the
        parameters sent patches for models the browser did not have yet: "reference … isn't
        known"); then the law and mode, so that the state's tie of V to w₊ in superkink mode
        acts on the new mode; then w₊, N and V."""
        tab, mode, w_plus, V, N = FIGURE_STATE[label]
        self.state.tab = tab
        self.state.param.update(a=-1.0, b=10.0, expression="", mode=mode)
        new = {"w_plus": w_plus, "N": N}
        if V is not None:
            new["V"] = V
        self.state.param.update(**new)

    def render(self, info: Info):
        """The list does not change; an invalid current state is named above it (the buttons
        set valid parameters)."""
        rows = self.comparison_rows()
        n = len(self._cmp_results)
        info.shown = f"{len(FIGURES)} figures of the paper; compared with our numbers: {n}"
        if n < len(FIGURES):
            info.notes.append(
                "figures without a comparison row: `fpu paper --out report.html` computes all "
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


def comparison_markdown(label: str, r) -> str:
    """One figure's comparison row: each printed number beside ours ± error and the verdict."""
    if r is None:
        return f"<small>_not compared yet: `fpu paper --figure {label}` computes it_</small>"
    parts = []
    for c in r.comparisons:
        mark = "✓" if c.agrees else "✗"
        parts.append(
            f"{mark} {md_literal(c.quantity)}: paper {md_literal(c.printed)}, ours "
            f"{fmt_num(c.ours, 8)} ± {c.error:.1g}"
        )
    size = " (reduced)" if r.reduced else ""
    head = f"**{r.n_agree}/{len(r.comparisons)} agree**{size}, computed in {r.elapsed_s:.1f} s"
    return "<small>" + head + " · " + " · ".join(parts) + "</small>"
