"""Piecewise-linear laws on every route: the routes whose integrators locate the corner
crossings answer (discrete waves, Floquet spectra, the RKN simulations, the QC closed forms);
a simulation method that does not locate them is refused with the reason, never answered with
error bars that assume the method's full order."""

import numpy as np
import pytest

import fpucore as F
from fpucore.errors import ParameterError
from fpucore.floquet.monodromy import base_state

LAW = F.TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.5)


def test_simulation_without_event_location_is_refused_with_the_reason():
    with pytest.raises(ParameterError, match="event location at its breakpoints"):
        F.simulate.config.configure(LAW, 200, 1.0, "fixed_strain", "dop853", 1e-8)
    cfg = F.simulate.config.configure(LAW, 200, 1.0, "fixed_strain", "rkn12", 1e-8)
    assert cfg.pwl and cfg.stepper.locate  # the RKN pairs locate the crossings


def test_discrete_waves_and_floquet_are_answered():
    """No longer refused: the period map, its tangent and the monodromy locate the crossings
    (tests/wave/test_wave_piecewise.py, tests/floquet/test_floquet_piecewise.py)."""
    spec = F.wave.solitary_spec(LAW, 0.1, 1.05)
    assert spec.law is LAW

    class Wave:  # the duck-typed wave a Floquet spectrum takes
        law, V, N = LAW, 1.05, 8
        w = np.zeros(8)
        wdot = np.zeros(8)
        w_left = w_right = 0.1

    assert base_state(Wave())[0] is LAW


def test_qc_of_the_same_law_is_answered():
    sw = F.qc.solitary(LAW, 0.1, 1.05)  # the closed forms need no integrator
    assert np.isfinite(sw.amplitude) and sw.amplitude > 0
