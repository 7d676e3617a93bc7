"""The explorer with any polynomial law: law selector, URL, cache keys, downloads,
"copy as Python" and every scene's compute path, without a browser.

References are independent of the app and of fpucore's QC module: the quartic's equal-area and
Rayleigh conditions (eqs. Rline, zero_G) and the solitary wave's turning point (eq. TW_QC_gen3,
∫ (f − Rayleigh line) = 0 between w_B and w_M) evaluated here with NumPy's exact polynomial
arithmetic and SciPy's brentq; the sonic speed c₊ = √f′(w₊) (eq. cplus); the paper's cubic
a = −1, b = 10 (V_SK = 2√65/3 at w₊ = 1); and, for "copy as Python", the numbers the scene showed.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import param
import pytest
from numpy.polynomial import polynomial as P
from scipy.optimize import brentq

pytest.importorskip("panel")

from bokeh.document import Document  # noqa: E402

from app import compute  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.state import MAX_URL_LAW, STATE_PARAMS, ExplorerState
from app.url_state import parse_url, url_query
from app.views import SCENES  # noqa: E402
from app.views.formatting import state_stamp  # noqa: E402
from app.views.untrusted import md_literal  # noqa: E402
from fpucore.law import (  # noqa: E402
    CubicLaw,
    PolynomialLaw,
    expression_of,  # noqa: E402
    law_from_expression,
)

ROOT = Path(__file__).resolve().parents[2]
BY_KEY = {cls.key: cls for cls in SCENES}
Q = "w + 10*w**2 - w**3 - 0.01*w**4"
#: f = Σ c_k w^k as NumPy's ascending coefficients (c_0 = 0)
QC = np.array([0.0, 1.0, 10.0, -1.0, -0.01])
V_SK1 = 2 * math.sqrt(65) / 3


def attached(key: str, **params):
    st = ExplorerState(**params)
    sc = BY_KEY[key](st)
    sc.panel.get_root(Document())
    return st, sc


def equal_area_residuals(c: np.ndarray, wp: float, wm: float, V: float) -> tuple[float, float]:
    """(Rayleigh, equal-area) residuals of a superkink (wp, wm, V) for the law with ascending
    coefficients c: f(w₋) − f(w₊) − V²(w₋ − w₊) and ∫_{w₊}^{w₋} (f − line) dw, both exact
    polynomial arithmetic (eqs. Rline, zero_G)."""
    fp = P.polyval(wp, c)
    g = P.polysub(c, [fp - V * V * wp, V * V])  # f(w) − f(w₊) − V²(w − w₊)
    G = P.polyint(g)
    return float(P.polyval(wm, g)), float(P.polyval(wm, G) - P.polyval(wp, G))


def solitary_amplitude(c: np.ndarray, wB: float, V: float, w_hi: float) -> float:
    """Turning point w_M of the QC solitary wave from w_B: the first zero beyond w_B of
    ∫_{w_B}^{w} (f − f(w_B) − V²(s − w_B)) ds (eq. TW_QC_gen3); returns w_M − w_B."""
    fB = P.polyval(wB, c)
    G = P.polyint(P.polysub(c, [fB - V * V * wB, V * V]))

    def h(w):
        return P.polyval(w, G) - P.polyval(wB, G)

    grid = np.linspace(wB + 1e-6, w_hi, 4001)
    vals = h(grid)
    k = int(np.flatnonzero(np.sign(vals[1:]) != np.sign(vals[:-1]))[0])
    return brentq(h, grid[k], grid[k + 1], xtol=1e-15, rtol=1e-15) - wB


# ---------------------------------------------------------------------------- state and URL
def test_state_law_is_the_expressions_polynomial_and_the_url_round_trips():
    st = ExplorerState(expression=Q, w_plus=1.0, V=5.1)
    lw = st.law()
    assert isinstance(lw, PolynomialLaw) and lw.coeffs == (1.0, 10.0, -1.0, -0.01)
    q = url_query(st)
    assert q["law"] == Q and list(q)[:3] == ["a", "b", "law"]
    values, errors = parse_url(q)
    assert errors == []
    again = ExplorerState(**values)
    assert all(getattr(again, n) == getattr(st, n) for n in STATE_PARAMS)
    assert again.law().coeffs == lw.coeffs
    # the cubic keeps its links: no law= at all
    assert "law" not in url_query(ExplorerState())
    assert parse_url({"law": ""}) == ({"expression": ""}, [])


@pytest.mark.parametrize(
    "raw, reason",
    [
        ("w + w**2", "no softening"),  # f′ > 0 for every w > 0
        ("w + 10*w**2 - w**3 +", "could not parse"),
        ("sin(w) + w**2", "'sin' is not allowed"),
        ("x*w + w**2", "unknown name 'x'"),
        ("-w + 10*w**2 - w**3", "f'(0) must be positive"),
        ("w" + " + 0*w**2" * 30, "at most 200 characters"),
    ],
)
def test_invalid_law_in_the_url_is_named_with_its_reason_and_the_rest_kept(raw, reason):
    values, errors = parse_url({"law": raw, "V": "5.1", "N": "200", "tab": "phase"})
    assert values == {"V": 5.1, "N": 200, "tab": "phase"}  # the others are kept
    assert len(errors) == 1 and "law=" in errors[0] and reason in errors[0], errors
    ex = Explorer(ExplorerState(**values), url_errors=errors)
    assert ex.url_alert.visible and "law=" in ex.url_alert.object
    assert ex.state.expression == "" and isinstance(ex.state.law(), CubicLaw)


def test_url_law_limit_is_longer_than_other_values_but_bounded():
    long_ok = "w + 10*w**2 - w**3 - 0.01*w**4" + " + 0*w**5" * 10  # > 40, < 200 characters
    assert 40 < len(long_ok) <= MAX_URL_LAW
    values, errors = parse_url({"law": long_ok})
    assert errors == [] and values["expression"] == long_ok
    values, errors = parse_url({"law": "w" * 5000})
    assert values == {} and "at most 200 characters" in errors[0]


def test_a_new_law_moves_w_plus_and_V_into_its_ranges_and_says_so():
    st = ExplorerState(w_plus=6.5, V=5.0)  # valid w₊ for the cubic (β = 6.716)
    st.expression = Q  # the quartic's superkinks need w₊ < 6.2067
    lo, ws, hi = st.w_plus_range()
    assert lo < st.w_plus < ws and st.problem() is None
    assert "new law" in st.note and "w₊ from 6.5" in st.note
    st = ExplorerState(w_plus=1.0, V=5.0)
    st.expression = Q  # (1, 5) is a tensile wave of the quartic too: nothing moves
    assert (st.w_plus, st.V, st.note) == (1.0, 5.0, "") and st.problem() is None


def test_invalid_expression_state_is_explained_everywhere():
    st = ExplorerState(expression="w + w**2")
    msg = st.problem()
    assert msg is not None and "no softening" in msg
    assert st.kind() == "invalid" and st.summary() == {}
    _, sc = attached("force", expression="w + w**2")
    sc.refresh()
    assert "no softening" in (sc.last_message or "")


# ---------------------------------------------------------------------------- cache keys
def test_cache_keys_tell_the_laws_apart():
    cubic, as_poly = CubicLaw(-1.0, 10.0), PolynomialLaw((1.0, 10.0, -1.0))
    quartic = compute.laws.expression_law(Q)
    keys = {compute.laws.law_key(lw) for lw in (cubic, as_poly, quartic)}
    assert len(keys) == 3  # the same cubic by two routes is two entries
    req = compute.WaveRequest("solitary", 1.0, 5.0, 200, 1e-10)
    wk = {compute.job_key(lw, req) for lw in (cubic, quartic)}
    assert len(wk) == 2
    qc_c = compute.run(cubic, compute.QCWaveRequest("solitary", 1.0, 5.0)).value
    qc_q = compute.run(quartic, compute.QCWaveRequest("solitary", 1.0, 5.0)).value
    assert qc_c is not qc_q and qc_c.amplitude != qc_q.amplitude
    # the closed form and the general route agree for the cubic (fpucore's ≤ 1e-12 contract)
    qc_p = compute.run(as_poly, compute.QCWaveRequest("solitary", 1.0, 5.0)).value
    assert qc_p.amplitude == pytest.approx(qc_c.amplitude, rel=1e-12)
    # keys are exact: a coefficient 1e-15 away is another law
    other = compute.laws.expression_law("w + 10*w**2 - w**3 - 0.010000000000000002*w**4")
    assert compute.laws.law_key(other) != compute.laws.law_key(quartic)


def test_changing_the_law_makes_every_scene_stale_and_redraws_the_force_law():
    st, sc = attached("force")
    sc.refresh()
    y_cubic = np.array(sc.r_f[1].data["y"])
    st.expression = Q
    assert all("expression" in cls.depends for cls in SCENES)
    sc.refresh()
    y_quartic = np.array(sc.r_f[1].data["y"])
    assert y_cubic.shape != y_quartic.shape or not np.allclose(y_cubic, y_quartic)
    assert "law=" + md_literal(Q) in sc.status.object


# ---------------------------------------------------------------------------- explorer widgets
def test_law_selector_switches_between_cubic_and_expression():
    ex = Explorer()
    law = ex.law_editor
    assert law.law_kind.value == "cubic" and law.a.visible and not law.law_text.visible
    law.law_kind.value = "expression"  # starts from the current cubic as a polynomial
    assert ex.state.expression == "w + 10.0*w**2 - w**3"
    assert ex.state.law().coeffs == (1.0, 10.0, -1.0)
    assert not law.a.visible and law.law_text.visible and len(law.coeff_sliders) == 3
    law.law_text.value = Q
    assert ex.state.expression == Q and len(law.coeff_sliders) == 4
    assert [s.value for s in law.coeff_sliders] == [1.0, 10.0, -1.0, -0.01]
    # the w₊ and V sliders follow the quartic's ranges (fpucore's general QC)
    lo, ws, hi = ex.state.w_plus_range()
    assert ex.w_plus.start == pytest.approx(lo, abs=1e-5 * (hi - lo))
    assert ex.w_plus.end == pytest.approx(hi, abs=1e-5 * (hi - lo))
    cp, _, cm = ex.state.speeds()
    assert (ex.V.start, ex.V.end) == (pytest.approx(cp), pytest.approx(cm))
    assert cp == pytest.approx(math.sqrt(P.polyval(1.0, P.polyder(QC))), rel=1e-14)  # eq. cplus
    law.law_kind.value = "cubic"
    assert ex.state.expression == "" and isinstance(ex.state.law(), CubicLaw)
    law.law_kind.value = "expression"  # back to the last expression
    assert ex.state.expression == Q


def move(slider, value: float) -> None:
    """What a slider drag ends with: value, then value_throttled."""
    slider.value = value
    with param.edit_constant(slider):
        slider.value_throttled = value


def test_coefficient_slider_rewrites_the_expression_and_the_law():
    ex = Explorer(ExplorerState(expression=Q))
    law = ex.law_editor
    c4 = law.coeff_sliders[3]
    assert c4.start <= -0.01 <= c4.end and c4.start < 0 < c4.end  # its sign can change
    move(c4, -0.02)
    assert ex.state.expression == "w + 10.0*w**2 - w**3 - 0.02*w**4"
    assert ex.state.law().coeffs == (1.0, 10.0, -1.0, -0.02)
    assert law.law_text.value == ex.state.expression
    assert (c4.start, c4.end) == (-0.03, 0.01)  # ranges stay anchored to the typed law
    # a move out of the law class: refused with its reason, the previous law stays on screen,
    # and the sliders stay to move back
    move(law.coeff_sliders[0], 0.0)  # f′(0) = 0: refused by fpucore
    assert "f'(0) must be positive" in law.refused and law.refusal.visible
    assert ex.state.expression == "w + 10.0*w**2 - w**3 - 0.02*w**4"
    assert ex.state.problem() is None and law.coeff_box.visible
    move(law.coeff_sliders[0], 1.0)
    move(law.coeff_sliders[2], -1.0)
    assert ex.state.law().coeffs == (1.0, 10.0, -1.0, -0.02) and ex.state.problem() is None


def test_typed_invalid_expression_is_refused_and_the_law_stays():
    ex = Explorer(ExplorerState(expression=Q))
    law = ex.law_editor
    law.law_text.value = "w + 10*w**2 - w**3 +"
    t_end = time.monotonic() + 60.0
    while not law.refused and time.monotonic() < t_end:  # built in the law worker
        time.sleep(0.05)
    assert "could not parse" in law.refused and law.refusal.visible
    assert ex.state.expression == Q and ex.state.problem() is None and law.coeff_box.visible
    assert all(s.copy_btn.disabled for s in ex.scenes)
    law.law_kind.value = "cubic"  # a valid law clears the refusal
    assert not law.refusal.visible and ex.state.problem() is None
    assert not any(s.copy_btn.disabled for s in ex.scenes)


def test_a_typed_law_is_named_as_being_checked_until_the_law_worker_has_built_it():
    """The law editor names a typed law while the law worker builds it (the page shows it in
    the sidebar), then applies it: state, coefficient sliders and the sidebar's ranges."""
    ex = Explorer()
    law = ex.law_editor
    text = "w + 9.25*w**2 - w**3"  # typed nowhere else: not built yet
    assert compute.laws.lookup_law(text) is None
    law.law_kind.value = "expression"
    # every text of the sidebar's ranges pane, recorded (a warm law worker answers within ms)
    shown: list[str] = []
    ex.ranges.param.watch(lambda e: shown.append(e.new), "object")
    law.law_text.value = text

    def coefficients() -> list[float]:
        return [s.value for s in law.coeff_sliders]

    # applied in the law worker's watcher thread: wait until the sidebar has followed it
    t_end = time.monotonic() + 60.0
    while time.monotonic() < t_end and (
        "checking" in ex.ranges.object or coefficients() != [1.0, 9.25, -1.0]
    ):
        time.sleep(0.05)
    assert shown and shown[0] == f"_checking the law {md_literal(text)} …_", shown
    assert ex.state.expression == text, ex.ranges.object
    assert coefficients() == [1.0, 9.25, -1.0], ex.ranges.object
    assert "checking" not in ex.ranges.object and "w₊ ∈ (α, β)" in ex.ranges.object


