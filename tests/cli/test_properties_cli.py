"""Property test, command line: every ``fpu`` command driven in-process
(``fpucore.cli.main(argv)``) with arbitrary option values — huge and tiny numbers, NaN, inf,
negative numbers in every notation, words, empty strings, missing or repeated options.

The property: exit 2 with exactly one line on stderr (``fpu: error: ...``) and no traceback; or
exit 0 (or 1 = computed but not converged, with its reason) with output whose numbers are right:
``fpu qc --json`` is checked against closed forms in exact rational arithmetic (c₊² = f′(w₊),
the Rayleigh relation eq. Rline of the superkink, the zero driving force eq. zero_G), other JSON
outputs must carry finite error estimates when they exit 0.  Never another exception, never a
hang (small sizes; hypothesis with derandomize=True, so the examples are fixed).
"""

from __future__ import annotations

import contextlib
import io
import json
from fractions import Fraction

import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from fpucore import atlas, wave
from fpucore.cli import main

CLI = settings(
    derandomize=True,
    max_examples=250,
    deadline=None,
    database=None,
    suppress_health_check=list(HealthCheck),
)

WILD = st.one_of(
    st.sampled_from(
        [
            "nan",
            "NaN",
            "inf",
            "-inf",
            "1e400",
            "-1e400",
            "1e-300",
            "-1e-300",
            "1e300",
            "-1e300",
            "0",
            "-0",
            "-0.0",
            "abc",
            "",
            "True",
            "None",
            "1_0",
            "0x10",
            " 5",
            "1e",
            "--",
            "-",
            "5e-324",
            "-1e-2",
            "1,5",
        ]  # fmt: skip
    ),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-(10**20), 10**20).map(str),
)


def num(lo: float, hi: float):
    """(good, bad) texts for a number: plausible values in [lo, hi], or anything (WILD)."""
    return st.floats(lo, hi).map(st_format), WILD


def pick(good: list[str], bad: list[str]):
    return st.sampled_from(good), st.sampled_from(bad)


def st_format(x: float) -> str:
    return f"{x:.6g}" if abs(x) >= 1e-3 or x == 0 else f"{x:.3e}"


def run_cli(argv: list[str]) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = main(argv)
        except SystemExit as exc:  # argparse refusals
            rc = exc.code if isinstance(exc.code, int) else 2
    return rc, out.getvalue(), err.getvalue()


def check_exit(argv, rc, out, err) -> None:
    event(f"exit {rc}")  # the statistics (--hypothesis-show-statistics) show both outcomes occur
    assert "Traceback" not in err, (argv, err)
    if rc == 2:
        assert err.startswith("fpu: error:") and err.count("\n") == 1, (argv, err)
        return
    assert rc in (0, 1), (argv, rc, err)


@st.composite
def options(draw, spec: dict, flags: tuple = ()) -> list[str]:
    """argv pieces from spec = {option: (good values, bad values)}: a third of the examples use
    good values throughout, a third spoil exactly one option (bad value or missing), a third
    draw every option freely (good, bad or missing; value sometimes glued with '=')."""
    mode = draw(st.sampled_from(["clean", "one", "free"]))
    spoiled = draw(st.sampled_from(sorted(spec))) if mode == "one" else None
    argv: list[str] = []
    for opt, (good, bad) in spec.items():
        if mode == "free":
            how = draw(st.sampled_from(["good", "good", "bad", "missing"]))
        elif opt == spoiled:
            how = draw(st.sampled_from(["bad", "bad", "missing"]))
        else:
            how = "good"
        if how == "missing":
            continue
        v = draw(good if how == "good" else bad)
        argv += [f"{opt}={v}"] if draw(st.booleans()) and not v.startswith(" ") else [opt, v]
    for flag in flags:
        if draw(st.booleans()):
            argv.append(flag)
    return argv


LAW_OPTS = {"--a": (st.sampled_from(["-1", "-1e-2", "-5", "-1e-3"]), WILD),
            "--b": (st.sampled_from(["10", "100", "0.2", "1e5"]), WILD)}  # fmt: skip


# ----------------------------------------------------------------------------- fpu qc
def _F(x) -> Fraction:
    return Fraction(float(x))


