""" "Copy as Python" copies the code of what is shown: disabled while a scene shows a message
instead of a plot (a refused law: its code would only raise), enabled again with the plot."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def test_copy_is_disabled_for_a_refused_law_and_back_with_the_plot():
    st = ExplorerState()
    sc = BY_KEY["force"](st)
    sc.refresh()
    assert sc.last_message is None and not sc.copy_btn.disabled
    st.expression = "w + w**2"  # not hardening-softening: refused
    sc.refresh()
    assert sc.last_message and sc.copy_btn.disabled and sc.download.disabled
    st.expression = ""
    sc.refresh()
    assert sc.last_message is None and not sc.copy_btn.disabled
