"""The committed paper material the explorer shows without computing, package data of the
explorer: app/assets/figures/<label>.png (one thumbnail per figure of the registry) and
app/assets/paper_comparison.json, which must carry the same numbers as docs/paper_comparison.md
(both written by one ``fpu paper --table … --table-json …`` run)."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import pytest
from PIL import Image

from fpucore import paper
from fpucore.cli.dispatch import main
from fpucore.paper.plot import THUMB_WIDTH

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
ASSETS = ROOT / "app" / "assets"
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def md_rows(text: str) -> list[dict]:
    """The comparison rows of the Markdown table (cells split on unescaped '|')."""
    rows = []
    for line in text.splitlines():
        m = re.match(r"\| (\d+) `([A-Za-z_0-9]+)` \|", line)
        if not m:
            continue
        cells = [c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", line)[1:-1]]
        assert len(cells) == 8, line
        rows.append(
            {"label": m.group(2), "number": int(m.group(1)), "quantity": cells[1],
             "printed": cells[2], "ours": cells[3], "error": cells[4],
             "agrees": cells[5] == "agrees", "why": cells[6]}
        )  # fmt: skip
    return rows


def json_rows(doc: dict) -> list[dict]:
    out = []
    for label, fig in doc["figures"].items():
        for c in fig["comparisons"]:
            out.append({"label": label, **c})
    return out


def assert_same_numbers(md_text: str, doc: dict) -> int:
    """Every Markdown row is the JSON row at the same place, with the same numbers as printed
    (ours to 10 significant digits, the error bar to 2); returns the number of rows."""
    md, js = md_rows(md_text), json_rows(doc)
    assert len(md) == len(js) > 0
    for m, j in zip(md, js, strict=True):
        assert m["label"] == j["label"] and m["number"] == paper.FIGURES[j["label"]].number
        assert (m["quantity"], m["printed"], m["why"]) == (j["quantity"], j["printed"], j["why"])
        assert m["agrees"] == j["agrees"]
        assert m["ours"] == f"{j['ours']:.10g}" and m["error"] == f"{j['error']:.2g}"
        assert math.isclose(float(m["ours"]), j["ours"], rel_tol=1e-9, abs_tol=1e-300)
    return len(md)


def test_every_figure_has_a_committed_thumbnail_of_the_stated_size():
    for label in paper.LABELS:
        path = ASSETS / "figures" / f"{label}.png"
        assert path.is_file(), f"{path} missing: fpu paper --thumbnails app/assets/figures"
        assert path.read_bytes()[:8] == PNG_MAGIC
        with Image.open(path) as im:
            im.verify()  # a complete, uncorrupted PNG
        with Image.open(path) as im:
            assert im.format == "PNG" and im.width == THUMB_WIDTH, (label, im.size)
            assert THUMB_WIDTH // 5 <= im.height <= 2 * THUMB_WIDTH, (label, im.size)
            assert len(set(im.convert("L").getdata())) > 8, label  # drawn, not blank
        assert path.stat().st_size < 100_000, label  # small: the Paper tab embeds all 17


def test_the_docs_json_holds_the_markdown_tables_numbers_for_every_figure():
    doc = json.loads((ASSETS / "paper_comparison.json").read_text(encoding="utf-8"))
    assert set(doc["figures"]) == set(paper.LABELS) and not doc["missing"]
    assert list(doc["figures"]) == list(paper.LABELS)  # paper order, as the Markdown
    assert isinstance(doc["fpucore_version"], str) and doc["fpucore_version"]
    n = assert_same_numbers((DOCS / "paper_comparison.md").read_text(encoding="utf-8"), doc)
    agree = sum(r["agrees"] for r in json_rows(doc))
    assert f"{agree} of {n} printed numbers agree" in (DOCS / "paper_comparison.md").read_text()


def test_one_run_writes_the_table_its_json_and_the_thumbnails(tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))
    table, thumbs = tmp_path / "cmp.md", tmp_path / "figs"
    thumbs.mkdir()
    argv = ["paper", "--reduced", "--workers", "1", "--table", str(table),
            "--thumbnails", str(thumbs), "--figure", "superkink", "--figure", "cubic"]  # fmt: skip
    assert main(argv) == 0
    doc = json.loads(table.with_suffix(".json").read_text(encoding="utf-8"))
    assert list(doc["figures"]) == ["superkink", "cubic"]
    assert all(f["reduced"] for f in doc["figures"].values())
    assert assert_same_numbers(table.read_text(encoding="utf-8"), doc) == sum(
        len(paper.compute(lab, True).comparisons) for lab in ("superkink", "cubic")
    )
    assert sorted(p.name for p in thumbs.iterdir()) == ["cubic.png", "superkink.png"]
    with Image.open(thumbs / "cubic.png") as im:
        assert im.width == THUMB_WIDTH


def test_thumbnails_need_an_existing_directory(tmp_path, capsys):
    assert main(["paper", "--figure", "superkink", "--thumbnails", str(tmp_path / "no")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error:") and "--thumbnails" in err and err.count("\n") == 1


@pytest.mark.parametrize("width", [10, 400.5])
def test_thumbnail_width_is_checked(width):
    from fpucore.errors import ParameterError
    from fpucore.paper import plot

    with pytest.raises(ParameterError, match="width"):
        plot.thumbnail(paper.compute("superkink", True), "x.png", width=width)
