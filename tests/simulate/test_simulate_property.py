"""Property test: simulate.riemann and simulate.gaussian driven with
arbitrary inputs, huge and tiny floats included, under small budgets.  Each call either refuses
with a ParameterError naming one of its arguments, or returns a result whose arrays and error
fields are finite (or a stopped run that says why) — never another exception, never a hang."""

import math

import numpy as np
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from fpucore import simulate
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw

LAW = CubicLaw(-1.0, 10.0)
NAMES = {
    "w_left", "w_right", "w_B", "A", "L", "t_end", "n_snapshots", "max_sites_out", "n_probe_t",
    "probes", "late_fraction", "rtol", "method", "initial strain min", "initial strain max",
}  # fmt: skip

WILD_FLOATS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, 1e7, 1e8]),
)
WILD_INTS = st.one_of(st.integers(-5, 10**12), st.sampled_from([0, 1, 2, 17, 10**7, 10**9]))


def mostly(valid, wild):
    """Five parts valid to one part wild, so that some examples get past every check and run."""
    return st.one_of(valid, valid, valid, valid, valid, wild)


strains = mostly(st.floats(-0.5, 7.0), WILD_FLOATS)
common = dict(
    t_end=mostly(st.floats(1e-3, 5.0), WILD_FLOATS),
    L=mostly(st.sampled_from([16, 64, 128, 200]), WILD_INTS),
    n_snapshots=mostly(st.integers(2, 50), WILD_INTS),
    n_probe_t=mostly(st.integers(2, 500), WILD_INTS),
    late_fraction=mostly(st.floats(0.01, 1.0), WILD_FLOATS),
    probes=mostly(st.lists(st.integers(1, 16), max_size=3), st.lists(st.integers(-3, 300))),
)


def _check(call):
    try:
        s = call()
    except ParameterError as e:
        assert e.name in NAMES, str(e)
        event(f"refused: {e.name}")
        return
    event(f"ran: {s.stop_reason}")
    assert s.status in ("ok", "stopped")
    for arr in (s.t, s.snapshots, s.energy, s.final_w, s.probe_series):
        assert np.all(np.isfinite(arr))
    assert math.isfinite(s.energy_drift)
    if s.converged:
        assert math.isfinite(s.error_estimate)
    else:
        assert s.message and s.stop_reason != "ok"


SETTINGS = settings(
    max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow], derandomize=True
)


@SETTINGS
@given(w_left=strains, w_right=strains, **common)
def test_riemann_arbitrary_inputs(w_left, w_right, t_end, L, n_snapshots, n_probe_t,
                                  late_fraction, probes):  # fmt: skip
    _check(
        lambda: simulate.riemann(
            LAW,
            w_left,
            w_right,
            L,
            t_end,
            n_snapshots=n_snapshots,
            n_probe_t=n_probe_t,
            late_fraction=late_fraction,
            probes=probes,
            time_budget_s=0.5,
            memory_budget="256MiB",
            max_sites_out=200,
        )  # fmt: skip
    )


@SETTINGS
@given(w_B=strains, A=mostly(st.floats(-6.0, 6.0), WILD_FLOATS), **common)
def test_gaussian_arbitrary_inputs(w_B, A, t_end, L, n_snapshots, n_probe_t, late_fraction,
                                   probes):  # fmt: skip
    _check(
        lambda: simulate.gaussian(
            LAW,
            w_B,
            A,
            L,
            t_end,
            n_snapshots=n_snapshots,
            n_probe_t=n_probe_t,
            late_fraction=late_fraction,
            probes=probes,
            time_budget_s=0.5,
            memory_budget="256MiB",
            guard="bounded",
            max_sites_out=200,
        )  # fmt: skip
    )
