"""Property test: every public function of fpucore driven with arbitrary inputs (huge and
tiny floats, NaN, inf, strings, bools, None, negatives, integers) by hypothesis.

The property, for every call: either a ParameterError naming one of the arguments of the call,
or a result whose arrays are all finite and whose error fields (``ERROR_FIELDS`` of the result
protocol) are finite — never another exception, never a hang (small sizes, short time budgets,
hypothesis ``deadline``).  Where a call succeeds, QC numbers are checked against closed-form
identities evaluated independently in exact rational arithmetic (Rayleigh relation eq. Rline,
c₊² = f′(w₊), the equal-area / zero-driving-force condition eq. zero_G), so a wrong number
cannot pass.  derandomize=True: the examples are the same on every run.
"""

from __future__ import annotations

import dataclasses
import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from fpucore import CubicLaw, ParameterError, floquet, qc, simulate, wave
from fpucore.atlas import sweeps
from fpucore.qc import diagram, phase
from fpucore.result import Result

FAST = settings(
    derandomize=True,
    max_examples=300,
    deadline=None,
    database=None,
    suppress_health_check=list(HealthCheck),
)
SLOW = settings(FAST, max_examples=40)

SPECIAL = [0.0, -0.0, 1e-300, -1e-300, 5e-324, 1e300, -1e300, 1.7976931348623157e308, math.nan]
SPECIAL += [math.inf, -math.inf, 1e-16, 1e16, -1.0, 1.0]
WILD_FLOAT = st.one_of(st.sampled_from(SPECIAL), st.floats(allow_nan=True, allow_infinity=True))
ANYTHING = st.one_of(
    WILD_FLOAT,
    st.integers(-(10**30), 10**30),
    st.booleans(),
    st.none(),
    st.text(max_size=4),
    st.sampled_from(["-1", "5.2", "nan", [1.0, 2.0], (), {"a": 1}, 1j]),
)


def mostly(good, bad):
    """good two times in three, bad otherwise (st.one_of flattens nested one_ofs, so
    ``one_of(good, good, bad)`` would weight every branch of ``bad`` like ``good``)."""
    return st.integers(0, 2).flatmap(lambda k: bad if k == 2 else good)


def law_params():
    """(a, b): mostly plausible laws (including stiff and soft ones), sometimes anything."""
    plausible = st.tuples(
        st.floats(-1e3, -1e-3).map(lambda x: float(f"{x:.3g}")),
        st.floats(1e-2, 1e3).map(lambda x: float(f"{x:.3g}")),
    )
    extreme = st.tuples(
        st.sampled_from([-1e-300, -1e-30, -1e-10, -1.0, -1e10, -1e30, -1e300]),
        st.sampled_from([1e-300, 1e-30, 1e-10, 1.0, 1e10, 1e20, 1e30, 1e80, 1.4e154, 1e300]),
    )
    good = st.one_of(st.just((-1.0, 10.0)), plausible)
    return mostly(good, st.one_of(extreme, st.tuples(ANYTHING, ANYTHING)))


def position(lo: float, hi: float, t) -> object:
    """t in [-0.2, 1.2] -> a point of [lo, hi] (or just outside); anything else passes through."""
    if isinstance(t, float) and -0.2 <= t <= 1.2 and math.isfinite(lo) and math.isfinite(hi):
        return lo + t * (hi - lo)
    return t


RELATIVE = st.one_of(st.floats(-0.2, 1.2), st.sampled_from([0.0, 1.0, 1e-12, 1 - 1e-12, 0.5]))
ARG = mostly(RELATIVE, ANYTHING)  # relative positions two times in three


# ----------------------------------------------------------------------------- the property
def assert_finite(obj, where: str = "result") -> None:
    """Arrays finite everywhere in obj; error fields of results finite."""
    if isinstance(obj, Result):  # the error fields that apply to this result (Result.errors)
        for name, v in obj.errors().items():
            assert math.isfinite(v), f"{where}.{name} = {v}"
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            if not (isinstance(obj, Result) and f.name in obj.ERROR_FIELDS):
                assert_finite(getattr(obj, f.name), f"{where}.{f.name}")
    elif isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc":
            assert np.all(np.isfinite(obj)), f"{where}: non-finite array entries"
    elif isinstance(obj, (list, tuple)):
        for i, x in enumerate(obj):
            assert_finite(x, f"{where}[{i}]")
    elif isinstance(obj, float) and where.count(".") == 0:  # bare numbers returned by a function
        assert math.isfinite(obj), f"{where} = {obj}"


