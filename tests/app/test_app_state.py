"""ExplorerState and the compute adapter, without a browser.

Reference values are the paper's closed forms for a = -1, b = 10 (Figs. SWs_cubic_DvsQC):
w₊ = 1: V_SK = 2√65/3, c₊ = 3√2, c₋ = 11/2, w₋ = 17/3; w₊ = 6: V_SK = 7√5/3, c₊ = √13,
c₋ = √29; superkink bounds 4.78423 < V < 5.85947 (§6.1).
"""

from __future__ import annotations

import math
import threading
import time

import pytest

pytest.importorskip("panel")

from app import compute  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.url_state import parse_url  # noqa: E402

C2 = 1.0 + 100.0 / 3.0  # c_max² = 1 + b²/(3|a|)
W_STAR = 10.0 / 3.0
CUBIC = compute.laws.law(-1.0, 10.0)  # the paper's law, a = -1, b = 10


def test_defaults_are_valid_and_ranges_follow_the_theory():
    st = ExplorerState()
    assert st.problem() is None
    lo, hi = st.V_range()
    assert lo == pytest.approx(3 * math.sqrt(2), rel=1e-14)
    assert hi == pytest.approx(5.5, rel=1e-14)
    s = st.summary()
    assert s["V_SK"] == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-14)
    assert s["w_star"] == pytest.approx(W_STAR, rel=1e-14)
    assert s["V_lo"] == pytest.approx(4.78423, abs=5e-6)
    assert s["V_hi"] == pytest.approx(5.85947, abs=5e-6)
    assert st.kind() == "tensile"  # c₊ < V = 5 < V_SK at w₊ < w*


def test_superkink_mode_ties_V_and_w_plus():
    st = ExplorerState(mode="superkink", w_plus=1.0)
    assert st.V == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-14)
    assert st.V_range() == pytest.approx((4.78423, 5.85947), abs=5e-6)
    st.V = 5.2  # eq. wpm_cubic: w₊ = w* − √((c_max² − V²)/|a|) on the lower branch
    assert st.w_plus == pytest.approx(W_STAR - math.sqrt(C2 - 5.2**2), rel=1e-13)
    st.w_plus = 6.0  # upper branch: V_SK = 7√5/3
    assert st.V == pytest.approx(7 * math.sqrt(5) / 3, rel=1e-14)
    assert st.kind() == "superkink"


def test_moving_w_plus_keeps_V_inside_the_same_interval():
    st = ExplorerState(w_plus=1.0, V=5.0)  # below V_SK (tensile)
    st.w_plus = 6.0
    cp, vsk = math.sqrt(13), 7 * math.sqrt(5) / 3
    assert cp < st.V < vsk
    assert st.problem() is None
    assert st.kind() == "compressive"  # below V_SK at w₊ > w*: compressive (Fig. SWvelocities)


@pytest.mark.parametrize(
    "params, needle",
    [
        ({"V": 9.0}, "V=9 is out of range"),
        ({"V": 2 * math.sqrt(65) / 3}, "V_SK"),
        ({"w_plus": W_STAR}, "w_plus"),
        ({"w_plus": 50.0}, "w_plus=50 is out of range"),
        ({"a": 1.0}, "a=1 is out of range"),
        ({"b": -2.0}, "b=-2 is out of range"),
    ],
)
def test_invalid_combinations_are_explained(params, needle):
    st = ExplorerState()
    st.param.update(**params)
    msg = st.problem()
    assert msg is not None and needle in msg
    assert st.kind() == "invalid"
    st.summary()  # never raises


def test_pick_sets_both_and_mirrors_negative_V():
    st = ExplorerState()
    st.pick(6.0, -5.3)
    assert (st.w_plus, st.V) == (6.0, 5.3)
    assert st.problem() is None  # 5.3 ∈ (7√5/3, √29): tensile above V_SK
    assert st.kind() == "tensile"


def test_url_query_reproduces_the_state():
    query = dict(a="-1.5", b="8", w_plus="5.5", V="4.1", mode="solitary", tab="phase", N="300")
    values, errors = parse_url(query)
    assert not errors
    st = ExplorerState(**values)
    assert (st.a, st.b, st.w_plus, st.V, st.mode, st.tab, st.N) == (
        -1.5,
        8.0,
        5.5,
        4.1,
        "solitary",
        "phase",
        300,
    )


def test_cache_deduplicates_inflight_work_and_keys_are_exact():
    cache = compute.cache.ResultCache()
    calls = []

    def slow():
        calls.append(1)
        time.sleep(0.2)
        return 42

    out = []
    th = [threading.Thread(target=lambda: out.append(cache.get("k", slow))) for _ in range(4)]
    for t in th:
        t.start()
    for t in th:
        t.join()
    assert len(calls) == 1 and [c.value for c in out] == [42] * 4
    assert sum(c.cached for c in out) == 3
    assert compute.cache.exact(5.0000000000001) != compute.cache.exact(5.0)
    assert compute.cache.exact(5.21749194749) != compute.cache.exact(
        5.2174919476
    )  # Fig. stabSW's two waves


def test_qc_results_are_shared_only_for_identical_inputs():
    compute.CACHE.clear()
    a = compute.run(CUBIC, compute.QCWaveRequest("solitary", 1.0, 5.0))
    b = compute.run(CUBIC, compute.QCWaveRequest("solitary", 1.0, 5.0))
    c = compute.run(CUBIC, compute.QCWaveRequest("solitary", 1.0 + 1e-15, 5.0))
    assert not a.cached and b.cached and a.value is b.value
    assert not c.cached and c.value is not a.value
    assert a.value.amplitude > 0
