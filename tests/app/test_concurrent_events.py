"""Two browser events of one session handled at once: Panel runs a session's events on its
handler threads (``--num-threads 2``).  An event handled while the other thread syncs the
sidebar after its own event waits for that sync and is applied — it was dropped as the sync's
echo (the state walk: three key presses on the b slider, 10 → 9.95 → 10 → 9.95; the last was
lost, and the URL and plot stayed at 10 while the slider showed 9.95)."""

from __future__ import annotations

import threading
import time

import param
import pytest

pytest.importorskip("panel")

from app import explorer as explorer_module  # noqa: E402
from app.explorer import Explorer  # noqa: E402


def move(slider, value: float) -> None:
    """What a slider release sends: value, then value_throttled."""
    slider.value = value
    with param.edit_constant(slider):
        slider.value_throttled = value


@pytest.mark.parametrize(
    ("widget", "name", "first", "second"),
    [(lambda ex: ex.law_editor.b, "b", 9.9, 9.95), (lambda ex: ex.V, "V", 5.1, 5.2)],
    ids=["law editor's b slider", "V slider"],
)
def test_an_event_during_another_threads_sync_is_applied(monkeypatch, widget, name, first, second):
    ex = Explorer()
    slider = widget(ex)
    in_sync = threading.Event()
    ranges_markdown = explorer_module.ranges_markdown

    def slow_ranges_markdown(state, summary):  # the sync after the first event, held open
        if getattr(state, name) == first:
            in_sync.set()
            time.sleep(0.5)
        return ranges_markdown(state, summary)

    monkeypatch.setattr(explorer_module, "ranges_markdown", slow_ranges_markdown)
    a = threading.Thread(target=move, args=(slider, first))
    a.start()
    assert in_sync.wait(60)
    b = threading.Thread(target=move, args=(slider, second))  # the second event, meanwhile
    b.start()
    a.join(60)
    b.join(60)
    assert getattr(ex.state, name) == second
    assert slider.value == second and slider.value_throttled == second