def outcome(names: set[str], fn, *args, **kw):
    """Call fn; a ParameterError must name one of ``names``; a result must be finite."""
    try:
        r = fn(*args, **kw)
    except ParameterError as exc:
        event(f"{fn.__name__} refused: {exc.name}")
        assert exc.name in names, f"{fn.__name__}: ParameterError names {exc.name!r}: {exc}"
        assert "\n" not in str(exc)
        return None
    assert_finite(r, fn.__name__)
    return r


def make_law(ab):
    """The law, or None when (a, b) is refused (by name)."""
    return outcome({"a", "b", "(a, b)"}, CubicLaw, *ab)


# ----------------------------------------------------------------------------- exact references
def _F(x) -> Fraction:
    return Fraction(float(x))


def f_exact(law, w) -> Fraction:
    a, b, x = _F(law.a), _F(law.b), _F(w)
    return ((a * x + b) * x + 1) * x


def df_exact(law, w) -> Fraction:
    a, b, x = _F(law.a), _F(law.b), _F(w)
    return (3 * a * x + 2 * b) * x + 1


def phi_exact(law, w) -> Fraction:
    a, b, x = _F(law.a), _F(law.b), _F(w)
    return ((a / 4 * x + b / 3) * x + Fraction(1, 2)) * x * x


def f_terms(law, w) -> Fraction:
    """|a||w|³ + b w² + |w|: the size of the terms that cancel in f(w) (its rounding scale)."""
    a, b, x = abs(_F(law.a)), _F(law.b), abs(_F(w))
    return ((a * x + b) * x + 1) * x


def phi_terms(law, w) -> Fraction:
    a, b, x = abs(_F(law.a)), _F(law.b), abs(_F(w))
    return ((a / 4 * x + b / 3) * x + Fraction(1, 2)) * x * x


def check_superkink(law, sk) -> None:
    """Eq. Rline: f(w₋) − f(w₊) = V²(w₋ − w₊); eq. zero_G: Φ(w₋) − Φ(w₊) = ½(f(w₊) + f(w₋))(w₋ −
    w₊) (equal areas); both in exact arithmetic at the returned floats, relative to the terms."""
    wp, wm, V2 = _F(sk.w_plus), _F(sk.w_minus), _F(sk.V) ** 2
    fp, fm = f_exact(law, wp), f_exact(law, wm)
    scale = f_terms(law, wp) + f_terms(law, wm) + V2 * (abs(wm) + abs(wp))
    assert abs(fm - fp - V2 * (wm - wp)) <= 1e-12 * scale
    G = phi_exact(law, wm) - phi_exact(law, wp) - (fp + fm) / 2 * (wm - wp)
    G_scale = phi_terms(law, wm) + phi_terms(law, wp) + scale * (abs(wm) + abs(wp))
    assert abs(G) <= 1e-12 * G_scale


def check_sound_speeds(law, w_plus, speeds) -> None:
    cp, vsk, cm = speeds
    ref = df_exact(law, w_plus)  # eq. cplus: c₊² = f′(w₊), to an ulp
    assert abs(_F(cp) ** 2 - ref) <= Fraction(1, 10**15) * ref + Fraction(1, 10**300)
    assert cp <= vsk <= cm


# ----------------------------------------------------------------------------- QC
@FAST
@given(law_params())
def test_cubic_law(ab):
    law = make_law(ab)
    if law is not None:
        assert law.alpha < 0 < law.w_star < law.beta
        for w in (law.alpha, law.beta):  # f′ vanishes at the ends of the convex interval
            d = df_exact(law, w)
            assert abs(d) <= 1e-12 * (
                1 + 2 * _F(law.b) * abs(_F(w)) + 3 * abs(_F(law.a) * _F(w) ** 2)
            )


