"""Input checks through the command line: extreme laws refused with exit 2 and one
line; a bad --out refused before any computation; negative numbers in any notation are values;
an interrupt gives exit 130 and one line."""

import pytest

from fpucore import atlas
from fpucore import warm as core_warm
from fpucore.cli import main


def one_line_refusal(capsys, argv, needle):
    rc = main(argv)
    out, err = capsys.readouterr()
    assert rc == 2, (out, err)
    assert err.count("\n") == 1 and err.startswith("fpu: error:") and needle in err, err
    assert "Traceback" not in err


@pytest.mark.parametrize(
    "argv",
    [
        ["qc", "--w-plus", "1", "--b", "1.4e154"],
        ["qc", "--w-plus", "0.5", "--a=-1e-300", "--b", "1"],
        ["qc", "--w-plus", "1", "--b", "1e80", "--V", "4e79"],
    ],
)
def test_extreme_laws_exit_2(capsys, argv):
    one_line_refusal(capsys, argv, "(a, b)=")


@pytest.mark.parametrize("out_path", ["{tmp}/missing/dir/t.csv", "{tmp}"])
def test_bad_out_refused_before_the_sweep(capsys, monkeypatch, tmp_path, out_path):
    def no_sweep(*a, **k):  # the check must come first: the sweep is never started
        raise AssertionError("sweep started")

    monkeypatch.setattr(atlas, "sweep", no_sweep)  # what `fpu floquet sweep` runs
    argv = ["floquet", "sweep", "superkink", "--V", "5.2", "--N", "16"]
    one_line_refusal(capsys, [*argv, "--out", out_path.format(tmp=tmp_path)], "--out=")


@pytest.mark.parametrize("value", ["-1e-2", "-1E-2", "-.01", "-1.0e-2"])
def test_negative_numbers_in_scientific_notation_are_values(capsys, value):
    assert main(["qc", "--w-plus", "1", "--a", value, "--json"]) == 0
    assert '"a": -0.01' in capsys.readouterr().out


def test_negative_infinity_is_a_value_and_refused_by_name(capsys):
    one_line_refusal(capsys, ["qc", "--w-plus", "1", "--a", "-inf"], "a=-inf")


def test_interrupt_exit_130_one_line(capsys, monkeypatch):
    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(core_warm, "warm_all", interrupted)  # imported by `fpu warm` as it runs
    assert main(["warm"]) == 130
    assert capsys.readouterr().err == "fpu: interrupted\n"
