"""Fixtures shared by every test folder.

Playwright's sync API runs its own event loop on the main thread for as long as it is open, and a
second `sync_playwright()` while one is open fails ("Sync API inside the asyncio loop"). The browser
tests keep one Chromium for the whole session, so every test that drives a browser (the explorer's,
the docs site's, the installed wheel's) takes it from this one session-wide Playwright.
"""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def playwright():
    """The session's one sync Playwright (started on first use, stopped at the session's end)."""
    sync_api = pytest.importorskip("playwright.sync_api")
    with sync_api.sync_playwright() as p:
        yield p
