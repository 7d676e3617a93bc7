"""'Copy as Python': the code box's style and copy script, and the first lines of every scene's
code (the imports and the state's law, built by the same fpucore call as the app's).

Kept apart from the Scene machinery (:mod:`.scene`): the generated code is what a user pastes
and runs, so its preamble, the law's source text and the browser-side copy live together.
"""

from __future__ import annotations

import panel as pn

import fpucore

from ..compute.laws import split_law
from ..state import ExplorerState

#: the code box: monospace, no soft wrap (a long call scrolls instead of breaking)
CODE_CSS = (
    "textarea { font-family: ui-monospace, SFMono-Regular, Menlo, Consolas, monospace; "
    "font-size: 12px; white-space: pre; overflow-wrap: normal; overflow: auto; }"
)

#: "Copy as Python": the Clipboard API where the page has it (https or localhost); else (plain
#: http on another host: navigator.clipboard is undefined) a hidden textarea and the legacy copy
#: command; if that fails too, the code card opens so the user can select the code.  The button
#: says which happened for two seconds.
COPY_JS = """
const say = (text) => {
  btn.label = text;
  setTimeout(() => { btn.label = "Copy as Python"; }, 2000);
};
const legacy = () => {
  const ta = document.createElement("textarea");
  ta.value = code.value;
  ta.setAttribute("readonly", "");
  ta.style.position = "fixed";
  ta.style.opacity = "0";
  document.body.appendChild(ta);
  ta.select();
  let ok = false;
  try { ok = document.execCommand("copy"); } catch (e) { ok = false; }
  document.body.removeChild(ta);
  if (ok) { say("Copied ✓"); } else { card.collapsed = false; say("Select the code below"); }
};
if (navigator.clipboard && window.isSecureContext) {
  navigator.clipboard.writeText(code.value).then(() => say("Copied ✓"), legacy);
} else {
  legacy();
}
"""


def law_source(state: ExplorerState) -> str:
    """The fpucore call that makes the state's law (as in "Copy as Python")."""
    if state.expression:
        expr, consts = split_law(state.expression)
        if consts:
            return f"fpucore.law_from_expression({expr!r}, constants={consts!r})"
        return f"fpucore.law_from_expression({expr!r})"
    return f"CubicLaw(a={float(state.a)!r}, b={float(state.b)!r})"


def python_preamble(state: ExplorerState) -> str:
    """First lines of every scene's "copy as Python" code: the imports and ``law``, built by the
    same fpucore call as the app's (CubicLaw, or fpucore.law_from_expression of the text)."""
    make = f"law = {law_source(state)}\n"
    return (
        f"# reproduces the fpu-explorer view; generated with fpucore {fpucore.__version__}\n"
        "import fpucore\n"
        "from fpucore import atlas, floquet, qc, simulate, wave\n"
        "from fpucore.law import CubicLaw\n\n"
        f"print(fpucore.__version__)  # {fpucore.__version__!r} when generated\n" + make
    )


def code_box() -> tuple[pn.widgets.TextAreaInput, pn.widgets.Button, pn.Card]:
    """A scene's code box (in a collapsed card) and its "Copy as Python" button."""
    code = pn.widgets.TextAreaInput(
        value="",
        height=220,
        sizing_mode="stretch_width",
        css_classes=["scene-code"],
        stylesheets=[CODE_CSS],
    )
    copy_btn = pn.widgets.Button(label="Copy as Python", color="light", css_classes=["scene-copy"])
    card = pn.Card(code, title="Python", collapsed=True, sizing_mode="stretch_width", margin=2)
    copy_btn.js_on_click(args={"code": code, "btn": copy_btn, "card": card}, code=COPY_JS)
    return code, copy_btn, card