def check_qc_json(d: dict) -> None:
    a, b, wp = _F(d["a"]), _F(d["b"]), _F(d["w_plus"])
    f = lambda x: ((a * x + b) * x + 1) * x  # noqa: E731
    ft = lambda x: ((abs(a) * abs(x) + b) * abs(x) + 1) * abs(x)  # noqa: E731
    phi = lambda x: ((a / 4 * x + b / 3) * x + Fraction(1, 2)) * x * x  # noqa: E731
    dfp = (3 * a * wp + 2 * b) * wp + 1
    assert abs(_F(d["c_plus"]) ** 2 - dfp) <= Fraction(1, 10**15) * dfp  # eq. cplus, to an ulp
    assert d["c_plus"] <= d["V_SK"] <= d["c_minus"]
    sk = d["superkink"]
    wm, V2 = _F(sk["w_minus"]), _F(sk["V"]) ** 2
    assert sk["V"] == d["V_SK"]
    scale = ft(wp) + ft(wm) + V2 * (abs(wm) + abs(wp))
    assert abs(f(wm) - f(wp) - V2 * (wm - wp)) <= 1e-12 * scale  # eq. Rline
    G = phi(wm) - phi(wp) - (f(wp) + f(wm)) / 2 * (wm - wp)  # eq. zero_G (equal areas)
    assert abs(G) <= 1e-12 * scale * (abs(wm) + abs(wp) + 1)
    for k in ("rayleigh_residual", "driving_force"):
        assert sk[k] is not None and sk[k] <= 1e-9
    if "solitary" in d:
        s = d["solitary"]
        assert d["c_plus"] < s["V"] < d["c_minus"]
        for k in ("energy", "energy_error", "first_integral_residual", "gamma", "w_M", "w_T"):
            assert s[k] is not None, k  # a null is a NaN or inf printed with exit 0
        assert s["first_integral_residual"] <= 1e-9


@CLI
@given(
    options(
        {**LAW_OPTS, "--w-plus": num(-0.2, 7.0), "--V": num(3.0, 6.0)},
        flags=("--json",),
    )
)
def test_fpu_qc(argv):
    argv = ["qc", *argv]
    rc, out, err = run_cli(argv)
    check_exit(argv, rc, out, err)
    if rc == 0 and "--json" in argv:
        check_qc_json(json.loads(out))
    elif rc == 0:
        assert "nan" not in out.lower() and "inf" not in out.lower(), out
    assert rc != 1


# ----------------------------------------------------------------------------- fpu wave
WAVE_LAW = {"--a": pick(["-1", "-1e-0"], ["nan", "abc", "1", "-1e300"]),
            "--b": pick(["10", "1e1"], ["-10", "1e300", "inf"])}  # fmt: skip
N_TEXT = pick(["64", "100"], ["7", "0", "-64", "1e3", "abc", "", "20001", "64.0"])
TOL_TEXT = pick(["1e-10", "1e-12"], ["0", "-1e-10", "nan", "1e-2", "abc"])


def check_wave_json(argv, rc, out) -> None:
    if "--json" not in argv or rc == 2:
        return
    d = json.loads(out)
    assert d["converged"] is (rc == 0)
    for k in ("residual", "dropped_residual", "tail_error", "integrator_error"):
        if rc == 0:
            assert d[k] is not None, k


@settings(CLI, max_examples=30)
@given(
    st.sampled_from(["superkink", "solitary"]),
    st.data(),
)
def test_fpu_wave(kind, data):
    spec = {**WAVE_LAW, "--V": num(4.8, 5.8), "--N": N_TEXT, "--tol": TOL_TEXT}
    if kind == "solitary":
        spec["--w-plus"] = num(0.5, 6.0)
    else:
        spec["--branch"] = pick(["lower", "upper"], ["middle", ""])
    argv = ["wave", kind, *data.draw(options(spec, flags=("--json",)))]
    rc, out, err = run_cli(argv)
    check_exit(argv, rc, out, err)
    check_wave_json(argv, rc, out)


# ----------------------------------------------------------------------------- fpu floquet
@settings(CLI, max_examples=12)
@given(st.data())
def test_fpu_floquet_one(data):
    spec = {**WAVE_LAW, "--V": num(5.0, 5.5), "--N": pick(["64"], ["7", "0", "abc", "3000", "-2"]),
            "--m": pick(["40", "60"], ["1", "abc", "-3", "0"])}  # fmt: skip
    argv = ["floquet", "superkink", *data.draw(options(spec, flags=("--json",)))]
    rc, out, err = run_cli(argv)
    check_exit(argv, rc, out, err)
    if rc == 0 and "--json" in argv:
        d = json.loads(out)
        for k in ("error", "symmetry_error", "integrator_error", "conservation_defect"):
            assert d[k] is not None, k