@pytest.mark.parametrize(
    "coeffs",
    [(1.0, 10.0, -1.0, -0.01), (1.0, 10.059999999999999, -1.0, 0.0, 1e-05), (0.3, 3.0, -0.1)],
)
def test_expression_of_parses_back_to_the_same_doubles(coeffs):
    text = expression_of(coeffs)
    assert text == PolynomialLaw(coeffs).expression
    assert law_from_expression(text).coeffs == coeffs


# ---------------------------------------------------------------------------- downloads, stamp
def test_download_header_and_stamp_name_the_law():
    st, sc = attached("force", expression=Q)
    sc.refresh()
    _, buf = sc.download_data()
    head = [ln for ln in buf.getvalue().splitlines() if ln.startswith("#")]
    assert any(f"law={Q!r}" in ln and "(1.0, 10.0, -1.0, -0.01)" in ln for ln in head), head
    assert any(f"law = fpucore.law_from_expression({Q!r})" in ln for ln in head)
    assert state_stamp(st).endswith(f"mode=solitary law={Q}")
    assert "a=" not in state_stamp(st) and "b=" not in state_stamp(st)  # unused by the law
    assert "law=" not in state_stamp(ExplorerState())


# ---------------------------------------------------------------------------- copy as Python
def run_code(code: str) -> list[str]:
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300
    )
    assert out.returncode == 0, out.stderr[-2000:]
    return out.stdout.splitlines()


