"""The explorer's law presets: fpucore's (fpucore.law.presets: the cubic, the smooth laws) and
the soft–hard–soft trilinear law (fpucore.law.TrilinearLaw, a piecewise-linear law with its own
five sliders), as the one law text each stands for in the state and the URL.

The server's warm-up builds every preset's law in the law worker (:func:`preset_texts`), so a
preset chosen later is applied from the built law at once.
"""

from __future__ import annotations

import math

from fpucore.errors import ParameterError
from fpucore.law.piecewise_text import is_piecewise_text, law_from_piecewise_text
from fpucore.law.presets import PRESETS

from . import compute

#: the trilinear preset's parameters in order, their defaults (fpucore.law.TrilinearLaw's: a
#: soft-hard-soft law with w1 < w2, E2 > E1, E3) and slider ranges
TRILINEAR = "trilinear"
TRILINEAR_DEFAULTS = {"w1": 0.5, "w2": 1.5, "E1": 1.0, "E2": 4.0, "E3": 0.2}
TRILINEAR_RANGES = {
    "w1": (0.05, 3.0),
    "w2": (0.1, 5.0),
    "E1": (0.0, 5.0),
    "E2": (0.1, 10.0),
    "E3": (0.0, 5.0),
}
TRILINEAR_DESCRIPTION = "soft-hard-soft piecewise-linear (breakpoints w1 < w2, moduli E1, E2, E3)"

#: the law editor's help: which laws are accepted
HELP = """\
**f(w) =** an expression in `w`: numbers, `+ - * / **`, parentheses and `exp`, `log`, `sqrt`,
`tanh`, `sinh`, `cosh`, `atan`; powers with integer or rational exponents (of positive
arguments). Named constants go after a `;` as `name=value` pairs, e.g.
`w + b*w**2 - c*w**3*exp(w/d); b=10, c=1, d=50`: each gets a slider. A polynomial is solved
by exact polynomial routes, any other law through a piecewise Chebyshev representation on its
represented interval (its error enters every error bar).

The law must be in the paper's class (§2): f(0) = 0, f′(0) > 0, a convex interval (α, β) around
0 with f′(α) = f′(β) = 0 (α may be −∞) and a single inflection w\\* in it (f″ from + to −).
A law outside it is refused with the reason and where it fails; the previous law stays.

**Piecewise-linear:** `trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)` (soft–hard–soft:
0 < w1 < w2, E2 > E1 ≥ 0, E2 > E3 ≥ 0; the preset gives a slider each) or
`piecewise(breakpoints=[b1, b2, ...], slopes=[s0, s1, ...])`, slopes rising to one hard regime
then falling. Waves, Floquet spectra and simulations refuse them for now (fpucore says why).
"""

#: the chooser's presets: label → preset name ("" while the law is no preset)
PRESET_OPTIONS = {
    "(choose a preset)": "",
    **{f"{n}: {p.description}": n for n, p in PRESETS.items()},
    f"{TRILINEAR}: {TRILINEAR_DESCRIPTION}": TRILINEAR,
}


def trilinear_text(values: dict) -> str:
    """The law text of a trilinear law (fpucore.law.TrilinearLaw.expression's form, exact reprs),
    e.g. ``trilinear(w1=0.5, w2=1.5, E1=1.0, E2=4.0, E3=0.2)``."""
    return "trilinear(" + ", ".join(f"{n}={float(values[n])!r}" for n in TRILINEAR_DEFAULTS) + ")"


def trilinear_values(text: str) -> dict | None:
    """{w1, w2, E1, E2, E3} of a trilinear law text, None for any other text (or one refused:
    the law class's reason is the law's to give, not this parser's)."""
    if not text or not is_piecewise_text(text) or not text.strip().lower().startswith(TRILINEAR):
        return None
    try:
        lw = law_from_piecewise_text(text)
    except ParameterError:
        return None
    out = {n: float(getattr(lw, n, math.nan)) for n in TRILINEAR_DEFAULTS}
    return out if all(math.isfinite(v) for v in out.values()) else None


def preset_text(name: str) -> str:
    """The law text a preset stands for ("" for the paper's cubic: its a, b sliders)."""
    if name == TRILINEAR:
        return trilinear_text(TRILINEAR_DEFAULTS)
    if name == "cubic":
        return ""
    p = PRESETS[name]
    return compute.laws.join_law(p.text, p.constants_dict)


def preset_of(text: str) -> str:
    """The preset whose law (or family, for the trilinear law and the smooth laws' constants)
    the text is, "" for none (the cubic: see the editor, which also compares a and b)."""
    if trilinear_values(text) is not None:
        return TRILINEAR
    try:
        expr, _ = compute.laws.split_law(text) if ";" in text else (text, {})
    except ParameterError:
        return ""
    return next((n for n, p in PRESETS.items() if p.text == expr and n != "cubic"), "")


def preset_texts() -> list[str]:
    """The law texts of every preset but the cubic (built at the server's warm-up)."""
    return [t for t in (preset_text(n) for n in [*PRESETS, TRILINEAR]) if t]
