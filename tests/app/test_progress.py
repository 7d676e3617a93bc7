"""A long job says what it is doing and how long it will take, and Cancel is answered at once.

The time left is elapsed × (1 − x) / x for the fraction x of the current stage."""

from __future__ import annotations

import re
import time

import pytest

pytest.importorskip("panel")

from scene_checks import assert_cancel_answers_within  # noqa: E402 - tests/support

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def test_progress_names_the_stage_and_estimates_the_time_left():
    sc = BY_KEY["profiles"](ExplorerState())
    sc.set_progress(0.0, stage="discrete wave")
    time.sleep(0.6)
    sc.set_progress(0.25, stage="discrete wave")
    m = re.fullmatch(r"discrete wave: 25 % · about ([0-9.]+) s left", sc.progress_text.object)
    assert m, sc.progress_text.object
    # 0.6 s for a quarter: about three times that left
    assert 1.5 <= float(m.group(1)) <= 3.5
    sc.set_stage("Floquet spectrum")  # a new stage restarts the estimate
    assert sc.progress_text.object == "Floquet spectrum …" and sc.progress.value == -1


def test_a_long_simulation_shows_its_progress_and_cancel_answers_within_a_second():
    sc = BY_KEY["simulation"](ExplorerState())
    sc.kind.value = "gaussian"
    for name, value in dict(L=3000, t_end=3000.0, w_B=1.0, A=1.0).items():
        getattr(sc, name).value = value
    sc._want_run = True  # the "Run simulation" button
    sc.request()
    t_end = time.monotonic() + 120
    while "left" not in sc.progress_text.object and time.monotonic() < t_end:
        time.sleep(0.05)
    assert re.match(r"simulation: \d+ % · about .+ left", sc.progress_text.object)
    assert sc.busy_shown
    assert_cancel_answers_within(sc, 1.0)