def test_copy_as_python_builds_the_law_and_reproduces_the_force_scene():
    st, sc = attached("force", expression=Q, w_plus=1.0)
    sc.refresh()
    code = sc.code.value
    assert f"law = fpucore.law_from_expression({Q!r})" in code
    lines = run_code(code)
    V, wm, _ = (float(x) for x in lines[1].split())
    sk = compute.run(
        st.law(), compute.QCWaveRequest("superkink", 1.0, st.V)
    ).value  # what the scene drew
    assert (V, wm) == (sk.V, sk.w_minus)
    # independent: the equal-area and Rayleigh conditions hold for (1, w₋, V)
    r_line, area = equal_area_residuals(QC, 1.0, wm, V)
    assert abs(r_line) < 1e-11 and abs(area) < 1e-10
    assert abs(1.0 + wm - 2 * st.law().w_star) > 0.03  # no cubic symmetry (docs/general_law.md)


def test_copy_as_python_reproduces_the_discrete_profile():
    st, sc = attached("profiles", expression=Q, N=120, tol=1e-8)
    sc.refresh()
    assert sc.last_message is None and sc._discrete is not None
    code = sc.code.value
    lines = run_code(code)
    conv, res, amp = lines[-1].split()
    assert conv == "True" and float(amp) == pytest.approx(sc._discrete.amplitude, rel=1e-12)


