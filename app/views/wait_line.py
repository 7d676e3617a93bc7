"""The user's wait, measured on the page: from the last click or key press to the browser's
first frame after the result arrived ("click → drawn"), split into its parts — the server's
(from the first request the input caused to the published result: the render loop's queue,
renders superseded on the way, the final render) with the final render's own share, and the
rest: the input's way to the server, page updates (a tab built on the click), the transfer of
the result and the browser's drawing.

The server knows only its own share (the Time line's "server" figure was read as the wait:
1.4–1.9 s for runs that took 9–29 s from click to plot).  So the browser measures: a
``jscallback`` on the status pane (BokehJS runs it when the status text changes) notes the time
of the page's last pointer or key input (a capture listener on the document, installed by the
first call), waits two animation frames (the plot's data arrived before the status text and is
painted by then) and reports the interval through a hidden text box.  BokehJS runs it when the
server changes a hidden token after publishing a render (after the status text and the plot's
data, in the order the browser applies them; a ``jscallback`` on the Markdown status itself is
attached by Panel to a property its model does not have).  The server turns it into
the line under the status; the browser never writes page text itself.
"""

from __future__ import annotations

import json
import logging
import math

import panel as pn

from .formatting import fmt_time
from .untrusted import LiteralMarkdown

log = logging.getLogger("fpu-explorer")

#: runs in the browser on each change of the token (a render was published; ``probe``: the
#: hidden box that reports back).  Only an input not yet reported counts.
WAIT_JS = """
const w = window;
if (!w.__fpuInput) {
  w.__fpuInput = {t: null};
  for (const ev of ["pointerdown", "keydown"]) {
    document.addEventListener(ev, () => { w.__fpuInput.t = performance.now(); }, true);
  }
}
const t_in = w.__fpuInput.t;
if (t_in === null) { return; }
w.__fpuInput.t = null;
const served = cb_obj.value;  // the server's parts of this very render, echoed back
requestAnimationFrame(() => requestAnimationFrame(() => {
  probe.value = JSON.stringify({wait_ms: performance.now() - t_in, served: served});
}));
"""


class WaitLine:
    """The "Your wait" line of a scene: ``served(server_s, render_s)`` after each published
    render (the server's parts of the wait; the browser then measures and reports the whole);
    ``line``, ``probe`` and ``token`` go into the scene's layout (the last two hidden)."""

    def __init__(self) -> None:
        self.probe = pn.widgets.TextInput(value="", visible=False, css_classes=["scene-wait-probe"])
        self.token = pn.widgets.TextInput(value="", visible=False, css_classes=["scene-wait-token"])
        self.token.jscallback(args={"probe": self.probe}, value=WAIT_JS)
        self._published = 0
        self.line = LiteralMarkdown("", visible=False, css_classes=["scene-wait"], margin=(0, 10))
        self.probe.param.watch(self._reported, "value")

    def arm(self) -> None:
        """Once the page has loaded: a token change runs the script, which installs the input
        listener (the page's first click is then timed too)."""
        self.token.value = json.dumps({"n": 0})

    def served(self, server_s: float, render_s: float) -> None:
        """``server_s``: first unanswered request → published; ``render_s``: the last render."""
        self._published += 1  # (a new value each time: the browser runs the script on change)
        self.token.value = json.dumps(
            {"n": self._published, "server_s": server_s, "render_s": render_s}
        )

    def _reported(self, event) -> None:
        try:
            report = json.loads(event.new)
            wait_s = float(report["wait_ms"]) / 1000.0
            served = json.loads(report["served"])
            parts = (float(served["server_s"]), float(served["render_s"]))
        except (ValueError, TypeError, KeyError):  # not the page's report: ignored
            return
        if not (math.isfinite(wait_s) and 0.0 <= wait_s < 86400.0):
            return
        self.line.param.update(object=wait_markdown(wait_s, *parts), visible=True)


def wait_markdown(wait_s: float, server_s: float, render_s: float) -> str:
    """'**Your wait:** 0.43 s click → drawn (server 0.31 s, of which the last render 0.30 s ·
    the rest 0.12 s: input, page updates, transfer, drawing)'; the parts the server does not
    know are left out."""
    parts = []
    if math.isfinite(server_s) and math.isfinite(render_s):
        rest = max(wait_s - server_s, 0.0)
        parts = [
            f"server {fmt_time(server_s)}, of which the last render {fmt_time(render_s)}",
            f"the rest {fmt_time(rest)}: input, page updates, transfer, drawing",
        ]
    tail = f" ({' · '.join(parts)})" if parts else ""
    return f"**Your wait:** {fmt_time(wait_s)} click → drawn{tail}"
