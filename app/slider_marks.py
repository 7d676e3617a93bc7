"""A named mark under a slider's track: V_SK under the V slider, w* under the w₊ slider.

The mark is its own small HTML pane placed right below the slider, never a change of the slider
model: a change of a slider's label, stylesheet or styles re-renders it in the browser, and a
mark that moves with w₊ would do that on every state change.  Only this pane re-renders when the
mark moves.  (A typed V = 5.2 that ended at 5.200694 was a stale ``value_throttled`` in the
browser, fixed in app/widgets.py, not a snap of the re-rendered slider.)

Geometry (measured in Chromium): a Panel slider with horizontal margin 10 px draws its track
(``.noUi-base``) inside a 1 px border, so a value at fraction x of (start, end) sits at
1 px + x · (width − 2 px) of the slider's box; the pane has the slider's horizontal margins, so
the same expression places the tick.
"""

from __future__ import annotations

import math

import panel as pn

#: the tick's colour (the red of the scenes' critical points)
COLOUR = "#d62728"


def mark_fraction(value: float | None, start: float, end: float) -> float | None:
    """Where ``value`` lies along a slider over (start, end), in [0, 1]; None when it is
    missing, not finite or off the track (no mark is drawn then)."""
    if value is None or not (math.isfinite(value) and math.isfinite(start) and math.isfinite(end)):
        return None
    if not end > start or not start <= value <= end:
        return None
    return (value - start) / (end - start)


class SliderMark:
    """The mark of one slider: ``show(value, start, end)`` after the slider's range is set."""

    def __init__(self, name: str, css_class: str):
        self.name = name
        self.fraction: float | None = None
        self.value: float | None = None
        self.pane = pn.pane.HTML(
            "",
            css_classes=["slider-mark", css_class],
            sizing_mode="stretch_width",
            margin=(0, 10, 2, 10),  # the slider's horizontal margins (see the module docstring)
            height=16,
            visible=False,
        )

    def show(self, value: float | None, start: float, end: float) -> None:
        """Place the mark at ``value`` on a track over (start, end), or hide it when it is off
        the track; the pane is updated only when the mark moves or its value changes (w* keeps
        its place, the middle of the cubic's w₊ range, when the law changes)."""
        x = mark_fraction(value, start, end)
        if x is None:
            self.fraction = self.value = None
            if self.pane.visible:
                self.pane.visible = False
            return
        x = round(x, 6)
        if x == self.fraction and float(value) == self.value and self.pane.visible:
            return
        self.fraction, self.value = x, float(value)
        # the label sits beside the tick, on the side with room for it
        side = "left: 5px" if x < 0.6 else "right: 5px"
        self.pane.param.update(
            object=(
                '<div class="mark-track" style="position: relative; height: 16px; width: 100%;">'
                f'<div class="mark-at" data-fraction="{x:.6f}" style="position: absolute; '
                f'left: calc(1px + (100% - 2px) * {x:.6f}); top: 0; height: 16px; width: 0;">'
                f'<div class="mark-tick" style="position: absolute; left: -1px; top: 0; '
                f'width: 2px; height: 9px; background: {COLOUR};"></div>'
                f'<span class="mark-label" style="position: absolute; {side}; top: 1px; '
                f'font-size: 11px; line-height: 12px; color: {COLOUR}; white-space: nowrap;">'
                f"{self.name} = {value:.6g}</span></div></div>"
            ),
            visible=True,
        )