@FAST
@given(law_params(), ARG)
def test_qc_speeds_and_superkink(ab, t):
    law = make_law(ab)
    if law is None:
        return
    w_plus = position(law.alpha, law.beta, t)
    speeds = outcome({"w_plus"}, qc.sound_speeds, law, w_plus)
    if speeds is not None:
        check_sound_speeds(law, w_plus, speeds)
    sk = outcome({"w_plus"}, qc.superkink_from_w_plus, law, w_plus)
    if sk is not None:
        check_superkink(law, sk)
        assert sk.converged
    outcome({"w_plus"}, qc.solitary_intervals, law, w_plus)
    outcome({"w_plus"}, qc.w_minus_sonic, law, w_plus)
    lo, hi = outcome(set(), qc.superkink_velocity_bounds, law)
    assert lo * lo == pytest.approx(2 / 3 * hi * hi, rel=1e-14)  # eq. V_bounds_cubic
    outcome({"V"}, qc.require_V, t)
    # the array form of c₊ (existence diagram) against √f′ in exact arithmetic, relative to the
    # rounding of α and β (the factored form's conditioning) — cheap: a few points per law
    ws = law.alpha + (law.beta - law.alpha) * np.array([1e-9, 0.01, 0.5, 0.99, 1 - 1e-9])
    cps = qc.sound_speed_plus(law, ws)
    for w, c in zip(ws, cps, strict=True):
        ref = df_exact(law, w)
        tol = (
            1e-14
            * 3
            * abs(_F(law.a))
            * (abs(_F(w)) + abs(_F(law.alpha)))
            * (abs(_F(w)) + _F(law.beta))
        )
        assert abs(_F(c) ** 2 - ref) <= tol + Fraction(1, 10**15) * ref


@FAST
@given(law_params(), ARG, st.sampled_from(["lower", "upper", "middle", None, 1]))
def test_qc_superkink_from_V(ab, t, branch):
    law = make_law(ab)
    if law is None:
        return
    lo, hi = qc.superkink_velocity_bounds(law)
    sk = outcome({"V", "branch"}, qc.superkink_from_V, law, position(lo, hi, t), branch)
    if sk is not None:
        check_superkink(law, sk)


@FAST
@given(law_params(), RELATIVE, ARG)
def test_qc_solitary_and_rayleigh(ab, s, t):
    law = make_law(ab)
    if law is None:
        return
    w_plus = position(law.alpha, law.beta, s)
    speeds = outcome({"w_plus"}, qc.sound_speeds, law, w_plus)
    if speeds is None:
        return
    cp, vsk, cm = speeds
    V = position(cp, cm, t)
    sw = outcome({"V", "w_plus"}, qc.solitary, law, w_plus, V)
    if sw is not None:
        assert cp < sw.V < cm and sw.V != vsk
        assert sw.converged and math.isfinite(sw.energy)
        # the background and the turning points lie on one Rayleigh line through w_B (eq. w_T_M
        # from G(w) = 0): G(w_M) = G(w_T) = 0 with G of eq. TW_QC_gen3, exact arithmetic
        wb, V2 = _F(sw.w_B), _F(sw.V) ** 2
        for w in (sw.w_M, sw.w_T):
            x = _F(w)
            G = phi_exact(law, x) - phi_exact(law, wb) - f_exact(law, wb) * (x - wb)
            G -= V2 / 2 * (x - wb) ** 2
            scale = phi_terms(law, x) + phi_terms(law, wb) + f_terms(law, wb) * abs(x - wb)
            scale += V2 * (x - wb) ** 2
            assert abs(G) <= 1e-12 * scale
    for fn in (qc.rayleigh_roots, qc.w_S):
        roots = outcome({"V", "w_plus"}, fn, law, w_plus, V)
        for r in np.atleast_1d(roots if roots is not None else []):
            R = f_exact(law, r) - f_exact(law, w_plus) - _F(V) ** 2 * (_F(r) - _F(w_plus))
            scale = f_terms(law, r) + f_terms(law, w_plus)
            scale += _F(V) ** 2 * (abs(_F(r)) + abs(_F(w_plus)))
            assert abs(R) <= 1e-12 * scale


