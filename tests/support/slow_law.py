"""A law job that takes longer than any budget (tests of the law worker's budget).

Module-level, importable by name in a worker process (tests/support is on the path of pytest and
of the processes it starts), so a test can stand it in for app.compute.laws.build_law_job: every
real law text is now answered in milliseconds, so a real one cannot make the budget trip."""

import time


def slow_law_job(expression: str, progress=None):
    if progress is not None:
        progress(0.0)  # the budget starts here, as in build_law_job
    time.sleep(60.0)
    raise AssertionError("the law worker's budget should have stopped this job")