@pytest.fixture(scope="module")
def out_paths(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("out")
    return [str(tmp / "missing" / "t.csv"), str(tmp), str(tmp / "t.csv"), "", "/proc/x.json"]


class ValidSweep(Exception):
    """Raised by the stub sweep: the command accepted its arguments (no real sweep is run)."""


@pytest.fixture
def stub_sweep(monkeypatch, tmp_path):
    """Sweeps in this module write no cache into the working tree and do no real work: the stub
    validates exactly as the sweep does, then stops."""
    monkeypatch.setenv("FPU_CACHE_DIR", str(tmp_path))
    real_check = atlas.sweeps.check_sweep_args

    def stub(law, kind, V_values, w_plus=None, N=500, progress=None, branch="lower", m=None,
             tol=1e-12, use_cache=True, time_budget_s=3600.0, **kw):  # fmt: skip
        real_check(law, kind, V_values, w_plus, N, branch, m, tol, time_budget_s)
        for v in V_values:  # the sweep's own up-front check of every velocity
            wave.superkink_spec(law, float(v), branch) if kind == "superkink" else (
                wave.solitary_spec(law, w_plus, float(v)))  # fmt: skip
        raise ValidSweep

    monkeypatch.setattr(atlas, "sweep", stub)


@settings(CLI, max_examples=40)
@given(st.data())
def test_fpu_floquet_sweep_refusals(out_paths, stub_sweep, data):
    """Everything the sweep command refuses, it refuses before sweeping, in one line."""
    spec = {
        **WAVE_LAW,
        "--V": pick(["5.2", "5.3"], ["nan", "-1", "abc", "1e300", "5.2 5.3", "7"]),
        "--V-min": num(4.8, 5.8),
        "--V-max": num(4.8, 5.8),
        "--n": pick(["2", "3"], ["1", "0", "-5", "10001", "abc"]),
        "--N": pick(["16", "64"], ["7", "10**6", "1000000", "-2", "abc"]),
        "--out": pick(out_paths[2:3], out_paths[:2] + out_paths[3:]),
        "--w-plus": num(0.5, 6.0),
    }
    kind = data.draw(st.sampled_from(["superkink", "solitary", "other"]))
    argv = ["floquet", "sweep", kind, *data.draw(options(spec)), "--no-progress", "--no-cache"]
    try:
        rc, out, err = run_cli(argv)
    except ValidSweep:
        return
    check_exit(argv, rc, out, err)
    assert rc == 2


# ----------------------------------------------------------------------------- fpu simulate
SIM_COMMON = {
    "--method": pick(["rkn12", "dop853"], ["euler", ""]),
    "--rtol": pick(["1e-8", "1e-10"], ["0", "-1", "nan", "1"]),
    "--snapshots": pick(["10", "50"], ["0", "-1", "abc", "100000000"]),
    "--max-sites": pick(["50", "1000"], ["0", "-5", "1e3"]),
    "--progress": pick(["never", "always"], ["sometimes"]),
}
L_TEXT = pick(["40", "100"], ["7", "0", "-40", "abc", "1e9", "40.0", "1000000000000"])
T_TEXT = (st.floats(0.0, 2.0).map(st_format), st.sampled_from(["0", "-1", "nan", "inf", "abc"]))


def check_sim_json(argv, rc, out) -> None:
    if "--json" not in argv or rc == 2:
        return
    d = json.loads(out)
    if rc == 0:
        for k in ("error_estimate", "energy_drift"):
            assert d[k] is not None, k


@settings(CLI, max_examples=40)
@given(st.sampled_from(["riemann", "gaussian"]), st.data())
def test_fpu_simulate(scenario, data):
    if scenario == "riemann":
        spec = {"--w-left": num(-0.2, 7.0), "--w-right": num(-0.2, 7.0)}
    else:
        spec = {"--w-B": num(-0.2, 7.0), "--A": num(-7.0, 7.0),
                "--guard": pick(["convex", "bounded"], ["none"])}  # fmt: skip
    spec |= {"--L": L_TEXT, "--t-end": T_TEXT, **SIM_COMMON}
    argv = ["simulate", scenario, *data.draw(options(spec, flags=("--json",)))]
    rc, out, err = run_cli(argv)
    check_exit(argv, rc, out, err)
    check_sim_json(argv, rc, out)


@settings(CLI, max_examples=10)
@given(st.data())
def test_fpu_simulate_wave(data):
    spec = {"--V": num(5.0, 5.5), "--L": pick(["200", "300"], ["7", "abc", "-4"]),
            "--periods": pick(["2", "1", "0.5"], ["2"])}  # fmt: skip
    argv = ["simulate", "wave", "superkink", *data.draw(options(spec, flags=("--json",)))]
    rc, out, err = run_cli(argv)
    check_exit(argv, rc, out, err)
    check_sim_json(argv, rc, out)


@CLI
@given(st.lists(WILD, max_size=4))
def test_unknown_commands_and_words(words):
    rc, out, err = run_cli(words)
    check_exit(words, rc, out, err)
    assert rc == 2
