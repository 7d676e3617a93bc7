"""``fpu wave`` command line: JSON contract and refusal of bad input (exit code 2)."""

import json

import numpy as np
import pytest

from fpucore.cli import main

KEYS = {
    "kind",
    "V",
    "N",
    "w_left",
    "w_right",
    "residual",
    "dropped_residual",
    "iterations",
    "converged",
    "elapsed_s",
    "amplitude",
    "energy",
    "qc_max_deviation",
    "n",
    "w",
    "wdot",
}


def test_superkink_json(capsys):
    assert main(["wave", "superkink", "--V", "5.2", "--N", "500", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert KEYS <= d.keys()
    assert d["kind"] == "superkink" and d["N"] == 500 and d["converged"] is True
    assert d["residual"] <= 1e-11 and d["dropped_residual"] <= 1e-11
    assert d["energy"] is None  # E_ren^D is defined for solitary waves only
    assert len(d["n"]) == len(d["w"]) == len(d["wdot"]) == 500
    assert d["n"][0] == -250 and abs(d["w"][250] - 10 / 3) < 0.5


def test_solitary_json_and_law_args(capsys):
    assert main(["wave", "solitary", "--w-plus", "6", "--V", "5.0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["kind"] == "compressive" and d["converged"] and np.isfinite(d["energy"])
    assert main(["wave", "superkink", "--V", "2.1", "--a", "-2", "--b", "5", "--json"]) == 0
    d2 = json.loads(capsys.readouterr().out)
    assert d2["a"] == -2 and d2["b"] == 5 and d2["converged"]


def test_text_output(capsys):
    assert main(["wave", "superkink", "--V", "5.5", "--branch", "upper"]) == 0
    out = capsys.readouterr().out
    assert "superkink" in out and "residual" in out and "dropped eq." in out


@pytest.mark.parametrize(
    "argv",
    [
        ["wave", "superkink", "--V", "7"],
        ["wave", "superkink", "--V", "nan"],
        ["wave", "superkink", "--V", "5.2", "--N", "501"],
        ["wave", "solitary", "--w-plus", "1", "--V", "5.6"],
        ["wave", "solitary", "--w-plus", "inf", "--V", "5"],
    ],
)
def test_bad_input_exit_2(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("fpu: error:") and "valid" in err and err.count("\n") == 1
