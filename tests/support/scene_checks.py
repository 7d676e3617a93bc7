"""Checks on a scene object shared by the app tests (tests/support is on the test path)."""

import time


def assert_cancel_answers_within(sc, limit_s: float = 1.0) -> None:
    """Press Cancel on a scene with a running job: the handler says "cancelled" before it
    returns (before any cleanup), "Cancelled" is shown within ``limit_s``, and the worker then
    goes idle with the progress text hidden."""
    t0 = time.perf_counter()
    sc.cancel()
    # the word comes from the click's handler itself, before the job stops and the cleanup runs
    assert sc.computing_text.object == "cancelled: stopping the job …", sc.computing_text.object
    while not (sc.last_message or "").startswith("Cancelled") and time.perf_counter() - t0 < 10:
        time.sleep(0.01)
    assert (sc.last_message or "").startswith("Cancelled")
    assert time.perf_counter() - t0 < limit_s
    assert sc.wait_idle(10) and not sc.busy_shown
