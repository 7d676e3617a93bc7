"""The CLI's words fit its numbers: no "nan" where a quantity does not exist, no "0 iterations"
for a wave nobody iterated, no rate for a run that computed nothing, and "out of range" only for
a number outside its range."""

import math

import pytest

from fpucore import CubicLaw, ParameterError, qc, wave
from fpucore.cli import main


def run_cli(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def test_a_superkink_has_no_energy_line_with_nan(capsys):
    code, out, _ = run_cli(capsys, ["wave", "superkink", "--V", "5.2"])
    assert code == 0
    assert "nan" not in out.lower(), out
    assert "E_ren^D n/a" in out
    assert "amplitude 0 (exact by construction)" in out


def test_a_solitary_wave_keeps_its_numbers(capsys):
    code, out, _ = run_cli(capsys, ["wave", "solitary", "--w-plus", "1", "--V", "5"])
    assert code == 0 and "n/a" not in out
    energy = float(out.split("E_ren^D")[1].split()[0])
    assert math.isfinite(energy) and energy > 0


def test_a_flat_top_built_by_the_plateau_route_does_not_claim_zero_iterations():
    """w+ = 1, V = V_SK - 1e-8: the plateau route's mass continuation hands Newton a wave that
    already meets the tolerance (it printed "residual 6.9e-14 in 0 iterations")."""
    law = CubicLaw()
    v_sk = qc.sound_speeds(law, 1.0)[1]
    r = wave.solve_solitary(law, 1.0, v_sk - 1e-8)
    assert r.converged
    assert "in 0 iterations" not in r.message and "in 1 iterations" not in r.message
    if r.iterations == 0:
        assert "with no Newton step: the start wave met the tolerance" in r.message
    assert "plateau route" in r.message


def test_resume_of_a_finished_store_says_nothing_was_left(capsys, tmp_path):
    out_dir = str(tmp_path / "sk.zarr")
    argv = ["atlas", "superkink", "--V", "5.0:5.2:2", "--N", "64", "--out", out_dir,
            "--backend", "inline", "--no-progress"]  # fmt: skip
    code, out, _ = run_cli(capsys, argv)
    assert code == 0 and "2 computed" in out
    code, out, _ = run_cli(capsys, argv + ["--resume"])
    assert code == 0
    assert "nothing left to compute: all 2 points from the store" in out, out
    assert "points/s" not in out and "none workers" not in out, out


@pytest.mark.parametrize(
    "argv, words",
    [
        (["wave", "superkink", "--V", "5.2", "--law", "sin(w)"], "is not valid: expected"),
        (["floquet", "sweep", "superkink", "--V", "5", "--out", "/nonexistent-dir/t.csv"],
         "is not valid: expected a file in an existing directory"),
        (["wave", "superkink", "--V", "nan"], "V=nan is not valid: expected a finite real"),
        (["wave", "superkink", "--V", "9"], "V=9 is out of range: valid ("),
    ],
)  # fmt: skip
def test_refusals_are_worded_by_their_reason(capsys, argv, words):
    code, _, err = run_cli(capsys, argv)
    assert code == 2
    assert words in err, err
    if "out of range" not in words:
        assert "out of range" not in err, err


def test_parameter_error_wording():
    assert str(ParameterError("V", 9.0, "(4, 5)")) == "V=9 is out of range: valid (4, 5)"
    assert str(ParameterError("N", 7, "an even integer >= 8")).startswith("N=7 is out of range")
    assert str(ParameterError("out", "/x/y", "a writable file", "permission denied")) == (
        "out='/x/y' is not valid: expected a writable file (permission denied)"
    )
    assert "is not valid" in str(ParameterError("flag", True, "a number"))


def test_a_value_that_is_not_a_number_is_refused_in_the_readmes_form(capsys):
    """`fpu qc --V abc` answered in argparse's words ("argument --V: invalid float value")."""
    with pytest.raises(SystemExit) as exc:
        main(["qc", "--V", "abc"])
    err = capsys.readouterr().err
    assert exc.value.code == 2
    assert "V='abc' is not valid: expected a real number" in err, err
    assert "invalid float value" not in err and "argument --V" not in err


def test_the_simulation_printout_names_waves_and_the_interval_in_words(capsys):
    code, out, _ = run_cli(capsys, ["simulate", "riemann", "--w-left", "4.6", "--w-right", "0",
                                    "--L", "400", "--t-end", "20",
                                    "--time-budget", "1200"])  # fmt: skip
    assert code == 0, out
    assert "DSW edge" in out and "dsw_edge" not in out, out
    assert "left_convex_interval" not in out
    assert "convex interval (α, β): the strains stayed inside" in out
