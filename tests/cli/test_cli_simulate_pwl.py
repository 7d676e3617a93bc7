"""`fpu simulate riemann --law '<piecewise-linear text>'`: the degenerate zero-modulus trilinear
law runs with event location at its breakpoints, and its waves are tracked.  Reference: an exact
symmetry, not the code's own numbers — w ↦ 2 − w, n ↦ −n maps the law with E1 = 0 (soundless
regime w < 0.5) on Riemann data 1 | 0 onto the law with E3 = 0 (soundless w > 1.5) on data 2 | 1
(f ↦ const − f on the strains reached), so each tracked wave of one run is the other's, mirrored:
velocity −V, amplitude −A.  The two runs cross different breakpoints from opposite sides."""

import json
import subprocess
import sys

import pytest

E1_ZERO = "trilinear(w1=0.5, w2=1.5, E1=0, E2=4, E3=0.2)"
E3_ZERO = "trilinear(w1=0.5, w2=1.5, E1=1, E2=4, E3=0)"


def run(law, wl, wr):
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "simulate", "riemann", "--law", law, "--w-left", wl,
         "--w-right", wr, "--L", "400", "--t-end", "30", "--guard", "bounded", "--time-budget",
         "900", "--json"],
        capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert p.returncode == 0, p.stderr
    return json.loads(p.stdout)


def test_degenerate_riemann_run_from_the_cli_tracks_mirrored_waves():
    a, b = run(E1_ZERO, "1", "0"), run(E3_ZERO, "2", "1")
    for d in (a, b):
        assert d["status"] == "ok" and d["energy_drift"] < 1e-12
        det = d["details"]
        assert det["event_location"] and det["breakpoint_crossings"] > 500
        assert det["location_residual"] <= 1e-15
        assert len(d["waves"]) == 2
    wa = sorted(a["waves"], key=lambda w: w["velocity"])
    wb = sorted(b["waves"], key=lambda w: -w["velocity"])
    for x, y in zip(wa, wb, strict=True):
        assert x["kind"] == y["kind"]
        tol = x["velocity_error"] + y["velocity_error"]
        assert x["velocity"] == pytest.approx(-y["velocity"], abs=tol)
        assert x["amplitude"] == pytest.approx(-y["amplitude"], abs=1e-6)
    # the front into the soundless regime: the run's slowest-moving, sharpest structure
    assert abs(wa[1]["velocity"] + wb[1]["velocity"]) < 1e-6


def test_a_method_without_event_location_is_refused_naming_method():
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "simulate", "riemann", "--law", E1_ZERO, "--w-left",
         "1", "--w-right", "0", "--L", "100", "--t-end", "1", "--guard", "bounded", "--method",
         "dop853"],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert p.returncode == 2
    assert "method" in p.stderr and "event location" in p.stderr


def test_velocity_jump_from_the_cli_tracks_the_train_of_compact_waves():
    """`fpu simulate velocity-jump ... --train right`: the train's velocity against the mass
    balance written out here, V δ/(1 − πV/(2√(2E₂))) = |v_left| (spacing 2), δ = w₁ − w_B."""
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "simulate", "velocity-jump", "--law", E1_ZERO,
         "--w-left", "0.2", "--w-right", "0.2", "--v-left", "-0.2", "--L", "200", "--t-end", "60",
         "--guard", "bounded", "--probes", *map(str, range(104, 116)), "--train", "right",
         "--json"],
        capture_output=True, text=True, timeout=900,
    )  # fmt: skip
    assert p.returncode == 0, p.stderr
    tr = json.loads(p.stdout)["train"]
    delta, q = 0.5 - 0.2, 0.2
    V = q / (delta + q * 3.141592653589793 / (2 * 8**0.5))
    assert tr["converged"] and tr["n_waves"] >= 8
    assert abs(tr["velocity"] - V) <= tr["velocity_error"]
    assert abs(tr["spacing"] - 2) <= tr["spacing_error"]


def test_velocity_jump_bad_velocity_refused_naming_it():
    p = subprocess.run(
        [sys.executable, "-m", "fpucore", "simulate", "velocity-jump", "--law", E1_ZERO,
         "--w-left", "0.2", "--w-right", "0.2", "--v-left", "nan", "--L", "64", "--t-end", "1",
         "--guard", "bounded"],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert p.returncode == 2 and "v_left" in p.stderr
