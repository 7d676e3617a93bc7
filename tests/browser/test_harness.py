"""The browser harness itself: the server-log check and the serve command it starts."""

from __future__ import annotations

import pytest
from browser_harness import ROOT, SERVE_COMMAND, client_disconnect, tracebacks

from fpucore.cli import serve

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
    """The tested command (SERVE_COMMAND: fpu serve) is the Makefile's serve target and the
    Dockerfile's, and it is panel serve of the app with its warm-up, guards and /liveness."""
    make = (ROOT / "Makefile").read_text()
    docker = (ROOT / "Dockerfile").read_text()
    assert SERVE_COMMAND[1:] == ["-m", "fpucore", "serve"]
    assert "$(BIN)/fpu serve --port $(PORT) --address 0.0.0.0" in make
    assert 'CMD ["fpu", "serve", "--port", "5006", "--address", "0.0.0.0"]' in docker
    cmd = " ".join(serve.command(5006, "0.0.0.0", 1, ROOT / "app"))
    assert f"-m panel serve {ROOT / 'app' / 'main.py'} --port 5006 --address 0.0.0.0" in cmd
    for flag in ("--allow-websocket-origin=*", "--liveness", "--num-threads 2",
                 f"--setup {ROOT / 'app' / 'warm.py'}", "--warm"):  # fmt: skip
        assert flag in cmd, flag
    assert "--num-procs" not in cmd  # Panel's single-process path, unless asked
    assert "--num-procs 3" in " ".join(serve.command(5006, "0.0.0.0", 3, ROOT / "app"))
    assert serve.explorer_dir() == ROOT / "app"  # a checkout serves its own app/
