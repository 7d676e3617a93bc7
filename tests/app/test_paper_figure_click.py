"""A click on a paper figure sets the whole view: the state (tab, law, mode, w₊, V, N), the held
curves of the families of profiles, the Simulation scene's initial data, and the URL's ``fig``
that reproduces all of it.  Expected values are the paper's (its captions and text; the
families' velocities are those fpucore.paper draws, noted per figure), checked against closed
forms evaluated here, independently of fpucore."""

from __future__ import annotations

import math

import pytest

pytest.importorskip("panel")

from app.explorer import Explorer  # noqa: E402
from app.paper_figures import FIGURE_SCENARIO  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.url_state import state_from_url, url_query  # noqa: E402
from app.views.simulation import SimulationScene  # noqa: E402
from fpucore import paper  # noqa: E402

SQ65 = math.sqrt(65)


def v_sk(w_plus: float, a: float = -1.0, b: float = 10.0) -> float:
    """eq. cubic_cond2 (the superkink's velocity for w₊), evaluated here."""
    return math.sqrt(1 + b * b / (3 * abs(a)) - abs(a) * (w_plus - b / (3 * abs(a))) ** 2)


def speeds(w_plus: float) -> tuple[float, float, float]:
    """(c₊, V_SK, c₋) as the paper prints them (captions of Figs. SWs_cubic_DvsQC,
    SWamp_cubic_DvsQC) for the two w₊ it uses, 1 and 6."""
    return {
        1.0: (3 * math.sqrt(2), 2 * SQ65 / 3, 11 / 2),
        6.0: (math.sqrt(13), 7 * math.sqrt(5) / 3, math.sqrt(29)),
    }[w_plus]


#: label → (tab, mode, w₊ (None: from the superkink's V), V of the current wave (the paper's),
#: the velocities of the held family (the rest of the figure's family))
PAPER = {
    # Fig. superkink: the superkink at the running example w₊ = 1, V_SK = 2√65/3
    "superkink": ("force", "superkink", 1.0, 2 * SQ65 / 3, ()),
    # Fig. pplane (a): w₊ = 1, V = V_SK − 0.001
    "pplane": ("phase", "solitary", 1.0, 2 * SQ65 / 3 - 0.001, ()),
    # Fig. cubic (b): QC superkink profiles; fpucore.paper draws V = 4.9, 5.2, 5.5, 5.8
    "cubic": ("profiles", "superkink", None, 4.9, (5.2, 5.5, 5.8)),
    # Fig. SWvelocities_cubic: velocities against w₊ (the diagram), at w₊ = 1
    "SWvelocities_cubic": ("diagram", "solitary", 1.0, 5.0, ()),
    # Fig. SWs_cubic (a), (b) at w₊ = 1: V = 4.5, 5.0, 5.3, 5.37 | 5.38, 5.42, 5.46
    "SWs_cubic": ("profiles", "solitary", 1.0, 5.0, (4.5, 5.3, 5.37, 5.38, 5.42, 5.46)),
    "SWamp_energy_QCcubic": ("diagram", "solitary", 1.0, 5.0, ()),
    # Fig. TWcubic: superkinks V = 4.8, 5.0, 5.2, 5.4, 5.6, 5.8
    "TWcubic": ("profiles", "superkink", None, 5.2, (4.8, 5.0, 5.4, 5.6, 5.8)),
    # Fig. SWs_cubic_DvsQC (a), (b) at w₊ = 1: V = 4.6, 5.2, 5.37 | 5.38, 5.43, 5.48
    "SWs_cubic_DvsQC": ("profiles", "solitary", 1.0, 5.2, (4.6, 5.37, 5.38, 5.43, 5.48)),
    # Figs. SWamp/SWenergy_cubic_DvsQC (b): w₊ = 6
    "SWamp_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, ()),
    "SWenergy_cubic_DvsQC": ("diagram", "solitary", 6.0, 5.0, ()),
    # Figs. floquet_SK, Floquet_example: the superkink V = 5.2
    "floquet_SK": ("floquet", "superkink", None, 5.2, ()),
    "Floquet_example": ("floquet", "superkink", None, 5.2, ()),
    # Fig. stabSK (b): the superkink V = 5.2
    "stabSK": ("simulation", "superkink", None, 5.2, ()),
    # Fig. Riemann1 (c): the superkink V = 5.7209 behind which w_B = 2.0667 (= w₊ = 20/3 − 4.6)
    "Riemann1": ("simulation", "superkink", 20 / 3 - 4.6, 5.7209, ()),
    # Fig. floquet_cubicSW (a): w₊ = 1 (a compressive wave above V_SK)
    "floquet_cubicSW": ("floquet", "solitary", 1.0, 5.38, ()),
    # Fig. stabSW (b): w₊ = 6, V = 5.2174919476 (a tensile wave)
    "stabSW": ("simulation", "solitary", 6.0, 5.2174919476, ()),
    # Fig. SWdyn (a): the Gaussian run forms solitary waves V = ±5.2494 on w_B = 1
    "SWdyn": ("simulation", "solitary", 1.0, 5.2494, ()),
}


