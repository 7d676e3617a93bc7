"""The box beside the N slider: a typed N reaches the state (and so the URL), an odd or
out-of-range N is corrected with a note, and slider, box and state always show the same N."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app.explorer import Explorer  # noqa: E402
from app.state import N_RANGE, ExplorerState  # noqa: E402
from app.url_state import parse_url, url_query  # noqa: E402


def test_typed_N_sets_the_state_the_slider_and_the_url():
    ex = Explorer(ExplorerState(tab="force"))
    for N in (200, 500, 64, 3998):
        ex.N_exact.value = N
        assert ex.state.N == ex.N.value == ex.N_exact.value == N
        assert url_query(ex.state)["N"] == str(N)
        assert parse_url(url_query(ex.state))[0]["N"] == N  # the link reproduces it
        assert ex.state.note == ""


@pytest.mark.parametrize(
    "typed,used,why",
    [(201, 200, "odd"), (5000, N_RANGE[1], "outside the range"), (10, N_RANGE[0], "outside")],
)
def test_an_odd_or_out_of_range_N_is_corrected_and_said(typed, used, why):
    ex = Explorer(ExplorerState(tab="force", N=300))
    ex.N_exact.value = typed
    assert ex.state.N == ex.N.value == ex.N_exact.value == used
    assert f"N = {typed} is {why}" in ex.state.note and f"using N = {used}" in ex.state.note
    assert f"using N = {used}" in ex.ranges.object  # shown in the sidebar


def test_the_slider_moves_the_box():
    ex = Explorer(ExplorerState(tab="force"))
    ex.state.N = 1200  # what the slider's throttled value does
    assert ex.N_exact.value == 1200
