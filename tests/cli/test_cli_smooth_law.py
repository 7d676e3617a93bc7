"""`--law EXPR --const NAME=VALUE` on the command line: smooth laws (exp, tanh, quotients …) with
named constants; the numbers are those of the API (checked against mpmath in
tests/qc/test_qc_smooth_law.py), refusals one line on stderr with exit code 2."""

import json

import pytest

from fpucore import law_from_expression, qc
from fpucore.cli import main

EXP = "w + b*w**2 - c*w**3*exp(w/d)"
CONSTS = ["--const", "b=10", "--const", "c=1", "--const", "d=50"]


def test_qc_json_with_a_smooth_law_and_constants(capsys):
    assert main(["qc", "--law", EXP, *CONSTS, "--w-plus", "1", "--V", "5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    law = law_from_expression(EXP, {"b": 10, "c": 1, "d": 50})
    assert d["law"] == EXP and d["constants"] == {"b": 10.0, "c": 1.0, "d": 50.0}
    assert d["represented_interval"] == list(law.interval)
    assert d["representation_error"]["f"] == law.representation_error.f
    assert d["V_SK"] == qc.superkink_from_w_plus(law, 1.0).V


def test_wave_superkink_with_a_smooth_law(capsys):
    rc = main(["wave", "superkink", "--law", EXP, *CONSTS, "--V", "5.2", "--N", "64", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["converged"] and d["law"] == EXP


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--law", EXP], "unknown name 'b'"),
        (["--law", EXP, *CONSTS, "--const", "q=1"], "do not appear"),
        (["--law", EXP, "--const", "b", "--const", "c=1", "--const", "d=50"], "NAME=VALUE"),
        (["--const", "b=1"], "--const needs --law"),
        (["--law", "log(1+w)"], "no softening"),
        (["--law", "w + w**2 - w**3*sqrt(w)"], "fractional power of a negative number"),
    ],
)
def test_refusals_are_one_line_exit_2(capsys, argv, words):
    assert main(["qc", "--w-plus", "0.5", *argv]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1, err


def test_help_describes_smooth_laws(capsys):
    with pytest.raises(SystemExit):
        main(["qc", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "--const NAME=VALUE" in out and "exp, log, sqrt, tanh" in out


def test_top_level_help_names_law_and_const(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "--const NAME=VALUE" in out and "--law EXPR" in out
