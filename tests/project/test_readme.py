"""The README's headless example runs as written, and its two commands are the Makefile's."""

import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_readme_python_example_runs(capsys):
    text = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "README has no python example"
    exec(compile(blocks[0], "README.md", "exec"), {})
    out = capsys.readouterr().out
    assert "True" in out  # the discrete superkink converged
    assert "superkink" in out  # the Riemann run found the superkink


def test_readme_commands_are_make_targets_and_ci_calls_the_test_one():
    text = (ROOT / "README.md").read_text()
    assert "make serve" in text and "make test" in text
    makefile = (ROOT / "Makefile").read_text()
    assert re.search(r"^serve:", makefile, flags=re.M) and re.search(r"^test:", makefile, re.M)
    assert "make test" in (ROOT / ".ci" / "run").read_text()
