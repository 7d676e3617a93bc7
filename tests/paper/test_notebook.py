"""A figure's notebook (``fpu paper --figure X --out X.ipynb``), executed top to bottom in a fresh
kernel with nbclient, prints the same numbers as the registry computed here."""

from __future__ import annotations

import pytest

from fpucore import paper
from fpucore.cli.dispatch import main

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")


def _text(nb) -> str:
    out = []
    for cell in nb.cells:
        for o in cell.get("outputs", []):
            out.append(o.get("text", ""))
            out.append(str(o.get("data", {}).get("text/plain", "")))
            if o.get("output_type") == "error":
                out.append(f"ERROR {o.get('ename')}: {o.get('evalue')}")
    return "\n".join(out)


@pytest.mark.parametrize("label", ["pplane", "cubic"])
def test_notebook_runs_and_reproduces_the_numbers(label, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))
    path = tmp_path / f"{label}.ipynb"
    assert main(["paper", "--figure", label, "--reduced", "--out", str(path)]) == 0
    nb = nbformat.read(str(path), as_version=4)
    assert f"def fig_{label}" in nb.cells[1].source  # the exact fpucore code, for reading
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()  # fmt: skip
    text = _text(nb)
    assert "ERROR" not in text, text[-2000:]
    r = paper.compute(label, reduced=True)
    for c in r.comparisons:
        assert f"ours {c.ours!r}" in text, (c.quantity, text[-1500:])
        assert f"-> {c.verdict}" in text
    assert "Layout" in text or ":Layout" in text or "Overlay" in text  # the plot cell's object


def test_a_notebook_holds_one_figure(capsys):
    argv = ["paper", "--figure", "pplane", "--figure", "cubic", "--out", "x.ipynb"]
    assert main(argv) == 2
    assert "one --figure" in capsys.readouterr().err
