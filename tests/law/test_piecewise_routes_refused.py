"""Piecewise-linear laws on routes whose integrators do not locate corner crossings yet: refused
with the reason, never answered with error bars that assume the method's full order."""

import numpy as np
import pytest

import fpucore as F
from fpucore.errors import ParameterError
from fpucore.floquet.monodromy import base_state

LAW = F.TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.5)


def test_discrete_solitary_wave_is_refused_with_the_reason():
    with pytest.raises(ParameterError, match="event location at its corners"):
        F.wave.solitary_spec(LAW, 0.1, 1.05)


def test_simulation_without_event_location_is_refused_with_the_reason():
    with pytest.raises(ParameterError, match="event location at its breakpoints"):
        F.simulate.config.configure(LAW, 200, 1.0, "fixed_strain", "dop853", 1e-8)
    cfg = F.simulate.config.configure(LAW, 200, 1.0, "fixed_strain", "rkn12", 1e-8)
    assert cfg.pwl and cfg.stepper.locate  # the RKN pairs locate the crossings


def test_floquet_is_refused_with_the_reason():
    class Wave:  # the duck-typed wave a Floquet spectrum takes
        law, V, N = LAW, 1.05, 8
        w = np.zeros(8)
        wdot = np.zeros(8)
        w_left = w_right = 0.1

    with pytest.raises(ParameterError, match="Floquet spectra of a piecewise-linear law"):
        base_state(Wave())


def test_qc_of_the_same_law_is_answered():
    sw = F.qc.solitary(LAW, 0.1, 1.05)  # the closed forms need no integrator
    assert np.isfinite(sw.amplitude) and sw.amplitude > 0
