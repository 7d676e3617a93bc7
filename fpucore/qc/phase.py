"""Phase plane of the QC traveling-wave equation (eq. TW_QC_gen2, Fig. pplane).

For given (w₊, V) the critical points are the intersections of f with the Rayleigh line
R(w) = f(w₊) + V²(w − w₊); a point is a saddle where V² > f′(w_c) and a center where V² < f′(w_c)
(linearize −V²/12 w″ = f(w) − R(w)).  The first integral H of eq. TW_QC_gen3 is evaluated on a
grid: its level sets are the exact phase portrait, and the separatrix levels are H at the saddles.
The highlighted orbit comes from the closed-form profile (homoclinic for solitary waves,
heteroclinic pair at V = V_SK).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from fpucore.budget import require_memory
from fpucore.errors import ParameterError, fmt_interval, require_finite, require_int
from fpucore.law import HardeningSofteningLaw, require_law
from fpucore.qc import dispatch as qc
from fpucore.qc.closed_forms import V_SPAN as V_SPAN_QC
from fpucore.qc.closed_forms import first_integral, require_V


@dataclass(frozen=True)
class CriticalPoint:
    w: float
    kind: str  # "saddle" | "center" | "degenerate"
    eigenvalue: float  # λ² of the linearization w″ = λ² δw: 12 (V² − f′(w_c)) / V²


@dataclass(frozen=True)
class Orbit:
    name: str  # "tensile solitary wave", "compressive solitary wave", "kink", "antikink"
    kind: str  # "homoclinic" | "heteroclinic"
    w: np.ndarray
    wp: np.ndarray


@dataclass(frozen=True)
class PhasePlane:
    """Grid ``H[j, i] = H(w[i], wp[j])`` with ``w`` (n,) and ``wp`` (m,), critical points,
    separatrix levels (H at each saddle) and the highlighted orbits.  ``orbit_residual`` is
    max |H| on the orbits relative to the grid's H range (round-off for closed forms)."""

    w_plus: float
    V: float
    w: np.ndarray
    wp: np.ndarray
    H: np.ndarray
    critical_points: list[CriticalPoint]
    separatrix_levels: list[float]
    orbits: list[Orbit] = field(default_factory=list)
    regime: str = ""
    orbit_residual: float = 0.0
    elapsed_s: float = 0.0


V_SPAN = V_SPAN_QC  # phase portraits for c_max / V_SPAN <= V <= V_SPAN c_max
N_GRID_MAX = 10**9  # an integer; the memory budget below decides how large
N_ORBIT_MAX = 100_001


def require_phase_V(law: HardeningSofteningLaw, V: float) -> float:
    """V > 0 within a factor V_SPAN of c_max: far outside, V² swamps f (or the reverse) and the
    portrait is the trivial one of a linear equation, computed with overflow (V = 1e300: all
    NaN) or a division by V² = 0 (V = 1e-300: ZeroDivisionError)."""
    V = require_V(V)
    c = law.c_max
    if not c / V_SPAN <= V <= c * V_SPAN:
        raise ParameterError(
            "V",
            V,
            fmt_interval(c / V_SPAN, c * V_SPAN, open_=False),
            f"phase portraits within a factor {V_SPAN:g} of c_max = {c:.10g}",
        )
    return V


def critical_points(law: HardeningSofteningLaw, w_plus: float, V: float) -> list[CriticalPoint]:
    """Critical points (w_c, 0) of eq. TW_QC_gen2 for (w₊, V), sorted by w."""
    law = require_law(law)
    w_plus = law.require_convex("w_plus", w_plus)
    V = require_phase_V(law, V)
    ws = [w_plus]
    if V <= qc.sound_speeds(law, w_plus)[2]:  # beyond c₋ the Rayleigh line meets f only at w₊
        ws += [w for w in qc.rayleigh_roots(law, w_plus, V) if math.isfinite(w)]
    out = []
    for w in sorted(set(ws)):
        lam2 = 12.0 * (V * V - float(law.df(w))) / (V * V)
        tol = 1e-12 * 12.0
        kind = "saddle" if lam2 > tol else ("center" if lam2 < -tol else "degenerate")
        out.append(CriticalPoint(w, kind, lam2))
    return out


