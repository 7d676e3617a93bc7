"""Explicit compact discrete solitary waves of a PL law with a zero-modulus regime (the
degenerate case of the trilinear family, E₁ = 0 or E₃ = 0; arXiv 2406.06437, abstract), derived
from the discrete traveling-wave equation (paper eq. TW_discrete)

    V² w″(ξ) = f(w(ξ+1)) − 2 f(w(ξ)) + f(w(ξ−1)).

**Setting.**  Z is the zero-modulus regime (f ≡ f_Z there), b its breakpoint with the adjacent
regime of modulus E and width h (the hard regime [w₁, w₂] of a trilinear law: b = w₁ for
E₁ = 0, b = w₂ for E₃ = 0).  The background w_B lies inside Z, δ = b − w_B ≠ 0 (δ > 0: a
tensile wave for E₁ = 0; δ < 0: compressive for E₃ = 0).

**Integral form.**  With F(ξ) = f(w(ξ)) − f_Z, compactly supported, and the tent
Λ(ξ) = max(0, 1 − |ξ|) (Λ″ = δ(ξ+1) − 2δ(ξ) + δ(ξ−1)), TW_discrete with w → w_B at ±∞ is

    V² (w − w_B) = Λ ∗ F.                                                             (1)

**Ansatz.**  The wave leaves Z on one interval (−a, a) only, with 2a < 1: there ξ ± 1 lie in
Z, so (TW_discrete) V² w″ = −2F = −2E (w − b):

    w = b + C cos(ωξ),  ω = √(2E)/V,  a = π/(2ω)  (w = b at ±a).

Inserting F = E C cos(ωη) on (−a, a) into (1): for |ξ| < a, Λ(ξ − η) = 1 − |ξ − η| and
∫ cos(ωη) dη = 2/ω, ∫ |ξ − η| cos(ωη) dη = 2a/ω − (2/ω²) cos(ωξ) (its ξ″ is 2 cos ωξ, even,
= 2a/ω at ξ = a), so (1) reads w = w_B + (E C/V²)(2/ω)(1 − a) + C cos(ωξ) (2E/(V²ω²) = 1):
consistent iff

    C = δ / (ω (1 − a)).

Outside (1) gives, with ζ = |ξ| − 1,

    w = w_B + ωC (1 − |ξ|)                     for a ≤ |ξ| ≤ 1 − a  (linear),
    w = w_B + (C/2) (ω(a − ζ) − cos ωζ)          for |ζ| ≤ a,
    w = w_B                                     for |ξ| ≥ 1 + a,

which stays in Z (monotone from b at |ξ| = a to w_B at |ξ| = 1 + a): so F = 0 there, as assumed.
Conditions: 2a < 1 ⇔ ω > π, and the crest stays in the adjacent regime, |C| ≤ h ⇔
ω ≥ π/2 + |δ|/h; together

    0 < V < V_max = √(2E) / max(π, π/2 + |δ|/h)   ("slow velocities").

Then amplitude |C| = |δ|/(ω − π/2) → 0, core width 2a = πV/√(2E) → 0 and support
[−1 − a, 1 + a] → [−1, 1] as V → 0: compact structures on a constant background that localize
at the lattice scale.  Mass ∫(w − w_B) dξ = (1/V²)∫F = ωC = δ/(1 − a).  The crossing of b at
ξ = ±a is transversal (w′ = ∓Cω).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from fpucore.errors import ParameterError, fmt_interval, require_finite
from fpucore.law.base import HardeningSofteningLaw
from fpucore.result import Result, status_of


def zero_modulus_side(law) -> tuple[int, float, float, float]:
    """(side, b, E, h): side −1 for a zero first regime (b = b₁), +1 for a zero last regime;
    E, h the modulus and width of the adjacent regime.  ParameterError if the law has none."""
    if not hasattr(law, "breakpoints"):
        raise ParameterError("law", type(law).__name__, "a piecewise-linear law")
    b, s = law._b, law._s
    if s[0] == 0.0:
        return -1, float(b[0]), float(s[1]), float(b[1] - b[0])
    if s[-1] == 0.0:
        return 1, float(b[-1]), float(s[-2]), float(b[-1] - b[-2])
    raise ParameterError(
        "law", law.expression, "a law with a zero-modulus first or last regime (E1 = 0 or E3 = 0)",
        "compact waves need a regime where f is constant",
    )  # fmt: skip


def v_max(law, w_B: float) -> float:
    """Largest velocity of the explicit compact wave on background w_B (module docstring)."""
    side, b, E, h = zero_modulus_side(law)
    return math.sqrt(2.0 * E) / max(math.pi, 0.5 * math.pi + abs(b - w_B) / h)


@dataclass(frozen=True)
class CompactWave(Result):
    """The explicit compact discrete solitary wave (module docstring).  Exact: its residual in
    eq. TW_discrete is rounding; ``residual`` is measured on a grid of ξ (scaled by |C| E), with
    the jumps of w and w′ at the junctions (scaled by |C|)."""

    law: HardeningSofteningLaw
    V: float
    w_B: float
    b: float
    E: float
    C: float
    omega: float
    a: float
    residual: float
    elapsed_s: float

    ERROR_FIELDS: ClassVar = ("residual",)
    DERIVED: ClassVar = ("amplitude", "mass", "support", "converged", "status", "message")
    EXCLUDE: ClassVar = ("law",)

    @property
    def amplitude(self) -> float:
        """max |w − w_B| = |b − w_B| + |C| (crest at ξ = 0)."""
        return abs(self.b + self.C - self.w_B)

    @property
    def mass(self) -> float:
        """∫(w − w_B) dξ = ωC."""
        return self.omega * self.C

    @property
    def support(self) -> tuple[float, float]:
        return (-1.0 - self.a, 1.0 + self.a)

    def _parts(self, xi):
        x = np.abs(np.asarray(xi, dtype=float))
        z = x - 1.0
        core, lin, outer = x <= self.a, (x > self.a) & (x <= 1 - self.a), np.abs(z) < self.a
        outer &= ~core & ~lin
        return x, z, core, lin, outer

    def profile(self, xi):
        """w(ξ)."""
        x, z, core, lin, outer = self._parts(xi)
        C, om, a = self.C, self.omega, self.a
        w = np.full_like(x, self.w_B)
        w[core] = self.b + C * np.cos(om * x[core])
        w[lin] = self.w_B + om * C * (1.0 - x[lin])
        w[outer] = self.w_B + 0.5 * C * (om * (a - z[outer]) - np.cos(om * z[outer]))
        return w

    def slope(self, xi):
        """w′(ξ)."""
        xi = np.asarray(xi, dtype=float)
        x, z, core, lin, outer = self._parts(xi)
        C, om = self.C, self.omega
        d = np.zeros_like(x)
        d[core] = -C * om * np.sin(om * x[core])
        d[lin] = -om * C
        d[outer] = 0.5 * C * om * (np.sin(om * z[outer]) - 1.0)
        return np.where(xi < 0, -d, d)

    def curvature(self, xi):
        """w″(ξ) (piecewise: jumps at ±a, ±(1 ± a) where F(ξ ± 1) or F(ξ) switch on)."""
        x, z, core, lin, outer = self._parts(xi)
        C, om = self.C, self.omega
        d = np.zeros_like(x)
        d[core] = -C * om * om * np.cos(om * x[core])
        d[outer] = 0.5 * C * om * om * np.cos(om * z[outer])
        return d

    def lattice(self, n, phase: float = 0.0):
        """(w_n(0), ẇ_n(0)) = (w(n + phase), −V w′(n + phase)) on sites n (ξ = n − V t)."""
        xi = np.asarray(n, dtype=float) + phase
        return self.profile(xi), -self.V * self.slope(xi)

    @property
    def converged(self) -> bool:
        return bool(self.residual <= 1e-12)

    @property
    def status(self) -> str:
        return status_of(self.converged)

    @property
    def message(self) -> str:
        return "" if self.converged else "TW_discrete residual above rounding"


def residual(wave: CompactWave, xi) -> np.ndarray:
    """V² w″(ξ) − [f(w(ξ+1)) − 2f(w(ξ)) + f(w(ξ−1))], eq. TW_discrete, evaluated directly."""
    f = wave.law.f
    xi = np.asarray(xi, dtype=float)
    rhs = f(wave.profile(xi + 1)) - 2 * f(wave.profile(xi)) + f(wave.profile(xi - 1))
    return wave.V**2 * wave.curvature(xi) - rhs


def junction_defect(wave: CompactWave) -> float:
    """Largest jump of w or w′ across the junctions ±a, ±(1 − a), ±(1 + a): the matching
    conditions that fix C (the piecewise residual alone does not see them)."""
    a, h = wave.a, 1e-9 * max(1.0, wave.a)
    pts = np.array([a, 1 - a, 1 + a, -a, a - 1, -1 - a])
    dw = np.abs(wave.profile(pts + h) - wave.profile(pts - h))
    dd = np.abs(wave.slope(pts + h) - wave.slope(pts - h))
    # a smooth function moves by |w′| h and |w″| h over the gap: subtract what is expected
    lip = abs(wave.C) * wave.omega**2 * 3 * h
    return float(max(np.max(dw), np.max(dd) / wave.omega) - lip)


def compact_wave(law, V: float, w_B: float) -> CompactWave:
    """The explicit compact wave with velocity V on the background w_B in the zero-modulus
    regime (module docstring); refused with the valid range of V or w_B otherwise."""
    t0 = time.perf_counter()
    side, b, E, h = zero_modulus_side(law)
    w_B = require_finite("w_B", w_B)
    if not (w_B < b if side < 0 else w_B > b):
        raise ParameterError(
            "w_B", w_B, f"w_B {'<' if side < 0 else '>'} {b:.10g}",
            "the background must lie inside the zero-modulus regime",
        )  # fmt: skip
    V = abs(require_finite("V", V))
    vm = v_max(law, w_B)
    if not 0 < V < vm:
        raise ParameterError(
            "V", V, fmt_interval(0.0, vm),
            "the explicit wave needs its core narrower than one lattice space (V < sqrt(2E)/pi) "
            "and its crest inside the adjacent regime (V <= sqrt(2E)/(pi/2 + |b - w_B|/h))",
        )  # fmt: skip
    om = math.sqrt(2.0 * E) / V
    a = 0.5 * math.pi / om
    C = (b - w_B) / (om * (1.0 - a))
    wave = CompactWave(law, V, w_B, b, E, C, om, a, 0.0, 0.0)
    xi = np.linspace(-2.0, 2.0, 801)
    r = float(np.max(np.abs(residual(wave, xi)))) / (abs(C) * E)
    r = max(r, junction_defect(wave) / abs(C))
    return CompactWave(law, V, w_B, b, E, C, om, a, r, time.perf_counter() - t0)