def test_the_table_covers_all_17_figures():
    assert set(PAPER) == set(paper.LABELS) and len(PAPER) == 17


@pytest.mark.parametrize("label", list(PAPER))
def test_a_click_sets_the_papers_state_held_family_and_url(label):
    tab, mode, w_plus, V, family = PAPER[label]
    ex = Explorer()
    ex.state.param.update(a=-2.0, b=12.0, mode="solitary", V=4.0, w_plus=0.5, N=200)
    ex.state.held = []
    ex.by_key["paper"].buttons[label].clicks += 1  # the user clicks
    st = ex.state
    # N = 500, except the seeded runs: fpucore.paper's wave (N = 64, tol = 1e-12)
    N, tol_ = (64, 1e-12) if label in ("stabSK", "stabSW") else (500, 1e-10)
    assert (st.a, st.b, st.expression, st.tab, st.mode, st.N) == (-1.0, 10.0, "", tab, mode, N)
    assert st.tol == tol_
    assert st.problem() is None and st.figure == label
    tol = 5e-5 if label == "Riemann1" else 1e-9  # the caption prints V = 5.7209
    assert st.V == pytest.approx(V, abs=tol)
    if w_plus is not None:
        assert st.w_plus == pytest.approx(w_plus, abs=1e-12)
    if mode == "superkink":
        assert v_sk(st.w_plus) == pytest.approx(st.V, abs=1e-12) and st.w_plus < 10 / 3
    else:
        cp, vsk, cm = speeds(st.w_plus)
        assert cp < st.V < vsk or vsk < st.V < cm
    # the held family: its velocities, each a wave of the figure (superkinks on the lower
    # branch, w₊ < w* = b/(3|a|), as drawn; solitary waves at the figure's w₊)
    held_V = []
    for h in st.held:
        assert h.mode == mode
        if mode == "superkink":
            assert h.w_plus < 10 / 3
            held_V.append(v_sk(h.w_plus))
        else:
            assert h.w_plus == st.w_plus
            held_V.append(h.V)
    assert held_V == pytest.approx(list(family), abs=1e-12)
    assert len(st.held) <= 6
    # the URL carries the figure and its held curves; it rebuilds exactly this state
    q = url_query(st)
    assert q["fig"] == label and ("hold" in q) == bool(family)
    again, errors = state_from_url(q)
    assert errors == []
    for name in ("a", "b", "expression", "tab", "mode", "w_plus", "V", "N", "held", "figure"):
        assert getattr(again, name) == getattr(st, name), name
    # a link with only ``fig`` gives the same view
    alone, errors = state_from_url({"fig": label})
    assert errors == [] and url_query(alone) == q
    assert (alone.scenario is None) == (label not in FIGURE_SCENARIO)


def test_an_unknown_figure_is_refused_listing_the_valid_ones():
    st, errors = state_from_url({"fig": "Riemann2", "V": "5.1"})
    assert st.V == 5.1 and st.figure == ""
    assert len(errors) == 1 and errors[0].startswith("URL value ignored: fig='Riemann2'")
    assert all(label in errors[0] for label in PAPER)


def test_a_link_that_changes_the_figures_state_keeps_the_change_and_drops_fig():
    st, errors = state_from_url({"fig": "SWs_cubic", "V": "5.1"})
    assert not errors and st.V == 5.1 and st.figure == "" and "fig" not in url_query(st)
    assert [h.V for h in st.held] == [4.5, 5.3, 5.37, 5.38, 5.42, 5.46]  # the family stays
    st, _ = state_from_url({"fig": "SWs_cubic", "tab": "phase"})  # another tab: same view
    assert st.figure == "SWs_cubic" and st.tab == "phase"


