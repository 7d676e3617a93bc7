"""The trilinear law's sliders in the law editor: breakpoints w1 < w2 and moduli E1, E2, E3 of
fpucore.law.TrilinearLaw, shown while the state's law is a trilinear law.

A slider moved rewrites the law text (``trilinear(w1=…, …)``, exact reprs: the state, the URL
and "Copy as Python" carry it) and hands it to the editor, which builds it (parse only: no
worker needed) and applies it, or shows fpucore's refusal (w1 >= w2, E2 <= E1, a negative
modulus …) literally while the previous law stays.
"""

from __future__ import annotations

from collections.abc import Callable

import panel as pn

from .law_presets import TRILINEAR_DEFAULTS, TRILINEAR_RANGES, trilinear_text, trilinear_values
from .widgets import FloatSlider, put, widened


class TrilinearSliders:
    """Five sliders (``sliders[name]``, CSS class ``w-pl-<name>``) in :attr:`box`;
    ``on_text(text)`` receives the law text a moved slider makes."""

    def __init__(self, on_text: Callable[[str], None]):
        self.on_text = on_text
        self.sliders: dict[str, FloatSlider] = {}
        for name, v in TRILINEAR_DEFAULTS.items():
            lo, hi = TRILINEAR_RANGES[name]
            sl = FloatSlider(
                label=name,
                start=lo,
                end=hi,
                step=(hi - lo) / 500,
                value=v,
                css_classes=[f"w-pl-{name}"],
                format="0.0[000]",
                sizing_mode="stretch_width",
                show_value=True,
            )
            sl.param.watch(lambda e, n=name: self.moved(n, e.new), "value_throttled")
            self.sliders[name] = sl
        self.box = pn.Column(
            *self.sliders.values(),
            visible=False,
            sizing_mode="stretch_width",
            css_classes=["law-trilinear"],
        )

    def moved(self, name: str, value) -> None:
        """Slider ``name`` released at ``value``: the law text of all five sliders."""
        if value is None:
            return
        values = {n: float(s.value) for n, s in self.sliders.items()}
        values[name] = float(f"{float(value):.6g}")  # no 0.30000000000000004 from the step
        self.on_text(trilinear_text(values))

    def sync(self, text: str) -> bool:
        """State → sliders: visible with the law's values when ``text`` is a trilinear law
        (ranges widened to include them); returns whether it is."""
        values = trilinear_values(text)
        if values is None:
            self.box.visible = False
            return False
        for name, v in values.items():
            put(self.sliders[name], v, **widened(v, *TRILINEAR_RANGES[name]))
        self.box.visible = True
        return True
