"""The user's wait, measured on the page: from the last click or key press to the browser's
first frame after the result arrived ("click → drawn"), split into its parts — queued on the
server (the request waited for the scene's render loop), computed on the server, and the rest:
the input's and the result's transfer and the browser's drawing.

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
requestAnimationFrame(() => requestAnimationFrame(() => {
  probe.value = JSON.stringify({wait_ms: performance.now() - t_in, seq: Math.random()});
}));
"""


class WaitLine:
    """The "Your wait" line of a scene: ``served(queued_s, server_s)`` after each published
    render (the server's parts of the wait; the browser then measures and reports the whole);
    ``line``, ``probe`` and ``token`` go into the scene's layout (the last two hidden)."""

    def __init__(self) -> None:
        self.probe = pn.widgets.TextInput(value="", visible=False, css_classes=["scene-wait-probe"])
        self.token = pn.widgets.TextInput(value="", visible=False, css_classes=["scene-wait-token"])
        self.token.jscallback(args={"probe": self.probe}, value=WAIT_JS)
        self._published = 0
        self.line = LiteralMarkdown("", visible=False, css_classes=["scene-wait"], margin=(0, 10))
        self._parts = (math.nan, math.nan)
        self.probe.param.watch(self._reported, "value")

    def arm(self) -> None:
        """Once the page has loaded: a token change runs the script, which installs the input
        listener (the page's first click is then timed too)."""
        self.token.value = "armed"

    def served(self, queued_s: float, server_s: float) -> None:
        self._parts = (queued_s, server_s)
        self._published += 1
        self.token.value = str(self._published)

    def _reported(self, event) -> None:
        try:
            wait_s = float(json.loads(event.new)["wait_ms"]) / 1000.0
        except (ValueError, TypeError, KeyError):  # not the page's report: ignored
            return
        if not (math.isfinite(wait_s) and 0.0 <= wait_s < 86400.0):
            return
        self.line.param.update(object=wait_markdown(wait_s, *self._parts), visible=True)


def wait_markdown(wait_s: float, queued_s: float, server_s: float) -> str:
    """'**Your wait:** 0.43 s click → drawn (queued 0.01 s · computed 0.30 s · transfer and
    draw 0.12 s)'; the parts the server does not know are left out."""
    parts = []
    if math.isfinite(queued_s) and math.isfinite(server_s):
        rest = max(wait_s - queued_s - server_s, 0.0)
        parts = [
            f"queued {fmt_time(queued_s)}",
            f"computed {fmt_time(server_s)}",
            f"transfer and draw {fmt_time(rest)}",
        ]
    tail = f" ({' · '.join(parts)})" if parts else ""
    return f"**Your wait:** {fmt_time(wait_s)} click → drawn{tail}"
