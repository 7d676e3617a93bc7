"""The work-precision report is reproducible by its one command (quick grid here), covers every
route, and its curves behave: more work buys less error."""

import re

from benchmarks.work_precision import main


def _rows(md: str, route: str, method: str) -> list[tuple[str, float, float]]:
    sec = md.split(f"### {route}")[1].split("\n### ")[0]
    out = []
    for line in sec.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) >= 4 and cells[0] == method:
            out.append((cells[1], float(cells[2]), float(cells[3])))
    return out


def test_quick_report_reproduces(tmp_path):
    md_path, html_path = tmp_path / "wp.md", tmp_path / "wp.html"
    assert main(["--quick", "--md", str(md_path), "--html", str(html_path)]) == 0
    md = md_path.read_text()
    for route in ("period map", "traveling wave", "Floquet", "simulation"):
        assert f"### {route}" in md
    assert md.count("Floor") >= 4 and "scipy" in md
    assert html_path.stat().st_size > 10_000 and "bokeh" in html_path.read_text().lower()
    # fixed-step DOP853 on the period map: error falls as m grows (8th order)
    rows = _rows(md, "period map", "fpucore dop853 fixed m")
    ms = [int(re.sub(r"\D", "", s)) for s, _, _ in rows]
    errs = [e for _, e, _ in rows]
    assert ms == sorted(ms) and all(b < a for a, b in zip(errs, errs[1:]))
    # the default simulation method: the seeded wave's shape error falls as rtol tightens, and at
    # rtol 1e-9 it is already below scipy's DOP853 at the same tolerance
    rows = _rows(md, "simulation: seeded superkink", "fpucore rkn12")
    errs = [e for _, e, _ in rows]
    assert len(errs) == 3 and all(b < a for a, b in zip(errs, errs[1:]))
    sp = dict(
        (s, e) for s, e, _ in _rows(md, "simulation: seeded superkink", "scipy solve_ivp DOP853")
    )
    assert errs[1] < sp["rtol=1e-09"]