def _orbit_points(wave, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Sample (w, w′) along a closed-form profile, clustered where the curve turns."""
    width = wave.width
    xi = np.sinh(np.linspace(-6.0, 6.0, n)) / math.sinh(6.0) * 40.0 * width
    return wave.profile(xi), wave.dprofile(xi)


def phase_plane(
    law: HardeningSofteningLaw,
    w_plus: float,
    V: float,
    n_grid: int = 241,
    n_orbit: int = 401,
    sk_tol: float = 1e-9,
) -> PhasePlane:
    """Exact phase portrait of eq. TW_QC_gen2 for (w₊, V).

    ``regime`` says what the highlighted orbit is: "tensile"/"compressive" solitary wave,
    "superkink" (|V − V_SK| ≤ sk_tol·V_SK), or "none" when V is outside (c₊, c₋) (then only the
    level sets and critical points are returned).
    """
    t0 = time.perf_counter()
    law = require_law(law)
    n_grid = require_int("n_grid", n_grid, 3, N_GRID_MAX)
    n_orbit = require_int("n_orbit", n_orbit, 3, N_ORBIT_MAX)
    # the grid (W, W′, H and the temporaries of H: ~8 arrays of n_grid² floats), before allocating
    n_floats = 8.0 * n_grid * n_grid
    require_memory("n_grid", 8 * n_floats, f"~8 arrays of n_grid² = {n_grid}² floats", n_grid)
    w_plus = law.require_convex("w_plus", w_plus)
    V = require_phase_V(law, V)
    sk_tol = require_finite("sk_tol", sk_tol)
    if not 0.0 <= sk_tol <= 1e-3:
        raise ParameterError("sk_tol", sk_tol, "[0, 0.001]", "relative distance from V_SK")
    cps = critical_points(law, w_plus, V)
    orbits: list[Orbit] = []
    regime = "none"
    ref = w_plus  # H is measured relative to the saddle the highlighted orbit leaves
    if abs(w_plus - law.w_star) > 1e-12 * max(1.0, law.w_star):
        cp, vsk, cm = qc.sound_speeds(law, w_plus)
        if abs(V - vsk) <= sk_tol * vsk:
            sk = qc.superkink_from_w_plus(law, w_plus)
            w, wp = _orbit_points(sk, n_orbit)
            orbits = [
                Orbit("kink", "heteroclinic", w, wp),
                Orbit("antikink", "heteroclinic", w, -wp),
            ]
            regime = "superkink"
        elif cp < V < cm:
            sw = qc.solitary(law, w_plus, V)
            w, wp = _orbit_points(sw, n_orbit)
            orbits = [Orbit(f"{sw.kind} solitary wave", "homoclinic", w, wp)]
            regime, ref = sw.kind, sw.w_B

    ws = (
        [c.w for c in cps]
        + [float(np.min(o.w)) for o in orbits]
        + [float(np.max(o.w)) for o in orbits]
    )
    lo, hi = min(ws), max(ws)
    pad = 0.25 * max(hi - lo, 0.5)
    # The window stays in the law's stable interval [alpha, beta] except where a critical point
    # lies outside it: the paper counts three critical points for c+^2 < V^2 < c-^2, and the
    # second saddle w_S can lie beyond beta (w_S = 6.79 > beta = 6.72 at w+ = 1, V = 5).
    ext = 0.03 * (law.beta - law.alpha)  # a margin, so a marker there is not cut in half
    w_lo = min([law.alpha] + [c.w - ext for c in cps if c.w < law.alpha])
    w_hi = max([law.beta] + [c.w + ext for c in cps if c.w > law.beta])
    w_grid = np.linspace(max(lo - pad, w_lo), min(hi + pad, w_hi), n_grid)
    wp_max = max([float(np.max(np.abs(o.wp))) for o in orbits] + [0.0])
    if wp_max == 0.0:
        wp_max = math.sqrt(24.0 / (V * V) * float(np.ptp(law.phi(w_grid)))) + 1e-3
    wp_grid = np.linspace(-1.4 * wp_max, 1.4 * wp_max, n_grid)
    W, WP = np.meshgrid(w_grid, wp_grid)
    H = first = first_integral(law, W, WP, ref, V)
    levels = [float(first_integral(law, c.w, 0.0, ref, V)) for c in cps if c.kind == "saddle"]
    span = float(np.ptp(first)) or 1.0
    res = max(
        [float(np.max(np.abs(first_integral(law, o.w, o.wp, ref, V)))) for o in orbits] + [0.0]
    )
    return PhasePlane(
        w_plus,
        V,
        w_grid,
        wp_grid,
        H,
        cps,
        levels,
        orbits,
        regime,
        res / span,
        time.perf_counter() - t0,
    )


@dataclass(frozen=True)
class LevelOrbit:
    """The orbit of eq. TW_QC_gen2 through one point (w0, w0′) of the phase plane: the connected
    component of the level set H = H(w0, w0′) of eq. TW_QC_gen3 that contains it, within the
    window ``w_window``.  ``w``, ``wp``: (n,) points along it, NaN between separate branches;
    ``closed``: a periodic orbit (both turning points inside the window); ``turning_points``:
    the w where w′ = 0 (roots of the level, by bracketing); ``residual``: max |H − level| on the
    points relative to the size of H's terms (round-off for an exact orbit)."""

    w0: float
    wp0: float
    level: float
    w: np.ndarray
    wp: np.ndarray
    closed: bool
    turning_points: tuple[float, ...]
    residual: float
    elapsed_s: float = 0.0


def orbit_through(
    law: HardeningSofteningLaw,
    w_plus: float,
    V: float,
    w0: float,
    wp0: float,
    w_window: tuple[float, float],
    n: int = 801,
) -> LevelOrbit:
    """The orbit through (w0, w0′) in the phase portrait of (w₊, V) (pplane's "click to draw an
    orbit"), from the first integral in closed form instead of a numerical integration:
    w′(w) = ±√(24/V² (E − U(w))) with E = H(w0, w0′) and U = H(w, 0) (eq. TW_QC_gen3), on the
    interval of w around w0 where E ≥ U.  Its ends are the turning points (solved to round-off
    by bisection) or the window's edges (an orbit that leaves the window is drawn as two open
    branches).  ``n`` points per branch."""
    t0 = time.perf_counter()
    law = require_law(law)
    w_plus = law.require_convex("w_plus", w_plus)
    V = require_phase_V(law, V)
    w0, wp0 = require_finite("w0", w0), require_finite("wp0", wp0)
    n = require_int("n", n, 3, N_ORBIT_MAX)
    lo, hi = (require_finite("w_window", x) for x in w_window)
    if not lo < hi:
        raise ParameterError("w_window", (lo, hi), "lo < hi", "an interval of strains")
    if not lo <= w0 <= hi:
        raise ParameterError("w0", w0, fmt_interval(lo, hi, open_=False), "inside the window")

    def gap(w):  # E − U(w) = V²/24 w′² on the level set; ≥ 0 exactly where the orbit runs
        return level - first_integral(law, w, 0.0 * w, w_plus, V)

    level = float(first_integral(law, w0, wp0, w_plus, V))
    grid = np.linspace(lo, hi, 4 * n + 1)
    g = gap(grid)
    k0 = int(np.clip(np.searchsorted(grid, w0), 1, len(grid) - 1))
    ends = []
    for step, edge in ((-1, lo), (1, hi)):
        # walk from w0 to the first sign change of the gap (a turning point) or the window edge
        k = k0 - 1 if step < 0 else k0
        idx = range(k, -1, -1) if step < 0 else range(k, len(grid))
        end, turning, prev = edge, False, w0
        for i in idx:
            if g[i] < 0.0:
                a, b = (grid[i], prev) if step < 0 else (prev, grid[i])
                inside = b if step < 0 else a  # where the gap is >= 0
                outside = a if step < 0 else b
                for _ in range(200):  # bisection to round-off: no derivative needed
                    mid = 0.5 * (inside + outside)
                    if mid in (inside, outside):
                        break
                    if gap(mid) >= 0.0:
                        inside = mid
                    else:
                        outside = mid
                end, turning = inside, True
                break
            prev = grid[i]
        ends.append((float(end), turning))
    (wl, tl), (wr, tr) = ends
    # points clustered at the turning points, where w′ varies like a square root
    u = 0.5 - 0.5 * np.cos(np.linspace(0.0, math.pi, n))
    w = wl + (wr - wl) * u
    wp = np.sqrt(np.maximum(24.0 / (V * V) * gap(w), 0.0))
    closed = tl and tr
    if closed:  # one loop: upper branch left to right, lower branch back
        W, WP = np.concatenate([w, w[::-1]]), np.concatenate([wp, -wp[::-1]])
    else:  # two open branches (the orbit leaves the window)
        W = np.concatenate([w, [np.nan], w])
        WP = np.concatenate([wp, [np.nan], -wp])
    ok = np.isfinite(W)
    res = _level_residual(law, W[ok], WP[ok], w_plus, V, level)
    turning = tuple(x for x, t in ((wl, tl), (wr, tr)) if t)  # type: ignore[assignment]
    return LevelOrbit(w0, wp0, level, W, WP, bool(closed), turning, res, time.perf_counter() - t0)  # type: ignore[arg-type]


def _level_residual(law, w, wp, w_ref, V, level) -> float:
    """max |H(w, w′) − level| relative to the size of H's terms (see first_integral_residual)."""
    d = w - w_ref
    phi_w, phi_r, f_r = law.phi(w), float(law.phi(w_ref)), float(law.f(w_ref))
    H = V * V / 24.0 * wp * wp + phi_w - phi_r - f_r * d - 0.5 * V * V * d * d
    scale = (
        np.abs(phi_w) + abs(phi_r) + np.abs(f_r * d) + V * V * (d * d + wp * wp / 24.0) + abs(level)
    )
    return float(np.max(np.abs(H - level) / (scale + 1e-300)))
