"""`fpu qc` contract: JSON keys, values, and one-line refusals with exit code 2."""

import json
import math
import subprocess
import sys

import pytest

from fpucore.cli import main


def run(*args):
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "qc", *args], capture_output=True, text=True, timeout=120
    )
    return p.returncode, p.stdout, p.stderr


def test_json_contract_w_plus_1():
    rc, out, err = run("--w-plus", "1", "--V", "5.0", "--json")
    assert rc == 0, err
    d = json.loads(out)
    for k in ("a", "b", "w_plus", "w_star", "alpha", "beta", "c_plus", "c_minus", "superkink"):
        assert k in d
    assert set(("V", "w_minus", "p")) <= set(d["superkink"])
    s = d["solitary"]
    assert set(("V", "kind", "w_B", "w_T", "w_M", "gamma", "amplitude", "energy")) <= set(s)
    assert d["a"] == -1 and d["b"] == 10
    assert d["superkink"]["V"] == pytest.approx(2 * math.sqrt(65) / 3, rel=1e-14)
    assert d["superkink"]["w_minus"] == pytest.approx(17 / 3, rel=1e-14)
    assert s["kind"] == "tensile" and s["w_B"] == 1.0


def test_readable_summary(capsys):
    assert main(["qc", "--w-plus", "6"]) == 0
    out = capsys.readouterr().out
    assert "V_SK = 5.217491947" in out and "c+ = 3.605551275" in out


@pytest.mark.parametrize(
    "args,needle",
    [
        (["--w-plus", "1", "--V", "7"], "V=7"),
        (["--w-plus", "20"], "w_plus=20"),
        (["--w-plus", "1", "--a", "2"], "a=2"),
        (["--w-plus", "1", "--b", "-1"], "b=-1"),
        (["--w-plus", "abc"], "w-plus"),
    ],
)
def test_bad_input_exit_2_one_line(args, needle, capsys):
    rc = main(["qc", *args]) if "abc" not in args else None
    if rc is None:
        rc, _, err = run(*args)
    else:
        err = capsys.readouterr().err
    assert rc == 2
    assert needle in err and err.count("\n") == 1
