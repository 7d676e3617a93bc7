"""Every ``--json`` of the ``fpu`` command line prints JSON alone on stdout (``fpu … --json | jq``
works); progress bars, summaries and "wrote …" lines go to stderr.  The commands are enumerated
from the parser itself, so a new command with ``--json`` must be added to CHEAP below."""

from __future__ import annotations

import argparse
import json

import pytest

from fpucore.cli import build_parser, main

# one cheap invocation per command path that has --json (tiny N, short runs)
CHEAP = {
    ("qc",): "--w-plus 1 --V 5",
    ("wave", "superkink"): "--V 5.2 --N 64",
    ("wave", "solitary"): "--w-plus 1 --V 5.2 --N 64",
    ("floquet", "superkink"): "--V 5.2 --N 64 --no-finite-size",
    ("floquet", "solitary"): "--w-plus 1 --V 5.2 --N 64 --no-finite-size",
    ("floquet", "sweep"): "superkink --V 5.2 --N 64 --no-cache",
    ("simulate", "riemann"): "--w-left 1 --w-right 0 --L 40 --t-end 1",
    ("simulate", "gaussian"): "--w-B 0 --A 0.1 --L 40 --t-end 1",
    ("simulate", "velocity-jump"): "--w-left 1 --w-right 1 --v-left -0.2 --L 40 --t-end 1",
    ("simulate", "wave", "superkink"): "--V 5.2 --N 64 --periods 1",
    ("simulate", "wave", "solitary"): "--w-plus 1 --V 5.2 --N 64 --periods 1",
    ("atlas", "superkink"): "--V 5.2:5.3:2 --N 64 --backend inline",
    ("atlas", "solitary"): "--w-plus 1:1:1 --V 5.2:5.3:2 --N 64 --backend inline",
    ("paper",): "--figure Riemann1 --reduced",
}
# the same command, other output paths that must not leak onto stdout either
EXTRA = [
    ("paper", "--list"),
]


def _json_commands(parser: argparse.ArgumentParser, path=()) -> list[tuple[str, ...]]:
    """Every leaf command path of the parser that takes --json."""
    found = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                found += _json_commands(sub, (*path, name))
    if "--json" in parser._option_string_actions:
        found.append(path)
    return found


def test_every_json_command_is_listed():
    assert sorted(_json_commands(build_parser())) == sorted(CHEAP)


@pytest.mark.parametrize("path", sorted(CHEAP), ids=" ".join)
def test_json_alone_on_stdout(path, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)  # outputs (atlas stores, caches) stay in the temporary directory
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path / "cache"))
    args = [*path, *CHEAP[path].split(), "--json"]
    if path[0] == "atlas":
        args += ["--out", str(tmp_path / "atlas.zarr"), "--no-progress"]
    assert main(args) == 0, capsys.readouterr().err
    out = capsys.readouterr().out
    doc = json.loads(out)  # the whole of stdout is one JSON document
    assert isinstance(doc, dict) and doc


@pytest.mark.parametrize("args", EXTRA, ids=" ".join)
def test_json_alone_on_stdout_other_paths(args, capsys):
    assert main([*args, "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert len(doc["figures"]) == 17