# ---------------------------------------------------------------------------- every scene
def test_force_scene_draws_the_quartics_superkink():
    st, sc = attached("force", expression=Q)
    info = sc.refresh()
    assert sc.last_message is None and info is not None
    x = np.array(sc.r_sk[1].data["x"])
    y = np.array(sc.r_sk[1].data["y"])
    V2 = (y[1] - y[0]) / (x[1] - x[0])
    r_line, area = equal_area_residuals(QC, float(x.min()), float(x.max()), math.sqrt(V2))
    assert abs(area) < 1e-9 and abs(r_line) < 1e-9


def test_phase_and_profiles_scenes_show_the_quartics_solitary_wave():
    ref = solitary_amplitude(QC, 1.0, 5.0, 6.2)
    st, sc = attached("phase", expression=Q)
    assert sc.refresh() is not None and "tensile solitary wave" in sc.last_info.shown
    st, sc = attached("profiles", expression=Q, N=120, tol=1e-8)
    sc.show_discrete.value = False
    sc.refresh()
    assert sc.last_message is None
    y = np.array(sc.r_qc[1].data["y"])
    assert y.max() - 1.0 == pytest.approx(ref, abs=1e-8)  # QC profile's peak (1601 points)


def test_diagram_scene_for_the_quartic():
    st, sc = attached("diagram", expression=Q)
    sc.refresh()
    assert sc.last_message is None
    c_plus = math.sqrt(P.polyval(1.0, P.polyder(QC)))
    assert sc._fam.c_plus == pytest.approx(c_plus, rel=1e-13)
    # the existence diagram is not symmetric about w* (no cubic mirror symmetry)
    d = sc._exist
    ws = d.w_star
    left = np.interp(ws - 1.5, d.w_plus, d.V_SK)
    right = np.interp(ws + 1.5, d.w_plus, d.V_SK)
    assert abs(left - right) > 1e-3


