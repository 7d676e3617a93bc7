"""A column of sliders kept in the page and re-labelled, never replaced: the law editor's
constant sliders (one per named constant of a smooth law) and coefficient sliders (one per
coefficient of a polynomial).

Adding a widget to a served page makes Bokeh recompute the document's whole model graph when
the change is sent: measured 0.64 s of a 0.93 s smooth-preset change (the tanh preset's four
new constant sliders, on a loaded 2-core machine).  A pool made with the page and reused (label,
CSS class, range and value updated; unused ones hidden) adds no model unless a law has more
constants than any before.
"""

from __future__ import annotations

from collections.abc import Callable

import panel as pn

from .widgets import FloatSlider

#: sliders made with the page (the presets' most named constants: tanh's four)
POOL_SIZE = 4


class SliderPool:
    """``box`` holds the sliders; ``on_move(slider, value)`` is called on a slider's release."""

    def __init__(self, on_move: Callable, css_class: str, size: int = POOL_SIZE):
        self.on_move = on_move
        self.sliders: list[FloatSlider] = []
        self.box = pn.Column(sizing_mode="stretch_width", css_classes=[css_class], visible=False)
        self._grow(size)

    def _grow(self, n: int) -> None:
        new = []
        for _ in range(n - len(self.sliders)):
            sl = FloatSlider(
                label="",
                start=0.0,
                end=1.0,
                step=0.001,
                value=0.0,
                visible=False,
                format="0.0[000]",
                sizing_mode="stretch_width",
                show_value=True,
            )
            sl.param.watch(lambda e, s=sl: self.on_move(s, e.new), "value_throttled")
            new.append(sl)
        if new:
            self.sliders += new
            self.box.objects = list(self.sliders)

    def take(self, labels: list[str], classes: list[str]) -> list[FloatSlider]:
        """The first ``len(labels)`` sliders, labelled and shown (CSS classes ``classes``, one
        each); the others hidden.  The caller sets their ranges and values."""
        self._grow(len(labels))
        for k, sl in enumerate(self.sliders):
            if k < len(labels):
                sl.param.update(label=labels[k], css_classes=[classes[k]], visible=True)
            else:
                sl.visible = False
        return self.sliders[: len(labels)]
