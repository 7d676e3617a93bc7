"""A running Floquet job names its stage (discrete wave → Floquet spectrum → shorter rings),
estimates the time left once a spectrum has been timed on this server, and Cancel is answered
within a second (it showed an indeterminate bar with no stage, and Cancel took 6.7 s)."""

from __future__ import annotations

import re
import time

import pytest

pytest.importorskip("panel")

from scene_checks import assert_cancel_answers_within  # noqa: E402 - tests/support

from app import compute  # noqa: E402
from app.compute import heavy  # noqa: E402
from app.compute.jobs import FLOQUET_STAGES, floquet_job, stage_of, stage_progress  # noqa: E402
from app.compute.requests import WaveRequest  # noqa: E402
from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def test_stage_and_fraction_survive_the_one_number_the_pool_forwards():
    for stage in FLOQUET_STAGES:
        for done in (0.0, 0.3, 0.999):
            s, d = stage_of(stage_progress(stage, done))
            assert s == stage and d == pytest.approx(done, abs=1e-9)
    xs = [stage_progress(s, d) for s in FLOQUET_STAGES for d in (0.0, 0.5, 1.0)]
    assert xs == sorted(xs) and 0.0 <= xs[0] and xs[-1] < 1.0  # ordered, never "done" early


def test_the_job_reports_its_stages_in_order():
    seen: list[float] = []
    law = compute.laws.law(-1.0, 10.0)
    r, fr = floquet_job(law, WaveRequest("superkink", 1.0, 0.0, 200, 1e-10), progress=seen.append)
    assert fr is not None
    stages = [stage_of(x)[0] for x in seen]
    assert stages[0] == "discrete wave" and "Floquet spectrum" in stages
    assert seen == sorted(seen)
    rings = len(fr.finite_size_N) > 1  # the window of shorter rings was computed
    assert ("shorter rings" in stages) == rings


def test_a_running_spectrum_shows_its_stage_and_time_left_and_cancel_answers_within_a_second():
    law = compute.laws.law(-1.0, 10.0)
    wave = WaveRequest("solitary", 1.0, 5.0, 300, 1e-10)
    compute.run(law, compute.SpectrumRequest(wave))  # times one spectrum here
    assert heavy.spectrum_time_estimate(1000) > 0
    sc = BY_KEY["floquet"](ExplorerState(N=1000, tol=1e-10))
    texts: list[str] = []
    sc.progress_text.param.watch(lambda e: texts.append(e.new), "object")
    sc.request()
    t_end = time.monotonic() + 240
    while not any("left" in t for t in texts) and time.monotonic() < t_end:
        time.sleep(0.05)
    assert any(t.startswith("discrete wave") for t in texts), texts
    assert any(re.match(r"Floquet spectrum: \d+ % · about .+ left", t) for t in texts), texts
    assert sc.busy_shown
    assert_cancel_answers_within(sc, 1.0)
