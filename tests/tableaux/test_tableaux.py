"""The tableau registry: every tableau is validated when it is built, the copied DOP853 data equals
Hairer's coefficients as SciPy ships them, and one lookup serves all three families."""

import numpy as np
import pytest
from scipy.integrate._ivp import dop853_coefficients as scipy_dop  # the source of the copy

from fpucore.errors import ParameterError
from fpucore.tableaux import (
    DOP853,
    DOP853E,
    REGISTRY,
    Tableau,
    check_consistency,
    get,
)

ALL = [(fam, name, tab) for fam, table in REGISTRY.items() for name, tab in table.items()]


def test_copied_dop853_coefficients_equal_the_source_bit_for_bit():
    s = scipy_dop.N_STAGES
    assert np.array_equal(DOP853.A, scipy_dop.A[:s, :s])
    assert np.array_equal(DOP853.B, scipy_dop.B[:s])
    assert np.array_equal(DOP853.C, scipy_dop.C[:s])
    assert np.array_equal(DOP853E.E5, scipy_dop.E5[:13])
    assert np.array_equal(DOP853E.E3, scipy_dop.E3[:13])


@pytest.mark.parametrize("fam,name,tab", ALL, ids=[f"{f}:{n}" for f, n, _ in ALL])
def test_every_registered_tableau_is_consistent_and_read_only(fam, name, tab):
    assert get(fam, name) is tab
    if fam == "rkn":  # Nyström: Σ_j a_ij = c_i²/2, Σ b′ = 1, Σ b = 1/2
        assert np.max(np.abs(tab.A.sum(axis=1) - tab.c**2 / 2)) < 1e-14
        assert abs(tab.bp.sum() - 1) < 1e-14 and abs(tab.b.sum() - 0.5) < 1e-14
        arrays = (tab.A, tab.b, tab.c)
    else:
        assert abs(tab.B.sum() - 1) < 1e-14
        assert np.max(np.abs(tab.A.sum(axis=1) - tab.C)) < 1e-14
        arrays = (tab.A, tab.B, tab.C)
    for a in arrays:
        with pytest.raises(ValueError):
            a[0] = 1.0  # frozen data: a kernel cannot change a coefficient by accident


def test_a_mistyped_coefficient_fails_at_construction():
    A = np.array(DOP853.A, copy=True)
    A[5, 2] += 1e-9
    with pytest.raises(ValueError, match="rows of A miss C"):
        Tableau("bad", A, DOP853.B, DOP853.C, 8)
    B = np.array(DOP853.B, copy=True)
    B[0] += 1e-9
    with pytest.raises(ValueError, match="sum"):
        check_consistency("bad", DOP853.A, B, DOP853.C)
    with pytest.raises(ValueError, match="lower triangular"):
        check_consistency("bad", DOP853.A + np.triu(np.ones((12, 12)), 1), DOP853.B, DOP853.C)


def test_lookup_names_the_valid_choices():
    with pytest.raises(ParameterError, match="rk | embedded | rkn"):
        get("nope", "dop853")
    with pytest.raises(ParameterError, match="rkn12"):
        get("rkn", "dop853")