def test_moving_a_slider_leaves_the_figure():
    st = ExplorerState()
    st.show_figure("TWcubic")
    assert st.figure == "TWcubic"
    st.tab = "phase"  # looking at another scene keeps it
    assert st.figure == "TWcubic"
    st.N = 600
    assert st.figure == "" and "fig" not in url_query(st) and len(st.held) == 5


class Recorder(SimulationScene):
    """The Simulation scene, its renders counted instead of run."""

    def request(self, prepare=None):
        if prepare is not None:
            prepare()
        self.requested = getattr(self, "requested", 0) + 1


@pytest.mark.parametrize(
    "label, kind, widgets, probes",
    [
        # Fig. Riemann1: w^l = 4.6, w^r = 0, L = 3600, t = 300; sites 100, 200, 3000 (c)-(e)
        ("Riemann1", "riemann", {"w_l": 4.6, "w_r": 0.0, "L": 3600, "t_end": 300.0},
         "100, 200, 3000"),
        # Fig. SWdyn (a): w_B = 1, A = 6, L = 2400 (t = 200: fpucore.paper's run)
        ("SWdyn", "gaussian", {"w_B": 1.0, "A": 6.0, "L": 2400, "t_end": 200.0}, ""),
        # Figs. stabSK, stabSW: seeded with the current wave for 50 periods T = 1/V
        ("stabSK", "seeded", {"t_end": 50 / 5.2}, ""),
        ("stabSW", "seeded", {"t_end": 50 / 5.2174919476}, ""),
    ],
)  # fmt: skip
def test_a_simulation_figure_fills_the_simulation_scene(label, kind, widgets, probes):
    st = ExplorerState()
    sc = Recorder(st)
    st.show_figure(label)
    assert sc.kind.value == kind and sc.probes.value == probes
    for name, value in widgets.items():
        assert getattr(sc, name).value == pytest.approx(value, rel=1e-15), name
    assert sc._want_run and sc.requested >= 1  # the click starts the run (measured ≤ 3 s)
    if kind == "seeded":  # the chain holds the wave, its path and two margins of 100
        assert sc.L.value >= st.N + math.ceil(st.V * sc.t_end.value) + 200
    # built later (a link with fig=, another tab first): the scene starts with the figure's
    st2, _ = state_from_url({"fig": label, "tab": "paper"})
    later = Recorder(st2)
    assert later.kind.value == kind and later._want_run and not getattr(later, "requested", 0)


def test_the_riemann_figure_runs_once_and_gives_the_papers_velocities():
    """Riemann1 in one click (the explorer's own sequence of state updates): the run is
    submitted once — no render in flight takes it and is then superseded (its job cancelled,
    its worker killed, the run resubmitted to a cold worker: 10 s instead of 2 s) — and its
    tracked waves carry the caption's velocities −5.7209, −5.6159, 4.6404 within their error
    bars plus the printed rounding."""
    from app import compute

    ex = Explorer(lazy=True)
    cancelled = compute.workers.CANCELLED[0]
    ex.scene("paper").open("Riemann1")
    sc = ex.scene("simulation")
    assert sc.wait_idle(300.0) and sc.last_message is None, sc.last_message
    assert compute.workers.CANCELLED[0] == cancelled
    sim = sc._sim[-1]
    for printed in (-5.7209, -5.6159, 4.6404):
        best = min(sim.waves, key=lambda w: abs(w.velocity - printed))
        assert abs(best.velocity - printed) <= best.velocity_error + 5e-5, (printed, best)
    assert [fig.visible for fig in sc.fig_probe] == [True, True, True]  # panels (c)-(e)


def test_a_superseded_caller_submits_no_job():
    from app import compute

    cancelled, n = compute.workers.CANCELLED[0], compute.workers.jobs_in_flight()
    with pytest.raises(compute.Superseded):
        req = compute.RiemannRequest(L=400, t_end=1.0 + 1e-9, w_left=4.6, w_right=0.0)
        compute.run(compute.laws.law(-1.0, 10.0), req, stop=lambda: True)
    assert compute.workers.CANCELLED[0] == cancelled and compute.workers.jobs_in_flight() == n
