"""`--law EXPR` on the command line: any hardening–softening polynomial, parsed by
SymPy; the numbers are those of the API (fpucore.qc.general is checked against mpmath in
tests/law/test_law_general.py), refusals are one line on stderr with exit code 2."""

import json

import pytest

from fpucore import law_from_expression, qc
from fpucore.cli import main

QUARTIC = "w + 10*w**2 - w**3 - 0.01*w**4"


def test_qc_json_with_a_law_expression(capsys):
    assert main(["qc", "--law", QUARTIC, "--w-plus", "1", "--V", "5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    law = law_from_expression(QUARTIC)
    assert d["coeffs"] == [1.0, 10.0, -1.0, -0.01] and "a" not in d
    assert law_from_expression(d["law"]) == law  # the JSON law parses back to the same law
    sk = qc.superkink_from_w_plus(law, 1.0)
    assert d["V_SK"] == sk.V and d["superkink"]["w_minus"] == sk.w_minus
    assert d["superkink"]["symmetry_defect"] == pytest.approx(1.0 + sk.w_minus - 2 * law.w_star)
    assert d["solitary"]["energy"] == qc.solitary(law, 1.0, 5.0).energy
    assert d["solitary"]["energy_error"] > 0


def test_law_replaces_a_b_and_the_cubic_keeps_its_keys(capsys):
    assert main(["qc", "--w-plus", "1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert (d["a"], d["b"]) == (-1.0, 10.0)


def test_wave_with_a_law_expression(capsys):
    rc = main(["wave", "superkink", "--law", QUARTIC, "--V", "5.2", "--N", "64", "--json"])
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["converged"] and d["law"] == law_from_expression(QUARTIC).expression
    sk = qc.superkink_from_V(law_from_expression(QUARTIC), 5.2)
    assert (d["w_left"], d["w_right"]) == (sk.w_minus, sk.w_plus)


@pytest.mark.parametrize(
    "expr, words",
    [
        ("w + (w**2", "could not parse"),
        ("w + sin(w)", "'sin' is not allowed"),
        ("w + 10*w**2 + w**3", "no softening"),
        ("-w + 10*w**2 - w**3", "f'(0) must be positive"),
        ("w + 3*w**2 - 11*w**3/6 + w**4/2 - w**5/20", "inflections"),
        ("w + 1e400*w**2 - w**3", "non-finite"),
    ],
)
def test_law_refusals_are_one_line_with_exit_2(capsys, expr, words):
    assert main(["qc", f"--law={expr}", "--w-plus", "1"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("fpu: error: ") and words in err, err
