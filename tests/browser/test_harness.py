"""The browser harness itself: the server-log check and the serve command it starts."""

from __future__ import annotations

import pytest
from browser_harness import ROOT, client_disconnect, tracebacks

pytestmark = pytest.mark.browser


def test_server_log_check_tells_app_errors_from_disconnects():
    log = (
        'Traceback (most recent call last):\n  File "x.py", line 1, in f\n'
        "tornado.websocket.WebSocketClosedError\n"
        'Traceback (most recent call last):\n  File "app/views/scene.py", line 2, in g\n'
        "RuntimeError: boom\n"
    )
    tbs = tracebacks(log)
    assert len(tbs) == 2
    assert [client_disconnect(t) for t in tbs] == [True, False]


def test_serve_command_is_the_containers():
    """The tested command (SERVE_FLAGS) is the Makefile's serve target and the Dockerfile's."""
    make = (ROOT / "Makefile").read_text()
    docker = (ROOT / "Dockerfile").read_text()
    for flag in ("--liveness", "--num-threads 2", "--setup app/warm.py", "--warm"):
        assert flag in make, flag
        assert flag.replace(" ", '", "') in docker or flag in docker, flag
    assert "panel serve app/main.py" in make and '"panel", "serve", "app/main.py"' in docker