@FAST
@given(law_params(), RELATIVE, ARG, ARG, ARG)
def test_qc_first_integral_and_closed_form(ab, s, t, w, wp):
    law = make_law(ab)
    if law is None:
        return
    w_ref = position(law.alpha, law.beta, s)
    outcome({"w", "wp", "w_ref", "V"}, qc.first_integral, law, w, wp, w_ref, t)
    try:
        *vals, ok = qc.solitary_closed_form(law, w_ref, t)
    except ParameterError as exc:
        assert exc.name in {"w_B", "V"}
    else:  # ok marks the entries where the closed form exists; there they are finite
        for v in vals:
            assert np.all(np.isfinite(np.asarray(v)[np.asarray(ok)]))


@SLOW
@given(
    law_params(),
    RELATIVE,
    ARG,
    st.one_of(st.sampled_from([3, 41, 241]), ANYTHING),
    st.one_of(st.sampled_from([3, 101]), ANYTHING),
)
def test_phase_plane(ab, s, t, n_grid, n_orbit):
    law = make_law(ab)
    if law is None:
        return
    w_plus = position(law.alpha, law.beta, s)
    speeds = outcome({"w_plus"}, qc.sound_speeds, law, w_plus)
    V = position(0.5 * speeds[0], 1.5 * speeds[2], t) if speeds else t
    names = {"w_plus", "V", "n_grid", "n_orbit", "sk_tol"}
    pp = outcome(names, phase.phase_plane, law, w_plus, V, n_grid=n_grid, n_orbit=n_orbit)
    if pp is not None:
        assert pp.orbit_residual <= 1e-9
    outcome({"w_plus", "V"}, phase.critical_points, law, w_plus, V)


@SLOW
@given(law_params(), ARG, st.one_of(st.sampled_from([3, 50, 400]), ANYTHING), ARG)
def test_diagrams(ab, s, n, t):
    law = make_law(ab)
    if law is None:
        return
    d = outcome({"n"}, diagram.existence_diagram, law, n)
    if d is not None:
        assert np.all(d.c_plus <= d.V_SK) and np.all(d.V_SK <= d.c_minus)
    w_plus = position(law.alpha, law.beta, s)
    outcome({"w_plus", "n"}, diagram.solitary_family, law, w_plus, n)
    speeds = outcome({"w_plus"}, qc.sound_speeds, law, w_plus)
    V = position(speeds[0], speeds[2], t) if speeds else t
    outcome({"w_plus", "V"}, diagram.classify, law, w_plus, V)


# ----------------------------------------------------------------------------- discrete waves
WAVE_LAW = mostly(st.sampled_from([(-1.0, 10.0), (-1.0, 100.0)]), st.tuples(ANYTHING, ANYTHING))
WAVE_NAMES = {"V", "w_plus", "N", "tol", "branch", "jacobian", "max_iter", "time_budget_s", "law"}
N_BAD = st.one_of(st.sampled_from([7, 0, -2, 10**9, 2.0, True]), ANYTHING)
N_ARG = mostly(st.sampled_from([None, 64, 100]), N_BAD)
TOL_ARG = mostly(st.just(1e-10), st.one_of(st.sampled_from([0.0, 1e-16, 1e-2, -1e-10]), ANYTHING))


@SLOW
@given(WAVE_LAW, ARG, N_ARG, TOL_ARG, st.sampled_from(["lower", "upper", "x"]))
def test_wave_superkink(ab, t, N, tol, branch):
    law = None if ab is None else make_law(ab)
    lo, hi = qc.superkink_velocity_bounds(law) if law is not None else (4.8, 5.9)
    V = position(lo, hi, t)
    r = outcome(WAVE_NAMES, wave.solve_superkink, law, V, branch, N, tol, time_budget_s=2.0)
    if r is not None and r.converged:
        assert r.residual <= 1e-6 and lo < r.V < hi