@pytest.mark.parametrize("mode", ["solitary", "superkink"])
def test_floquet_scene_for_the_quartic(mode):
    st, sc = attached("floquet", expression=Q, N=100, tol=1e-8, mode=mode)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    assert len(sc.r_mu[1].data["x"]) == 200  # 2N multipliers
    assert sc._fr.symmetry_error < 1e-8  # Hamiltonian quartets
    assert "law=" + md_literal(Q) in sc.status.object


def test_simulation_scene_for_the_quartic_seeded_and_its_code():
    st, sc = attached("simulation", expression=Q, N=120, tol=1e-8)
    sc.kind.value = "riemann"
    sc.L.value, sc.t_end.value = 300, 5.0
    sc._want_run = True
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    req, sim = sc._sim
    assert req.kind == "riemann" and sim.waves
    assert f"law = fpucore.law_from_expression({Q!r})" in sc.code.value
    assert "simulate.riemann(law, " in sc.code.value


def test_atlas_scene_runs_a_tiny_atlas_for_the_quartic():
    st, sc = attached("atlas", expression=Q)
    sc.n_w.value, sc.n_V.value, sc.N_run.value = 2, 2, 80
    sc._want_run = True
    sc.refresh()
    assert sc.last_message is None or "no max" in sc.last_message, sc.last_message
    w = sc.atlas_data.w_plus
    lo, _, hi = st.w_plus_range()
    assert lo < w.min() and w.max() < hi  # rows inside the quartic's w₊ range


def test_top_coefficient_to_zero_keeps_its_slider_and_other_state_changes_keep_the_sliders():
    ex = Explorer(ExplorerState(expression=Q))
    law = ex.law_editor
    sliders = list(law.coeff_sliders)
    ex.state.w_plus = 1.2  # not a law change: the same slider widgets
    assert law.coeff_sliders == sliders
    move(law.coeff_sliders[3], 0.0)  # the cubic again, as a polynomial
    assert ex.state.law().coeffs == (1.0, 10.0, -1.0)
    assert law.coeff_sliders == sliders and law.coeff_sliders[3].value == 0.0
    move(law.coeff_sliders[3], -0.01)
    assert ex.state.law().coeffs == (1.0, 10.0, -1.0, -0.01)
