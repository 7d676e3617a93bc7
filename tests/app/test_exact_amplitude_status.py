"""A superkink's amplitude |w₋ − w₊| is exact by construction (eq. Rline): the status says so
and shows no "amplitude error bound 0.00e+00" beside it; a solitary wave keeps its bound."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


@pytest.mark.parametrize("mode, bound", [("superkink", False), ("solitary", True)])
def test_the_amplitude_bound_is_shown_only_where_there_is_one(mode, bound):
    st = ExplorerState(N=200, mode=mode)
    sc = BY_KEY["profiles"](st)
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    text = sc.status.object
    assert ("amplitude error bound" in text) == bound, text
    if mode == "superkink":
        assert "(exact by construction)" in text