@settings(SLOW, max_examples=12)
@given(
    st.sampled_from([(-1.0, 10.0), (-1.0, 100.0), (-0.01, 10.0), (-5.0, 0.2)]),
    st.floats(0.02, 0.98),
    st.sampled_from(["lower", "upper"]),
)
def test_wave_superkink_inside_the_interval(ab, t, branch):
    """Valid inputs: a converged wave has its boundary states at the QC w± of eq. wpm_cubic (which
    satisfy eq. Rline exactly) and its residual within tol x strain scale; otherwise it says why
    (never a wrong number with converged=True).  time_budget_s bounds every call."""
    law = CubicLaw(*ab)
    lo, hi = qc.superkink_velocity_bounds(law)
    V = lo + t * (hi - lo)
    r = outcome(WAVE_NAMES, wave.solve_superkink, law, V, branch, None, 1e-10, time_budget_s=2.0)
    if r is not None:
        sk = qc.superkink_from_V(law, V, branch)
        check_superkink(law, sk)
        assert (r.w_left, r.w_right) == (sk.w_minus, sk.w_plus)
        if r.converged:
            assert r.residual <= 1e-10 * max(1.0, abs(r.w_left), abs(r.w_right))
        else:
            assert r.message


@SLOW
@given(WAVE_LAW, RELATIVE, ARG, N_ARG, TOL_ARG)
def test_wave_solitary(ab, s, t, N, tol):
    law = make_law(ab)
    if law is None:
        outcome(WAVE_NAMES, wave.solve_solitary, None, 1.0, 5.0)
        return
    w_plus = position(law.alpha, law.beta, s)
    speeds = outcome({"w_plus"}, qc.sound_speeds, law, w_plus)
    V = position(speeds[0], speeds[2], t) if speeds else t
    outcome(WAVE_NAMES, wave.solve_solitary, law, w_plus, V, N, tol, time_budget_s=2.0)


# ----------------------------------------------------------------------------- Floquet
@pytest.fixture(scope="module")
def small_wave():
    r = wave.solve_superkink(CubicLaw(), 5.2, N=64)
    assert r.converged
    return r


class _Mutated:
    """A wave result with some attributes replaced (duck-typed like the result)."""

    def __init__(self, r, **changes):
        for k in ("law", "V", "w", "wdot", "w_left", "w_right", "residual", "converged", "m"):
            setattr(self, k, changes.get(k, getattr(r, k)))


