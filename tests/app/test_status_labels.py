"""The words of a scene's status say what each number is.

A model difference (discrete against QC) is not an error; a superkink's amplitude |w₋ − w₊| is
exact (both plateau states are fixed by the Rayleigh line, eq. Rline) rather than "± 0"; a law
other than the cubic has its QC profile by quadrature, not by closed form; a cached result keeps
the cost of its computation.
"""

from __future__ import annotations

import re

import pytest

pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}
QUARTIC = "w + 10*w**2 - w**3 - 0.01*w**4"  # a hardening–softening law that is not the cubic


def profiles(**params):
    st = ExplorerState(**params)
    return st, BY_KEY["profiles"](st)


def line(status: str, head: str) -> str:
    """The status line that starts with **head:**, or ''."""
    for ln in status.split("\n\n"):
        if ln.startswith(f"**{head}:**"):
            return ln
    return ""


def test_discrete_against_qc_is_a_model_difference_not_an_error():
    _, sc = profiles(mode="solitary", w_plus=1.0, V=5.0, N=200, tol=1e-10)
    info = sc.refresh()
    assert sc.last_message is None, sc.last_message
    status = sc.status.object
    assert "discrete − QC" not in line(status, "Error")
    assert "max |discrete − QC|" in line(status, "Model difference")
    ((label, value),) = info.differences
    assert label == "max |discrete − QC|" and 0 < value < 1  # QC and the chain differ, O(1e-2)


def test_superkink_amplitude_is_exact_by_construction():
    _, sc = profiles(mode="superkink", w_plus=1.0, N=200, tol=1e-10)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    shown = sc.last_info.shown
    assert "± 0.0e+00" not in shown
    m = re.search(r"amplitude \|w₋ − w₊\| = ([0-9.]+) \(exact by construction\)", shown)
    assert m and float(m.group(1)) == pytest.approx(17 / 3 - 1, rel=1e-5)  # w₋ = 17/3


@pytest.mark.parametrize("expression,method", [("", "closed form"), (QUARTIC, "quadrature")])
def test_qc_timing_names_how_the_profile_was_computed(expression, method):
    _, sc = profiles(mode="solitary", expression=expression, w_plus=1.0, V=5.0)
    sc.show_discrete.value = False
    sc.wait_idle(30)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    assert f"QC {method}" in line(sc.status.object, "Time")


def test_a_cached_result_keeps_the_cost_of_its_computation():
    st, sc = profiles(mode="solitary", w_plus=1.0, V=5.0, N=204, tol=1e-10)
    compute.CACHE.clear()
    first = sc.refresh()
    computed = dict(first.timings)["discrete N=204"]
    assert not computed.cached and computed.elapsed_s > 0
    st.V = 5.01
    sc.refresh()
    st.V = 5.0
    again = sc.refresh()
    cached = dict(again.timings)["discrete N=204"]
    assert cached.cached and cached.elapsed_s == computed.elapsed_s
    assert "(computed earlier, now from the cache)" in line(sc.status.object, "Time")


def test_simulation_status_names_what_its_error_estimate_estimates():
    st = ExplorerState()
    sc = BY_KEY["simulation"](st)
    sc.kind.value = "gaussian"
    for name, value in dict(L=400, t_end=5.0, w_B=1.0, A=1.0).items():
        getattr(sc, name).value = value
    sc._want_run = True  # what the "Run simulation" button sets
    info = sc.refresh()
    assert sc.last_message is None, sc.last_message
    labels = [k for k, _ in info.errors]
    assert "error estimate" not in labels
    assert "relative energy drift" in labels
    assert "accumulated local error (RMS over the state)" in labels  # rkn12: adaptive
