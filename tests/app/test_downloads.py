"""Downloads say what they hold, and exist only when there is something to download."""

from __future__ import annotations

import pytest

pytest.importorskip("panel")

from app.state import ExplorerState  # noqa: E402
from app.views import SCENES  # noqa: E402

BY_KEY = {cls.key: cls for cls in SCENES}


def run(L: int):
    sc = BY_KEY["simulation"](ExplorerState())
    sc.kind.value = "riemann"
    sc.L.value, sc.t_end.value = L, 2.0
    sc._want_run = True  # the "Run simulation" button
    sc.refresh()
    assert sc.last_message is None, sc.last_message
    return sc


def header_and_columns(sc):
    name, buf = sc.download_data()
    lines = buf.getvalue().splitlines()
    header = "\n".join(ln for ln in lines if ln.startswith("#"))
    columns = next(ln for ln in lines if not ln.startswith("#")).split(",")[1:]
    return header, columns


def test_the_field_header_says_which_sites_it_holds():
    sc = run(300)  # every site kept
    header, columns = header_and_columns(sc)
    assert "one column per site n (all 300)" in header and len(columns) == 300
    sc = run(2500)  # more sites than fpucore keeps by default (max_sites_out = 1000): all kept
    header, columns = header_and_columns(sc)
    assert "one column per site n (all 2500)" in header and len(columns) == 2500
    sites = [int(c.removeprefix("n=")) for c in columns]
    assert sites == list(range(1, 2501))


def test_no_download_before_there_is_data():
    sc = BY_KEY["simulation"](ExplorerState())
    sc.refresh()  # no run yet: a message, no plot
    assert sc.last_message and sc.download.disabled
    sc.kind.value = "riemann"
    sc.L.value, sc.t_end.value = 300, 2.0
    sc._want_run = True
    sc.refresh()
    assert sc.last_message is None and not sc.download.disabled
