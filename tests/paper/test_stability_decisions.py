"""The paper's stability cases decided by the window test (§6; Figs. floquet_SK,
floquet_cubicSW), through the CLI and the API, with a = −1, b = 10.

References: the paper's words — every mild oscillatory instability of superkinks and solitary
waves is "a spurious artifact of the finite chain size" (no row may be "unstable"), and its
bounds on max |μ| (≤ 1.005 over the superkink range, < 1.0001 for V ≥ 5.57, O(1e-8) for
V ≥ 5.74; ≤ 1.0006 at w₊ = 1 and ≤ 1.001 at w₊ = 6).  At other laws the reference is the
definition of an instability of the wave: it must persist on a ring twice as long.
The old three-point test labelled 16 of the 44 rows of the README sweep "unstable".
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from fpucore import atlas, qc, wave
from fpucore import floquet as fq
from fpucore.cli import main as cli_main
from fpucore.law import CubicLaw, PolynomialLaw

LAW = CubicLaw(-1.0, 10.0)


@pytest.mark.slow
def test_readme_superkink_sweep_has_no_unstable_row(capsys, tmp_path, monkeypatch):
    """README: fpu floquet sweep superkink --V-min 4.8 --V-max 5.85 --n 22 --N 200 500."""
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    argv = ["floquet", "sweep", "superkink", "--V-min", "4.8", "--V-max", "5.85", "--n", "22",
            "--N", "200", "500", "--json", "--no-cache"]  # fmt: skip
    assert cli_main(argv) == 0
    obj = json.loads(capsys.readouterr().out)
    assert [s["N"] for s in obj["sweeps"]] == [200, 500]
    for s in obj["sweeps"]:
        rows = s["rows"]
        assert len(rows) == 22 and all(r["floquet_converged"] for r in rows)
        classes = [r["classification"] for r in rows]
        assert "unstable" not in classes, [(r["V"], r["verdict"]) for r in rows]
        for r in rows:
            assert r["classification"] in fq.CLASSES and r["headline"]
            # one record: the sentence starts with the class the headline names
            assert r["verdict"].split(":")[0].split()[0] == r["headline"].split()[0]
            mm = r["max_modulus"]
            if s["N"] != 500:  # the paper's bounds are at its N = 500 (N = 200: up to 1.0094)
                continue
            assert mm < 1.005
            if r["V"] >= 5.57:
                assert mm < 1.0001
            if r["V"] >= 5.74:
                assert mm - 1.0 <= 1e-8 and r["classification"] == "stable"
        for r in rows:  # an open case says what decides it (measured: V = 5.55 at N = 1000)
            if r["classification"] == "undetermined":
                assert f"compute at N >= {2 * s['N']}" in r["verdict"]
        if s["N"] == 500:  # the paper's N: nearly every excess is decided (measured: 21 of 22)
            assert classes.count("undetermined") <= 2


@pytest.mark.slow
@pytest.mark.parametrize("w_plus, bound", [(1.0, 1.0006), (6.0, 1.001)])
def test_solitary_families_have_no_unstable_row(w_plus, bound, tmp_path, monkeypatch):
    """Fig. floquet_cubicSW at N = 500, both velocity intervals (c₊, V_SK) and (V_SK, c₋)."""
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    (cp, vsk), (_, cm) = qc.solitary_intervals(LAW, w_plus)
    t = np.array([0.25, 0.5, 0.75, 0.97])
    Vs = np.concatenate([cp + (vsk - cp) * t, vsk + (cm - vsk) * (1.0 - t)])
    sw = atlas.sweep(LAW, "solitary", Vs, w_plus=w_plus, N=500, use_cache=False)
    assert sw.converged
    assert "unstable" not in sw.classification, [r["verdict"] for r in sw.rows]
    assert np.nanmax(sw.max_modulus) < bound
    assert any(c == "finite_size" for c in sw.classification)  # the excesses are there


def _unstable_survive_doubling(law, kind, Vs, w_plus=None, N=200):
    sw = atlas.sweep(law, kind, Vs, w_plus=w_plus, N=N, use_cache=False)
    assert sw.floquet_converged.any()
    for V, c in zip(sw.V, sw.classification, strict=True):
        if c != "unstable":
            continue
        r = (wave.solve_superkink(law, V, N=2 * N) if kind == "superkink"
             else wave.solve_solitary(law, w_plus, V, 2 * N))  # fmt: skip
        big = fq.spectrum(r, method="structured")
        assert big.classification == "unstable", (V, big.verdict)
    return sw


@pytest.mark.slow
@pytest.mark.parametrize(
    "law", [CubicLaw(-1.0, 6.0), CubicLaw(-2.0, 10.0), PolynomialLaw((1.0, 10.0, -1.0, -0.01))],
    ids=["cubic(-1,6)", "cubic(-2,10)", "quartic"],
)  # fmt: skip
def test_other_laws_every_unstable_survives_twice_the_chain(law, tmp_path, monkeypatch):
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    lo, hi = qc.superkink_velocity_bounds(law)
    sw = _unstable_survive_doubling(law, "superkink", lo + (hi - lo) * np.array([0.1, 0.5, 0.9]))
    assert set(sw.classification) <= set(fq.CLASSES)
    (cp, vsk), _ = qc.solitary_intervals(law, 1.0)
    _unstable_survive_doubling(law, "solitary", cp + (vsk - cp) * np.array([0.5, 0.95]), 1.0)


@pytest.mark.parametrize("N", [40, 80])
def test_quartic_positive_control_is_unstable_at_N_and_2N(N):
    """The quartic's constant state beyond β (f′ < 0): "unstable" on every ring, growth rate
    2√(−f′) per unit time (derived in tests/floquet/test_finite_size.py) at N and at 2N: what
    a genuine instability looks like to the window test at a law other than the paper's."""
    law = PolynomialLaw((1.0, 10.0, -1.0, -0.01))
    w0 = float(law.beta) + 0.5
    fp = float(law.df(w0))
    assert fp < 0
    fr = fq.spectrum(fq.HomogeneousState(law, w0, 6.0, N, convex=False), method="structured")
    assert fr.classification == "unstable" and fr.decision.reason == "persists", fr.verdict
    assert fr.growth_rate == pytest.approx(2.0 * np.sqrt(-fp), rel=1e-9)
