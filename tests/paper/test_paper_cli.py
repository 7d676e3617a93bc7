"""``fpu paper``: list, one figure exported as HTML / SVG / PNG, the HTML report of a reduced set
with the comparison table, the cache a re-run reuses, the time budget, bad input (exit 2)."""

from __future__ import annotations

import json
import re
import xml.etree.ElementTree as ET
from html.parser import HTMLParser

import pytest

from fpucore import paper
from fpucore.cli.dispatch import main
from fpucore.paper import registry
from fpucore.paper.report import cache_dir

FAST = ("superkink", "pplane", "cubic")
# a fetch that leaves the file: another host, or a path beside the file (a page opened from disk
# has no server behind it: "static/extensions/..." is net::ERR_FILE_NOT_FOUND)
IN_FILE = re.compile(r"\s*(#|data:|blob:|javascript:)", re.IGNORECASE)


class _Links(HTMLParser):
    """Every attribute that makes a browser fetch something (src, href, …) from outside the file.
    Script *contents* are data here, not tags: a URL string inside Bokeh's bundled JavaScript
    (e.g. a license comment) is not a request."""

    def __init__(self) -> None:
        super().__init__()
        self.external: list[tuple[str, str, str]] = []
        self.tags: set[str] = set()

    def handle_starttag(self, tag, attrs):
        self.tags.add(tag)
        for k, v in attrs:
            if (
                k in ("src", "href", "data", "poster", "srcset", "action")
                and v
                and not IN_FILE.match(v)
            ):
                self.external.append((tag, k, v))


def external_links(text: str) -> list[tuple[str, str, str]]:
    p = _Links()
    p.feed(text)
    assert "script" in p.tags
    return p.external


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))


def test_the_link_checker_sees_a_cdn_link():
    assert external_links('<script src="https://cdn.bokeh.org/x.js"></script>')
    assert external_links('<script></script><link href="//cdn.holoviz.org/favicon.ico">')
    assert not external_links('<script>var u = "https://bokeh.org/";</script>')
    assert external_links('<script src="static/extensions/panel/x.js"></script>')  # from disk
    assert not external_links('<script src="data:text/javascript,1"></script><a href="#t">')


def test_list(capsys):
    assert main(["paper", "--list"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert len(lines) == 17 and "pplane" in lines[1] and "SWdyn" in lines[-1]


@pytest.mark.parametrize(
    "argv, match",
    [
        (["paper", "--figure", "Riemann2", "--out", "x.html"], "figure='Riemann2'"),
        (["paper", "--figure", "pplane", "--out", "x.pdf"], "--out"),
        (["paper", "--figure", "pplane", "--figure", "cubic", "--out", "x.svg"], "several"),
        (["paper", "--table", "t.txt"], "Markdown"),
        (["paper"], "--out FILE"),
        (["paper", "--figure", "pplane", "--out", "/no/such/dir/x.html"], "does not exist"),
    ],
)
def test_bad_input_exit_2_one_line(argv, match, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error:") and match in err and err.count("\n") == 1


def test_one_figure_as_html_svg_png(tmp_path):
    for ext in ("html", "svg", "png"):
        out = tmp_path / f"pplane.{ext}"
        assert main(["paper", "--figure", "pplane", "--reduced", "--workers", "1",
                     "--out", str(out)]) == 0  # fmt: skip
        assert out.stat().st_size > 10_000
    html = (tmp_path / "pplane.html").read_text()
    assert external_links(html) == []  # nothing fetched from another host or beside the file
    assert "Bokeh" in html and "V = V_SK" in html
    # the figure's comparison rows come with it (what the README promises): each printed number
    # of the figure, in the table's cells (the Div's text sits in Bokeh's JSON)
    rows = paper.compute("pplane", True).comparisons
    assert rows and "cmp" in html
    for c in rows:
        assert f"{c.ours:.10g}" in html, c.quantity
    root = ET.parse(tmp_path / "pplane.svg").getroot()  # valid XML
    assert root.tag.endswith("svg")
    paths = [e for e in root.iter() if e.tag.endswith("path")]
    assert len(paths) > 20  # the orbits, markers, axes
    # the orbits are long polylines (hundreds of vertices), not just axis ticks
    assert max(len(e.get("d", "")) for e in paths) > 2000
    assert (tmp_path / "pplane.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_report_of_a_reduced_set_offline_table_and_cache(tmp_path, monkeypatch, capsys):
    out, table = tmp_path / "report.html", tmp_path / "cmp.md"
    argv = ["paper", "--reduced", "--workers", "1", "--out", str(out), "--table", str(table)]
    for lab in FAST:
        argv += ["--figure", lab]
    assert main(argv) == 0
    text = out.read_text()
    assert external_links(text) == []
    for lab in FAST:
        fig = paper.FIGURES[lab]
        assert f"Fig. {fig.number} ({lab}" in text
        assert fig.caption[:19] in text  # ASCII start (the Div's text sits in Bokeh's JSON)
    assert "disagrees" not in capsys.readouterr().out
    md = table.read_text()
    assert md.count("| agrees |") == sum(len(paper.compute(lab, True).comparisons) for lab in FAST)
    assert "2√65/3" in md and "4.78423" in md
    cached = sorted(p.name for p in cache_dir().glob("*.pickle"))
    assert len(cached) == 3

    # a re-run reuses every figure: computing one now would fail
    def refuse(self, reduced=False):
        raise AssertionError(f"{self.label} recomputed")

    monkeypatch.setattr(registry.Figure, "compute", refuse)
    assert main(argv) == 0
    assert "3/3 figures" in capsys.readouterr().out


def test_time_budget_stops_between_figures(tmp_path, capsys):
    argv = ["paper", "--reduced", "--workers", "1", "--time-budget", "1e-6", "--json",
            "--figure", "superkink", "--figure", "cubic"]  # fmt: skip
    assert main(argv) == 0
    cap = capsys.readouterr()
    # --json: stdout is the JSON alone, the summary is for people (stderr)
    assert "1/2 figures" in cap.err and "not computed within the time budget" in cap.err
    assert json.loads(cap.out)["missing"]


@pytest.mark.slow
def test_report_in_the_process_pool(tmp_path, capsys):
    out = tmp_path / "r.html"
    assert main(["paper", "--reduced", "--workers", "2", "--figure", "superkink",
                 "--figure", "SWvelocities_cubic", "--out", str(out)]) == 0  # fmt: skip
    assert "2/2 figures" in capsys.readouterr().out
    assert external_links(out.read_text()) == []
