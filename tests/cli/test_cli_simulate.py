"""`fpu simulate` contract: JSON keys, exit codes, one-line refusals, progress bar on stderr."""

import json
import subprocess
import sys

import pytest

from fpucore.cli import main
from fpucore.cli.dispatch import build_parser


def run(*args):
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "simulate", *args],
        capture_output=True,
        text=True,
        timeout=300,
    )
    return p.returncode, p.stdout, p.stderr


WAVE_KEYS = {"kind", "velocity", "amplitude", "left_state", "right_state"}


def test_riemann_json_contract():
    rc, out, err = run(
        "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "1800", "--t-end", "150", "--json"
    )
    assert rc == 0, err
    d = json.loads(out)
    for k in ("waves", "energy_drift", "elapsed_s", "status", "error_estimate", "message"):
        assert k in d
    assert d["status"] == "ok" and d["boundary"] == "fixed_particles"
    kinds = [w["kind"] for w in d["waves"]]
    assert kinds == ["superkink", "dsw_edge", "dsw_edge"]
    assert all(WAVE_KEYS <= set(w) for w in d["waves"])
    assert d["waves"][0]["velocity"] == pytest.approx(-5.7209168, abs=1e-6)
    assert d["energy_drift"] < 1e-8 and d["elapsed_s"] > 0
    assert err == ""  # no progress bar when stderr is not a terminal


def test_gaussian_progress_always_and_text(capsys):
    rc = main(
        ["simulate", "gaussian", "--w-B", "1", "--A", "2", "--L", "600", "--t-end", "40",
         "--progress", "always"]
    )  # fmt: skip
    cap = capsys.readouterr()
    assert rc == 0
    assert "100%" in cap.err and "[" in cap.err
    assert "solitary" in cap.out and "energy" in cap.out


def test_refusals_exit_2():
    rc, out, err = run("riemann", "--w-left", "7", "--w-right", "0", "--L", "400", "--t-end", "1")
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and "w_left=7" in err and "alpha" in err
    rc, _, err = run("gaussian", "--w-B", "1", "--A", "6", "--L", "400", "--t-end", "1")
    assert rc == 2 and "guard='bounded'" in err


def test_left_convex_exit_1_with_message():
    rc, out, _ = run(
        "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "400", "--t-end", "5",
        "--boundary", "free", "--json",
    )  # fmt: skip
    assert rc == 1
    d = json.loads(out)
    assert d["stop_reason"] == "left_convex" and "convex interval" in d["message"]


def test_wave_superkink_json():
    pytest.importorskip("fpucore.wave")
    rc, out, err = run("wave", "superkink", "--V", "5.2", "--json")
    assert rc == 0, err
    d = json.loads(out)
    assert d["wave_solve"]["converged"] and d["details"]["periods"] >= 50
    assert d["details"]["velocity_error"] < 1e-8
    (w,) = d["waves"]
    assert w["kind"] == "superkink" and w["velocity"] == pytest.approx(5.2, abs=1e-6)


def test_wave_solitary_json():
    pytest.importorskip("fpucore.wave")
    rc, out, err = run("wave", "solitary", "--w-plus", "1", "--V", "5", "--json")
    assert rc == 0, err
    d = json.loads(out)
    assert d["details"]["kind"] == "tensile" and d["details"]["velocity_error"] < 1e-8


# ------------------------------------------------------------------------- input checks
def test_periods_negative_names_periods():
    """--periods -1 was reported as t_end=-0.19… (after solving the wave): now refused first,
    naming --periods as typed."""
    rc, out, err = run("wave", "superkink", "--V", "5.2", "--periods=-1")
    assert rc == 2 and out == ""
    assert err.count("\n") == 1 and "periods=-1" in err and "t_end" not in err


def test_default_time_budget_is_finite():
    """The CLI never runs unbounded: --time-budget defaults to 60 s."""
    args = build_parser().parse_args(
        ["simulate", "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "400", "--t-end", "1"]
    )
    assert args.time_budget == 60.0


def test_gaussian_runaway_stops_within_time_budget():
    """fpu simulate gaussian --w-B 1 --A 0.5 --L 200 --t-end 10000000 ran for minutes: with
    --time-budget 1 it stops cleanly with the times it reached (exit 1, status "stopped")."""
    rc, out, err = run(
        "gaussian", "--w-B", "1", "--A", "0.5", "--L", "200", "--t-end", "10000000",
        "--time-budget", "1", "--json",
    )  # fmt: skip
    assert rc == 1, err
    d = json.loads(out)
    assert d["status"] == "stopped" and d["stop_reason"] == "time_budget"
    assert "--time-budget" in d["message"] and 0 < d["t_final"] < 1e7
    assert d["details"]["time_budget_s"] == 1.0
    assert d["details"]["work_estimate"]["steps"] > 1e7
    assert d["elapsed_s"] < 30  # bounded, not a timing test


def test_time_budget_and_memory_budget_refusals():
    rc, _, err = run(
        "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "400", "--t-end", "1",
        "--time-budget=-1",
    )  # fmt: skip
    assert rc == 2 and err.count("\n") == 1 and "time_budget=-1" in err
    rc, _, err = run(
        "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "1000000", "--t-end", "0.01",
        "--snapshots", "100000", "--max-sites", "1000000",
    )  # fmt: skip
    assert rc == 2 and err.count("\n") == 1 and "n_snapshots=100000" in err and "GiB" in err
    rc, _, err = run(
        "riemann", "--w-left", "4.6", "--w-right", "0", "--L", "4000", "--t-end", "1",
        "--memory-budget", "1MiB",
    )  # fmt: skip
    assert rc == 2 and "1 MiB" in err


def test_wave_superkink_4_805_has_shape_error():
    """--V 4.805: 50·(1/V) exceeds 50/V by one ulp; the shape check was silently skipped."""
    rc, out, err = run("wave", "superkink", "--V", "4.805", "--json")
    assert rc == 0, err
    d = json.loads(out)["details"]
    assert d["periods"] == 50 and d["shape_error"] < 1e-6
