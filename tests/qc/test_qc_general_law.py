"""The public QC functions dispatch on the law: the cubic object keeps its closed
forms, any other law goes through fpucore.qc.general.  References: the closed forms (the cubic
written as a polynomial must reproduce them), the first integral (eq. TW_QC_gen3) on the
highlighted phase-plane orbits, and the ordering c₊ < V_SK < c₋ of paper §3."""

import json

import numpy as np
import pytest

from fpucore import CubicLaw, ParameterError, law_from_expression, qc
from fpucore.qc import closed_forms, general
from fpucore.result import STATUSES, Result, jsonable

QUARTIC = law_from_expression("w + 10*w**2 - w**3 - 0.01*w**4")
CUBIC = CubicLaw(-1.0, 10.0)
CUBIC_POLY = CUBIC.as_polynomial()


def test_dispatch_keeps_closed_forms_for_the_cubic_object():
    assert qc.is_closed_form(CUBIC) and not qc.is_closed_form(CUBIC_POLY)
    assert type(qc.solitary(CUBIC, 1.0, 5.0)) is qc.QCSolitary
    sw = qc.solitary(CUBIC_POLY, 1.0, 5.0)
    assert isinstance(sw, general.QCSolitaryGeneral) and isinstance(sw, qc.QCSolitary)
    sk = qc.superkink_from_V(QUARTIC, 5.2, "upper")
    assert isinstance(sk, qc.QCSuperkink) and sk.converged and sk.status == "ok"
    d = sk.as_dict()
    assert {"V_error", "w_minus_error", "xi_error", "symmetry_defect"} <= set(d)
    assert "tables" not in d and "law" not in d  # as for the closed forms (EXCLUDE)


def test_existence_diagram_cubic_both_routes():
    a = qc.diagram.existence_diagram(CUBIC, n=60)
    b = qc.diagram.existence_diagram(CUBIC_POLY, n=60)
    assert np.max(np.abs(a.w_plus - b.w_plus)) < 1e-12
    for k in ("c_plus", "V_SK", "c_minus"):
        assert np.max(np.abs(getattr(a, k) - getattr(b, k))) < 1e-12


def test_existence_diagram_quartic_is_not_symmetric_about_w_star():
    d = qc.diagram.existence_diagram(QUARTIC, n=80)
    assert np.all(d.c_plus < d.V_SK) and np.all(d.V_SK < d.c_minus)
    ws = QUARTIC.w_star
    for e in (0.5, 1.5, 2.5):  # the cubic's V_SK(w* − e) = V_SK(w* + e); not so here
        lo, hi = qc.sound_speeds(QUARTIC, ws - e), qc.sound_speeds(QUARTIC, ws + e)
        assert abs(lo[1] - hi[1]) > 1e-4 and abs(lo[0] - hi[0]) > 1e-4  # errors ~1e-14
    c = qc.sound_speeds(CUBIC, CUBIC.w_star - 1.5), qc.sound_speeds(CUBIC, CUBIC.w_star + 1.5)
    assert np.allclose(c[0], c[1], rtol=1e-14)


def test_solitary_family_cubic_general_route_vs_closed_forms():
    """The general route's family at its own velocities (they differ from the closed-form grid
    by round-off in c₊, V_SK, c₋) against the closed form at the same velocities."""
    b = qc.diagram.solitary_family(CUBIC_POLY, 1.0, n=40)
    for side in ("below", "above"):
        V = getattr(b, f"V_{side}")
        assert V.size == 40
        w_B = np.full_like(V, 1.0) if side == "below" else qc.w_S(CUBIC, 1.0, V)
        dM, _, _, E, err, ok = closed_forms.solitary_closed_form(CUBIC, w_B, V)
        assert np.all(ok)
        assert np.max(np.abs(getattr(b, f"amp_{side}") - np.abs(dM))) < 1e-9
        assert np.all(np.abs(getattr(b, f"energy_{side}") - E) <= b.max_energy_error + err)
    assert (b.kind_below, b.kind_above) == ("tensile", "compressive")


def test_quartic_tensile_and_compressive_families_are_not_mirror_images():
    """For the cubic, w₊ and its partner 2w* − w₊ carry the same velocity intervals with the
    kinds swapped; for the quartic the partner's intervals differ."""
    for law in (CUBIC, QUARTIC):
        sk = qc.superkink_from_w_plus(law, 1.0)
        (cp, vsk), (_, cm) = qc.solitary_intervals(law, 1.0)
        (cp2, vsk2), (_, cm2) = qc.solitary_intervals(law, sk.w_minus)
        gap = max(abs(vsk - vsk2), abs(cp - cp2), abs(cm - cm2))
        assert gap < 1e-12 if law is CUBIC else gap > 1e-3


@pytest.mark.parametrize("V", [5.0, 5.35, None])
def test_quartic_phase_plane_orbits_lie_on_the_first_integral(V):
    V = qc.sound_speeds(QUARTIC, 1.0)[1] if V is None else V
    p = qc.phase.phase_plane(QUARTIC, 1.0, V)
    assert p.regime == {5.0: "tensile", 5.35: "compressive"}.get(V, "superkink")
    assert p.orbit_residual < 1e-12
    assert [c.kind for c in p.critical_points].count("saddle") == 2


def test_general_route_refusals_name_the_argument():
    with pytest.raises(ParameterError) as e:
        qc.superkink_from_V(QUARTIC, 6.0)
    assert e.value.name == "V"
    with pytest.raises(ParameterError) as e:
        qc.solitary(QUARTIC, QUARTIC.w_star, 5.0)
    assert e.value.name == "w_plus"


def test_general_results_speak_the_result_protocol():
    for res in (
        general.speeds(QUARTIC, 1.0),
        qc.superkink_from_w_plus(QUARTIC, 1.0),
        qc.solitary(QUARTIC, 1.0, 5.35),
    ):
        assert isinstance(res, Result) and res.status in STATUSES and res.converged
        assert res.ERROR_FIELDS and all(np.isfinite(v) for v in res.errors().values())
        d = res.as_dict()
        assert all(k in d for k in ("status", "elapsed_s", *res.ERROR_FIELDS))
        json.dumps(jsonable(d))