@settings(SLOW, max_examples=30)
@given(
    st.sampled_from(["law", "V", "w", "wdot", "w_left", "scale", None]),
    ANYTHING,
    st.one_of(st.none(), st.sampled_from([2, 8, 0, True, 10**6]), ANYTHING),
)
def test_floquet_spectrum(small_wave, which, value, m):
    r = small_wave
    if which is None:
        state = r
    elif which == "scale":  # every strain multiplied: leaves the restoring interval quickly
        f = value if isinstance(value, float) else 1.0
        state = _Mutated(r, w=r.w * f, w_left=r.w_left * f, w_right=r.w_right * f)
    elif which in ("w", "wdot"):
        arr = np.array(getattr(r, which), dtype=object)
        arr[len(arr) // 2] = value
        state = _Mutated(r, **{which: arr})
    else:
        state = _Mutated(r, **{which: value})
    names = {"r", "V", "N", "m", "trivial_radius", "r.w_left/r.w_right"}
    names |= {f"r.{k}" for k in ("law", "V", "w", "wdot", "w_left", "w_right")}
    fr = outcome(names, floquet.spectrum, state, m=m)
    if fr is not None:
        assert fr.error < 1e-3


@settings(SLOW, max_examples=30)
@given(
    st.sampled_from(["superkink", "solitary", "x", None]),
    st.one_of(st.sampled_from([[5.2], [], [-1.0], "5.2"]), st.lists(ANYTHING, max_size=2)),
    st.one_of(st.sampled_from([16, 7, 10**6, True]), ANYTHING),
    TOL_ARG,
    st.one_of(st.sampled_from([-1.0, 0.0, math.nan]), ANYTHING),
)
def test_floquet_sweep_validation(kind, Vs, N, tol, budget):
    """Only the up-front validation is exercised (a sweep is minutes): every refusal names an
    argument; arguments that pass are exactly those the sweep accepts."""
    names = {"kind", "V", "V_values", "N", "tol", "time_budget_s", "w_plus", "branch", "m", "law"}
    try:
        sweeps.check_sweep_args(CubicLaw(), kind, Vs, 1.0, N, "lower", None, tol, budget)
    except ParameterError as exc:
        assert exc.name in names


# ----------------------------------------------------------------------------- simulations
SIM_NAMES = {
    "L", "t_end", "w_left", "w_right", "w_B", "A", "method", "rtol", "dt", "boundary",
    "guard", "n_snapshots", "max_sites_out", "probes", "n_probe_t", "threshold", "r", "law",
    "late_fraction", "margin", "time_budget_s", "memory_budget",
}  # fmt: skip
L_GOOD, T_GOOD = st.sampled_from([40, 100]), st.floats(0.05, 3.0)
INSIDE = st.floats(0.05, 0.95)  # positions inside (α, β)
S_ARG = mostly(INSIDE, ARG)
L_BAD = st.one_of(st.sampled_from([7, 0, -2, True, 10**12, 10**7]), ANYTHING)
L_ARG = mostly(L_GOOD, L_BAD)
T_ARG = mostly(T_GOOD, st.one_of(st.sampled_from([0.0, -1.0, 1e300, 1e5]), ANYTHING))
# the budgets of fpucore.budget bound every run: wall time and memory (with huge L or t_end the
# run is refused up front or stops cleanly with status "stopped")
BUDGETS = {"time_budget_s": 2.0, "memory_budget": "256MiB"}
SIM_KW_WILD = st.fixed_dictionaries(
    {},
    optional={
        "n_probe_t": st.one_of(st.sampled_from([4001, 2, 0, -1, 10**9]), ANYTHING),
        "late_fraction": st.one_of(st.sampled_from([0.5, 0.0, 1.0, -1.0, 2.0]), ANYTHING),
        "n_snapshots": st.one_of(st.sampled_from([4, 1, 0, 10**6]), ANYTHING),
        "rtol": st.one_of(st.sampled_from([1e-8, 0.0, 1.0]), ANYTHING),
        "method": st.sampled_from(["rkn12", "dop853", "yoshida4", "x", None]),
    },
)
SIM_KW = mostly(st.just({}), SIM_KW_WILD)


def check_simulation(s, t_end) -> None:
    """A run never goes past the requested end time (late_fraction=-1 once ran to 2 t_end)."""
    event("ran" if s is not None else "refused")  # both occur: --hypothesis-show-statistics
    if s is not None and isinstance(t_end, float):
        assert np.all(s.t <= t_end * (1 + 1e-12) + 1e-12)


@SLOW
@given(S_ARG, S_ARG, L_ARG, T_ARG, SIM_KW)
def test_simulate_riemann(s, t, L, t_end, kw):
    law = CubicLaw()
    wl, wr = position(law.alpha, law.beta, s), position(law.alpha, law.beta, t)
    r = outcome(SIM_NAMES, simulate.riemann, law, wl, wr, L, t_end, **kw, **BUDGETS)
    check_simulation(r, t_end)


@SLOW
@given(
    S_ARG,
    st.one_of(st.floats(-0.5, 0.5), ANYTHING),
    L_ARG,
    T_ARG,
    st.sampled_from(["convex", "bounded", "x"]),
    SIM_KW,
)
def test_simulate_gaussian(s, A, L, t_end, guard, kw):
    law = CubicLaw()
    wB = position(law.alpha, law.beta, s)
    r = outcome(SIM_NAMES, simulate.gaussian, law, wB, A, L, t_end, guard=guard, **kw, **BUDGETS)
    check_simulation(r, t_end)


@settings(SLOW, max_examples=20)
@given(st.one_of(st.none(), st.sampled_from([200, 0, -4, True]), ANYTHING), T_ARG, SIM_KW)
def test_simulate_seeded(small_wave, L, t_end, kw):
    r = outcome(SIM_NAMES, simulate.seeded, small_wave, L=L, t_end=t_end, **kw, **BUDGETS)
    check_simulation(r, t_end)
