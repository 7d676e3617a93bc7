"""Fixtures shared by every test folder.

Playwright's sync API runs its own event loop on the main thread for as long as it is open, and a
second `sync_playwright()` while one is open fails ("Sync API inside the asyncio loop"). The browser
tests keep one Chromium for the whole session, so every test that drives a browser (the explorer's,
the docs site's, the installed wheel's) takes it from this one session-wide Playwright.

Hypothesis runs derandomized (profile ``ci``) unless ``FPU_HYPOTHESIS=explore``.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import settings

# Property tests draw the same examples on every run (a red CI run is the code's, reproducible
# from the seed); FPU_HYPOTHESIS=explore draws new ones at random, as a fuzzing session does.
settings.register_profile("ci", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("FPU_HYPOTHESIS", "ci"))


@pytest.fixture(scope="session")
def playwright():
    """The session's one sync Playwright (started on first use, stopped at the session's end)."""
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        yield p
