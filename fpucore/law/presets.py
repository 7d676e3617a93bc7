"""Preset force laws (text + named constants) for the explorer's law chooser, the CLI and the
tests: the paper's cubic (eq. cubic, a = −1, b = 10), a quartic, an exponential tissue-like law,
a tanh law and a rational law.  Each is in the hardening–softening class with α < 0 < w* < β
(checked by tests/law/test_smooth_presets.py); :func:`preset_law` builds one.

* ``exponential``: f = w + b w² − c w³ e^{w/d} — collagen-like stiffening (b w²) cut off by an
  exponential damage term; b = 10, c = 1, d = 50 give α ≈ −0.0496, w* ≈ 2.964, β ≈ 5.770.
* ``tanh``: f = w + k (tanh((w − m)/s) + tanh(m/s)) − c w³ — fibres recruited around w = m over a
  width s (a smooth step of the stiffness), then cubic softening; k = 1, m = 1, s = 0.3, c = 0.1.
* ``rational``: f = w (1 + b w)/(1 + c w²) — hardening by b w, saturation at f → b/c;
  b = 1, c = 0.1.
"""

from __future__ import annotations

from dataclasses import dataclass

from fpucore.errors import ParameterError
from fpucore.law.cubic import CubicLaw
from fpucore.law.expression import law_from_expression


@dataclass(frozen=True)
class Preset:
    """A named law: its ``text``, ``constants`` {name: value} and a one-line ``description``."""

    name: str
    text: str
    constants: tuple
    description: str

    @property
    def constants_dict(self) -> dict:
        return dict(self.constants)


PRESETS = {
    p.name: p
    for p in (
        Preset(
            "cubic",
            "a*w**3 + b*w**2 + w",
            (("a", -1.0), ("b", 10.0)),
            "the paper's cubic (eq. cubic), closed forms",
        ),
        Preset(
            "quartic",
            "w + b*w**2 + a*w**3 + e*w**4",
            (("a", -1.0), ("b", 10.0), ("e", -0.01)),
            "a quartic polynomial",
        ),
        Preset(
            "exponential",
            "w + b*w**2 - c*w**3*exp(w/d)",
            (("b", 10.0), ("c", 1.0), ("d", 50.0)),
            "tissue-like: stiffening b w^2 cut off by an exponential damage term",
        ),
        Preset(
            "tanh",
            "w + k*(tanh((w - m)/s) + tanh(m/s)) - c*w**3",
            (("c", 0.1), ("k", 1.0), ("m", 1.0), ("s", 0.3)),
            "fibres recruited around w = m over a width s, then cubic softening",
        ),
        Preset(
            "rational",
            "w*(1 + b*w)/(1 + c*w**2)",
            (("b", 1.0), ("c", 0.1)),
            "rational: hardening b w, saturation f -> b/c",
        ),
    )
}


def preset_law(name: str, **constants):
    """The preset's law (``CubicLaw`` for "cubic", closed forms), constants overridden by
    keyword, e.g. ``preset_law("exponential", d=40)``."""
    if name not in PRESETS:
        raise ParameterError("preset", name, " | ".join(PRESETS))
    p = PRESETS[name]
    values = {**p.constants_dict, **constants}
    if name == "cubic" and set(values) == {"a", "b"}:
        return CubicLaw(values["a"], values["b"])
    return law_from_expression(p.text, values)
