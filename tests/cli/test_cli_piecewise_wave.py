"""`--law "trilinear(...)"` on the wave and Floquet commands: the numbers are the API's for the
law object (text = object), the degenerate law's solitary wave is the explicit compact wave."""

import json

import numpy as np

import fpucore as F
from fpucore.cli import main
from fpucore.law import TrilinearLaw
from fpucore.wave.compact import compact_wave

TEXT = "trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0.2)"
LAW = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)


def test_superkink_from_the_cli_is_the_api_superkink(capsys):
    assert main(["wave", "superkink", "--law", TEXT, "--V", "1.6", "--N", "64", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    r = F.wave.solve_superkink(LAW, 1.6, N=64)
    assert d["converged"] and d["law"] == LAW.expression
    assert d["residual"] == r.residual and d["profile_error"] == r.profile_error


def test_degenerate_solitary_wave_from_the_cli(capsys):
    text = "trilinear(w1=0.5, w2=1.5, E1=0, E2=4, E3=0.2)"
    args = ["wave", "solitary", "--law", text, "--w-plus", "0.2", "--V", "0.5", "--json"]
    assert main(args) == 0
    d = json.loads(capsys.readouterr().out)
    cw = compact_wave(TrilinearLaw(0.5, 1.5, 0.0, 4.0, 0.2), 0.5, 0.2)
    assert d["converged"]
    assert abs(d["amplitude"] - cw.amplitude) <= d["amplitude_error"]


def test_floquet_of_a_trilinear_superkink_from_the_cli(capsys):
    rc = main(["floquet", "superkink", "--law", TEXT, "--V", "1.6", "--N", "64", "--json"])
    assert rc == 0
    out = capsys.readouterr().out
    d = json.loads(out)
    assert np.isfinite(d["error"]) and d["symmetry_error"] <= 1e-12
