"""What a law change costs the explorer before the force law is drawn (counted, not timed).

Choosing the tanh preset from the default cubic state (w₊ = 1 stays, V goes to the middle of a
very narrow (c₊, V_SK): a near-sonic solitary wave) once took 5–7 s: the sidebar's sync asked
ExplorerState.problem()/kind() several times, and each computed the whole QC solitary wave — its
profile by quadrature and E_ren — where only its checks and kind are needed; the general
route's speeds were recomputed ~18 times per change.  Counted here: no general-route QC solitary
wave and at most one speeds computation per w₊ between the law change and the force law drawn.
And every preset's law is requested at the server's warm-up, with the very text a choice of
that preset applies.
"""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app import compute, warmup  # noqa: E402
from app.explorer import Explorer  # noqa: E402
from app.law_presets import PRESET_OPTIONS, preset_text  # noqa: E402
from fpucore.qc import general, general_speeds  # noqa: E402


@pytest.fixture
def counted(monkeypatch):
    """Calls of the general route's solitary wave and of its speeds' partner root (one per
    speeds computation), with the speeds memo emptied."""
    calls = {"solitary": 0, "speeds": []}
    solitary, partner = general.solitary, general_speeds.w_minus_from_w_plus

    def counting_solitary(*args, **kw):
        calls["solitary"] += 1
        return solitary(*args, **kw)

    def counting_partner(law, w_plus):
        calls["speeds"].append(w_plus)
        return partner(law, w_plus)

    monkeypatch.setattr(general, "solitary", counting_solitary)
    monkeypatch.setattr(general_speeds, "w_minus_from_w_plus", counting_partner)
    getattr(general_speeds.speeds, "cache_clear", lambda: None)()
    yield calls
    getattr(general_speeds.speeds, "cache_clear", lambda: None)()


@pytest.mark.parametrize("preset", ["tanh", "rational", "exponential"])
def test_a_smooth_preset_change_draws_the_force_law_without_solitary_profiles(counted, preset):
    text = preset_text(preset)
    compute.laws.trusted_expression_law(text)  # built (as at the warm-up): no law worker here
    ex = Explorer()
    assert ex.state.tab == "force"
    scene = ex.active_scene()
    scene.refresh()
    counted["solitary"], counted["speeds"][:] = 0, []
    ex.state.param.update(expression=text)  # what the editor's apply does once the law is built
    assert scene.wait_idle(120)
    assert scene.last_message is None
    assert scene.state.expression == text
    assert counted["solitary"] == 0
    per_w_plus = {w: counted["speeds"].count(w) for w in counted["speeds"]}
    assert per_w_plus and max(per_w_plus.values()) == 1, per_w_plus


def test_the_warm_up_builds_every_preset_a_choice_applies(monkeypatch):
    requested: list[str] = []
    monkeypatch.setattr(compute.laws, "request_law", lambda text: requested.append(text))
    assert warmup.request_preset_laws() == requested
    applied: list[str] = []
    ex = Explorer()
    monkeypatch.setattr(ex.law_editor, "apply", lambda text: applied.append(text))
    for name in PRESET_OPTIONS.values():
        if name and name != "cubic":
            ex.law_editor.preset.value = name
    assert applied and sorted(applied) == sorted(requested)
