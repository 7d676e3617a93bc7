"""Validation gaps of the simulations, each a regression test that failed
before: arguments out of range are refused naming the argument (never a wrong run, an IndexError
or an AttributeError), and the shape check after K whole periods is never silently skipped."""

import math

import numpy as np
import pytest

from fpucore import simulate
from fpucore.errors import ParameterError
from fpucore.law import CubicLaw
from fpucore.simulate import schedule

LAW = CubicLaw(-1.0, 10.0)


@pytest.mark.parametrize("late_fraction", [-1.0, 0.0, 1.5, float("nan"), "x"])
def test_late_fraction_out_of_range_is_refused(late_fraction):
    """late_fraction = −1 put the tracking window at [2 t_end, t_end]: the run went on to
    t = 10 when asked for t_end = 5."""
    with pytest.raises(ParameterError) as e:
        simulate.riemann(LAW, 4.6, 0.0, 200, 5.0, late_fraction=late_fraction)
    assert e.value.name == "late_fraction"


def test_late_fraction_one_tracks_the_whole_run_and_stops_at_t_end():
    s = simulate.riemann(LAW, 4.6, 0.0, 400, 5.0, late_fraction=1.0)
    assert s.success and s.t_final == 5.0 and s.t[-1] == 5.0


@pytest.mark.parametrize("n_probe_t", [0, -1, 1, 2.5, "many", None, 10**9])
def test_n_probe_t_out_of_range_names_the_argument(n_probe_t):
    """n_probe_t = 0 raised IndexError, −1 ValueError (from numpy), 10**9 allocated 7.7 GB."""
    with pytest.raises(ParameterError) as e:
        simulate.riemann(LAW, 4.6, 0.0, 200, 1.0, probes=(10,), n_probe_t=n_probe_t)
    assert e.value.name == "n_probe_t"


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(probes=("a",)), "probes"),
        (dict(probes=(1.5,)), "probes"),
        (dict(probes=(201,)), "probes"),
        (dict(probes=5), "probes"),
        (dict(n_snapshots="abc"), "n_snapshots"),
        (dict(n_snapshots=2.5), "n_snapshots"),
        (dict(max_sites_out=None), "max_sites_out"),
        (dict(max_steps=1.5), "max_steps"),
        (dict(progress=42), "progress"),
    ],
)
def test_other_arguments_name_themselves(kwargs, name):
    with pytest.raises(ParameterError) as e:
        simulate.riemann(LAW, 4.6, 0.0, 200, 1.0, **kwargs)
    assert e.value.name == name


@pytest.mark.parametrize("r", [None, object(), 5.2, "superkink"])
def test_seeded_without_a_wave_is_refused(r):
    """simulate.seeded(None) raised AttributeError ('NoneType' object has no attribute 'V')."""
    with pytest.raises(ParameterError) as e:
        simulate.seeded(r)
    assert e.value.name == "r" and "traveling wave" in str(e.value)


# --------------------------------------------------------------------------- shape check
VELOCITIES = np.linspace(4.79, 5.85, 20001)  # the superkink interval of the paper's law


@pytest.mark.parametrize("periods", [1.0, 5.0, 50.0, 123.0, 7.5])
def test_whole_periods_are_always_in_the_schedule(periods):
    """t_end = periods/V and T = 1/V: K·T exceeds t_end by an ulp for ~10 % of velocities
    (fpu simulate wave superkink --V 4.805 --json had no shape_error).  For every velocity the
    K whole periods are counted and their time is a stop of the run (at most 1e-12 relative from
    K·T)."""
    over = 0
    for V in VELOCITIES:
        t_end, T = periods / V, 1.0 / V
        K, t_K = simulate.whole_periods(t_end, T)
        assert K == math.floor(periods)
        over += t_K > t_end
        sch = schedule.output_schedule(t_end, 200, 1.0 / 3.0, 41, True, (t_K,))
        assert sch.t_extra.size == 1 and sch.t_extra[0] <= t_end
        assert abs(sch.t_extra[0] - t_K) <= 1e-12 * t_end
        assert float(sch.t_extra[0]) in sch.ext and sch.t_extra[0] in sch.stops
    if periods != int(periods) or periods == 1.0:
        assert over == 0
    else:
        assert over > 0.05 * VELOCITIES.size  # the case the fix is about does occur


def test_schedule_refuses_times_it_cannot_reach():
    """An extra time beyond rounding of t_end (or ≤ 0) is an error, not silently dropped."""
    for bad in (1.0 + 1e-9, 2.0, 0.0, -1.0):
        with pytest.raises(ValueError):
            schedule.output_schedule(1.0, 10, 0.5, 5, True, (bad,))


def test_whole_periods_just_short_of_t_end():
    """t_end a little more than rounding short of K periods counts K − 1 whole periods."""
    T = 1.0 / 4.805
    assert simulate.whole_periods(50 * T * (1 - 1e-10), T)[0] == 49
    assert simulate.whole_periods(50 * T * (1 - 1e-14), T)[0] == 50
    assert simulate.whole_periods(0.5 * T, T) == (0, 0.0)


wave = pytest.importorskip("fpucore.wave")


@pytest.mark.parametrize("V", [4.805, 5.317])
def test_seeded_shape_error_present_where_k_periods_overshoot_t_end(V):
    """V = 4.805 (a reported case) and another velocity where 50·(1/V) > 50/V: the shape error
    after 50 periods is reported, and it is small (reference: the initial profile shifted by
    50 sites, eq. period)."""
    assert 50 * (1.0 / V) > 50.0 / V  # the overshooting case
    r = wave.solve_superkink(LAW, V)
    assert r.converged, r.message
    s = simulate.seeded(r, t_end=50.0 / V, n_snapshots=20)
    assert s.success, s.message
    assert s.details["periods"] == 50
    assert "shape_error" in s.details
    assert s.details["shape_error"] < 1e-6
