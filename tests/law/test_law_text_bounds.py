"""A force-law text is bounded before any algebra: the strings that froze the server (SymPy
expanding ``(w+1)**100000``, ``w**99999999``, ``w*9**9**9``, a 1e999999 literal) and worse ones
drawn by hypothesis are refused in <= 50 ms each, through the API (``law_from_expression``) and
the CLI (``fpu qc --law``), naming the real cause; legitimate laws still parse.

Every text is tried in a separate worker process (one per module, restarted after a timeout):
on code without the bounds a string hangs for minutes and takes gigabytes, and the test must
fail in seconds and free them, not block the suite."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fpucore.law import PolynomialLaw, law_from_expression
from fpucore.law.polynomial import MAX_DEGREE

# budgets in CPU seconds of the worker (no process start-up in them): the cost of the text, not
# of the processes beside it on a loaded machine; a hang is still caught by TIMEOUT_S (wall)
LIMIT_S = 0.050  # a refusal's budget
# a smooth law (exp, log, ...): accepted after its class check and representation, or refused
# by them (f'' sign changes, domain errors inside (alpha, beta), too steep), within this budget
SMOOTH_S = 0.5
TIMEOUT_S = 10.0  # a worker that has not answered by then has hung

# the worker: reads one JSON line (mode, text), answers the refusal (or law) and its time
WORKER = r"""
import json, sys, time, io, contextlib
from sympy.core.cache import clear_cache
from fpucore.errors import ParameterError
from fpucore.law import law_from_expression
from fpucore.cli import main
for line in sys.stdin:
    mode, text = json.loads(line)
    err = io.StringIO()
    clear_cache()  # each try as new to SymPy as an attacker's next string: no cached subresult
    t0 = time.process_time()
    try:
        if mode == "api":
            law = law_from_expression(text)
            out = {"ok": True, "law": law.expression, "name": None,
                   "smooth": type(law).__name__ == "SmoothLaw"}
        else:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
                rc = main(["qc", "--w-plus", "0.5", "--law=" + text])
            out = {"ok": rc == 0, "rc": rc, "error": err.getvalue()}
    except ParameterError as e:
        out = {"ok": False, "error": str(e), "name": e.name}
    except Exception as e:
        out = {"ok": False, "error": f"{type(e).__name__}: {e}", "name": None}
    out["s"] = time.process_time() - t0
    print(json.dumps(out), flush=True)
"""


class Worker:
    def __init__(self):
        self.proc = None

    def start(self):
        env = dict(os.environ, PYTHONPATH=os.getcwd())
        self.proc = subprocess.Popen([sys.executable, "-c", WORKER], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, text=True, env=env)  # fmt: skip
        self.ask("api", "w + 10*w**2 - w**3")  # imports SymPy: not part of any timing below
        self.ask("cli", "w + 10*w**2 - w**3")  # and the CLI's first thread-policy scan

    def ask(self, mode: str, text: str) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self.start()
        self.proc.stdin.write(json.dumps([mode, text]) + "\n")
        self.proc.stdin.flush()
        t0 = time.monotonic()
        while time.monotonic() - t0 < TIMEOUT_S:
            import select

            ready, _, _ = select.select([self.proc.stdout], [], [], 0.1)
            if ready:
                return json.loads(self.proc.stdout.readline())
        self.proc.kill()  # a hang (old code): free the CPU and memory, fail this text
        self.proc.wait()
        self.proc = None
        pytest.fail(f"{mode}: {text[:60]!r} not answered within {TIMEOUT_S} s")

    def close(self):
        if self.proc is not None:
            self.proc.stdin.close()
            self.proc.wait(timeout=10)


@pytest.fixture(scope="module")
def worker():
    w = Worker()
    yield w
    w.close()


def refused(worker, text: str, *words: str) -> None:
    """Refused by the API and the CLI (``fpu qc --law``, exit 2, one line) in <= LIMIT_S each
    beyond the CLI's own start, naming the expression and a cause.  Times are the best of up to
    three tries: on the shared machine (load 10-18) one try can lose its core for > 50 ms."""
    api_s = cli_s = float("inf")
    for _ in range(3):
        api = worker.ask("api", text)
        assert not api["ok"] and api["name"] == "expression", api
        assert any(w in api["error"] for w in words), api["error"]
        cli = worker.ask("cli", text)
        assert cli["rc"] == 2 and cli["error"].count("\n") == 1, cli
        assert cli["error"].startswith("fpu: error: expression=")
        assert "Traceback" not in cli["error"]
        # the CLI's own cost (parser, thread policy: ~10-50 ms) measured by a text refused at once
        base = worker.ask("cli", "w + x")
        assert base["rc"] == 2 and "unknown name" in base["error"]
        api_s, cli_s = min(api_s, api["s"]), min(cli_s, cli["s"] - base["s"])
        if api_s <= LIMIT_S and cli_s <= LIMIT_S:
            return
    assert api_s <= LIMIT_S and cli_s <= LIMIT_S, (text[:60], api_s, cli_s)


# the strings of the fuzzing report (minutes to hours each before) and their causes
DOS = [
    ("(w+1)**100000", "degree 100000 of (w+1)**100000 exceeds the maximum 16"),
    ("w**99999999", "degree 99999999 of w**99999999 exceeds the maximum 16"),
    ("w*9**9**9", "the number 9**9**9 (about 10^3.7e+08) exceeds the float range"),
    ("w + 1e999999*w**2 - w**3", "the literal 1e999999 exceeds the float range"),
    ("w + " + "9" * 5000 + "*w**2 - w**3", "characters exceed the maximum"),
    ("w + " + "9" * 400 + "*w**2 - w**3", "has 400 digits"),
    ("(1/2)**(10**100)*w + w**2 - w**3", "is below the float range"),
    ("((1+10**-15)**1000)**1000*w", "digits (maximum 2000)"),
    ("w**2**2**2**2", "degree 65536 of w**2**2**2**2 exceeds the maximum 16"),
    ("w**2**2**2**2**2", "the number 2**2**2**2**2 (about 10^1.97e+04) exceeds the float"),
    ("(" * 100 + "w" + ")" * 100, "nesting depth exceeds the maximum 32"),
    ("w" + "+w" * 300, "exceed the maximum 256"),
    ("w + exp(10**6)*w**2", "exceeds the float range"),
]


@pytest.mark.parametrize("text, cause", DOS, ids=[t[:24] for t, _ in DOS])
def test_dos_strings_are_refused_fast_naming_the_cause(worker, text, cause):
    refused(worker, text, cause)


def big_int(draw) -> str:
    return str(draw(st.integers(17, 10**12)))


@st.composite
def worse(draw) -> tuple[str, tuple[str, ...]]:
    """A text whose algebra is unbounded, embedded in a legitimate law: (text, cause words)."""
    kind = draw(st.sampled_from(["power", "nested", "literal", "depth", "sum", "float"]))
    if kind == "power":  # a power of a sum of degree > 16
        base = draw(st.sampled_from(["w", "(w+1)", "(2*w-3/7)", "(w**2+w)", "(w+1)**2"]))
        bad, words = f"{base}**{big_int(draw)}", ("degree",)
    elif kind == "nested":  # a tower of numbers, times w
        n = draw(st.integers(3, 6))
        tower = "**".join(str(draw(st.integers(10, 99))) for _ in range(n))
        bad, words = f"w*{tower}", ("float range", "exceeds the maximum")
    elif kind == "literal":
        digits = draw(st.integers(331, 900))
        lit = draw(st.sampled_from(["1" + "0" * digits, f"1e{draw(st.integers(309, 10**9))}"]))
        bad, words = f"{lit}*w**2", ("float range", "digits")
    elif kind == "depth":
        d = draw(st.integers(33, 400))
        bad, words = "(" * d + "w" + ")" * d, ("nesting depth",)
    elif kind == "sum":  # a long sum raised to a power: degree and length both out of range
        n = draw(st.integers(130, 400))
        bad, words = "(" + "+".join(["w"] * n) + f")**{big_int(draw)}", ("maximum",)
    else:  # a rational near 1 to a huge power: a harmless float, an enormous exact value
        bad, words = f"(1+1/10**15)**{draw(st.integers(10**4, 10**12))}*w", ("digits", "maximum")
    text = draw(st.sampled_from([bad + " + w", f"w + 10*w**2 - w**3 + {bad}", f"w*({bad})"]))
    return text, words + LONG  # a long instance may be refused for its length first


LONG = ("characters exceed the maximum", "terms and operators exceed the maximum")


@settings(
    max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture]
)
@given(worse())
def test_worse_strings_are_refused_fast(worker, case):
    text, words = case
    refused(worker, text, *words)


GOOD = [
    "w + 10*w**2 - w**3",  # README
    "w + 10*w**2 - w**3 - 0.01*w**4",  # the tests' quartic
    "w + 10w^2 - w^3",  # ^ and implicit products
    "w + 21/2*w**2 - 7/3*w**3",  # cubic with rational coefficients
    "w + sqrt(2)*w**2 - w**3/3 - pi*w**4/1000",
    "w*(1 + 10*w - w**2)",
    "w + 10*w**2 - w**3 - 1e-20*w**16",  # the largest degree
    " w + 10*w**2 -\n\tw**3 ",  # surrounding spaces and line breaks are not indentation
]


@pytest.mark.parametrize("text", GOOD)
def test_legitimate_laws_still_parse(text):
    law = law_from_expression(text)
    assert law_from_expression(law.expression) == law  # and round-trip


def test_rational_coefficients_are_exact():
    law = law_from_expression("w + 21/2*w**2 - 7/3*w**3")
    assert law.coeffs == (1.0, 10.5, -7 / 3)
    law = law_from_expression("w + sqrt(2)*w**2 - w**3")
    assert law.coeffs[1] == 2**0.5  # a 30-digit constant rounds to the nearest double


@pytest.mark.parametrize("k", [12, 131])
def test_a_rational_of_hundreds_of_digits_in_a_smooth_law_is_evaluated(k):
    """1.000…01**k simplifies to an exact rational of ~34 k digits: for k = 12 (~400 digits)
    p and q each rounded to inf in double (inf/inf = NaN), for k = 131 (~4500 digits) Python
    refuses ``str`` of an int that long (ValueError); both escaped as bare errors (found by the
    grammar fuzz).  Reference: the binomial expansion, (1 + 1e-33)**k = 1 + k·1e-33 + O(1e-62)."""
    head = "w + 10*w**2 - w**3*exp(w/0.5)"
    law = law_from_expression(head + f" + 1e-3*((1.000000000000000000000000000000001)**({k}))*w")
    ref = law_from_expression(head + f" + 0.001000000000000000000000000000{k:03d}*w")
    for w in (-0.04, 0.3, 0.8):
        assert law.f(w) == pytest.approx(ref.f(w), rel=1e-15, abs=0)


def test_degree_limit_is_the_same_for_text_and_coefficients():
    assert MAX_DEGREE == 16
    with pytest.raises(ValueError, match="degree 17 of w\\*\\*17 exceeds the maximum 16"):
        law_from_expression("w + 10*w**2 - w**3 - 1e-20*w**17")
    with pytest.raises(ValueError, match="degree <= 16"):
        PolynomialLaw((1.0, 10.0, -1.0) + (0.0,) * 13 + (-1e-20,))


# ------------------------------------------------------------------ the grammar, adversarially
# Every text the screen's grammar admits, drawn recursively with the sizes an attacker would
# pick: literals in every base up to beyond the float range, exponents from 0 to 10**12 (also
# negative, fractional, towers), products and powers of sums, functions of huge constants,
# quotients, long sums.  Whatever the text, the API answers (a law or a ParameterError, never
# another exception) within the budget: a refusal in <= 50 ms, and an acceptance within the same
# budget (a legitimate law is built in ~1-10 ms).  The suite runs a moderate number of examples;
# FPU_LAW_FUZZ=N runs N (the hunt for holes: see the module's git log for the figures).


def _literal(draw) -> str:
    kind = draw(st.sampled_from(["small", "dec", "hex", "oct", "bin", "float", "exp", "long"]))
    if kind == "small":
        return str(draw(st.integers(0, 20)))
    n = draw(st.integers(1, 420))  # digits: up to beyond the float range
    if kind == "dec":
        return "9" * n
    if kind == "hex":
        return "0x" + "f" * n
    if kind == "oct":
        return "0o" + "7" * n
    if kind == "bin":
        return "0b" + "1" * n
    if kind == "float":
        return "1." + "0" * (n - 1) + "1"
    if kind == "long":
        return "0." + "3" * n
    return f"1e{draw(st.sampled_from(['', '-']))}{draw(st.integers(0, 400))}"


def _exponent(draw) -> str:
    kind = draw(st.sampled_from(["list", "int", "frac"]))
    if kind == "int":
        return f"({draw(st.integers(-40, 3000))})"
    if kind == "frac":
        return f"({draw(st.integers(-50, 50))}/{draw(st.integers(1, 13))})"
    return draw(
        st.sampled_from(["2", "3", "16", "17", "-1", "-16", "(1/2)", "(1/3)", "0.5", "666",
                         "1100", "1101", "10**12", "9**9**9", "(-1)", "(10**100)", "(2**64)"])
    )  # fmt: skip


@st.composite
def _atom(draw) -> str:
    kind = draw(st.sampled_from(["w", "w", "lit", "lit", "const"]))
    if kind == "w":
        return "w"
    if kind == "const":
        return draw(st.sampled_from(["pi", "E"]))
    return _literal(draw)


def _extend(children):
    def build(draw) -> str:
        kind = draw(st.sampled_from(["sum", "product", "power", "power", "func", "neg", "quot"]))
        if kind == "sum":
            parts = draw(st.lists(children, min_size=2, max_size=8))
            return "(" + "".join(draw(st.sampled_from("+-")) + p for p in parts) + ")"
        if kind == "product":
            parts = draw(st.lists(children, min_size=2, max_size=17))
            return draw(st.sampled_from(["*", ""])).join(f"({p})" for p in parts)  # or implicit
        if kind == "quot":
            return f"({draw(children)})/({draw(children)})"
        if kind == "power":  # ** or ^ (SymPy's convert_xor)
            return f"({draw(children)}){draw(st.sampled_from(['**', '^']))}{_exponent(draw)}"
        if kind == "func":
            fn = draw(st.sampled_from(["sin", "cos", "exp", "log", "sqrt", "tanh", "abs", "sinh",
                                       "cosh", "atan"]))  # fmt: skip
            return f"{fn}({draw(children)})"
        return f"-({draw(children)})"

    return st.composite(build)()


GRAMMAR = st.recursive(_atom(), _extend, max_leaves=60)


@st.composite
def adversarial(draw) -> str:
    """A grammar text, often embedded in a legitimate law (the screen must judge each part)."""
    bad = draw(GRAMMAR)
    c = draw(st.sampled_from(["0.5", "1e-3", "3", "1e3", "1e300", "-2", "0"]))
    return draw(st.sampled_from([
        bad, f"w + 10*w**2 - w**3 + {bad}", f"w*({bad})",
        f"w + 10*w**2 - w**3 + 1e-30*({bad})*w",
        # smooth laws and their domain errors: log of a negative, sqrt below 0, exp overflow
        f"w + 10*w**2 - w**3*exp(w/{c}) + 1e-3*({bad})*w",
        f"w + 10*w**2 - w**3 + log(w + {c}) - log({c})",
        f"w + 10*w**2 - w**3*sqrt(w - {c})",
        f"w + 10*w**2 - w**3*exp({c}*w)",
        f"w + 10*w**2 - w**3*tanh(w*{c}) + sinh(w*{c})/{c}",
    ]))  # fmt: skip


def answered_fast(worker, text: str) -> None:
    """The API's answer (a law or a ParameterError: the expression's or the law's checks) in
    <= LIMIT_S, best of five; a refusal also through the CLI (exit 2, one line)."""
    best = float("inf")
    for _ in range(5):  # the best of five: the cost of the text, not a loaded machine's noise
        api = worker.ask("api", text)
        assert api["ok"] or api["name"] is not None, (text, api)  # a ParameterError
        best = min(best, api["s"])
        smooth = api.get("smooth") or "a smooth expression in w" in api.get("error", "")
        limit = SMOOTH_S if smooth else LIMIT_S
        if best <= limit:
            break
    assert best <= limit, (text, best, api)
    if not api["ok"]:
        cli = worker.ask("cli", text)
        assert cli["rc"] == 2 and cli["error"].count("\n") == 1, (text, cli)
        assert "Traceback" not in cli["error"]


# CI draws the same 150 texts every run (the derandomized profile of tests/conftest.py);
# FPU_HYPOTHESIS=explore FPU_LAW_FUZZ=2000 explores 2000 new ones
@settings(
    max_examples=int(os.environ.get("FPU_LAW_FUZZ", "150")),
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow,
                           HealthCheck.data_too_large],
)  # fmt: skip
@given(adversarial())
def test_any_grammar_text_is_answered_fast(worker, text):
    answered_fast(worker, text)


# holes the grammar found in the screen of an earlier version, each seconds to minutes of SymPy
HOLES = [
    "(1+1/0x" + "f" * 255 + ")**666*w + 10*w**2 - w**3",  # a literal sized by its characters
    "w + (1/(w+1)+1/(w+2)+1/(w+3)+1/(w+4)+1/(w+5))**8",  # quotients by sums: 8.7 s
    "w + ((w+1)**-1+(w+2)**-1+(w+3)**-1+(w+4)**-1)**8",  # negative powers of sums: 2.2 s
    "(w**(1/3)+w**(1/5)+w**(1/7)+w**(1/11))**8",  # fractional powers of w
    "w + 10*w**2 - w**3 + 1e-9*(w + 2**(1/2)+3**(1/3)+5**(1/5)+(-2)**(1/3)+log(-3))**16",
    "w + 10*w**2 - w**3 + 1e-40*" + "*".join(f"(w+{k}.1)" for k in range(1, 17)),  # 0.15 s
    "w + 10*w**2 - w**3 + 1e-40*(w+pi)**16",
    "(0)/(w)",  # a zero coefficient of w^-1: IndexError in the coefficient list
    "(" + "9" * 200 + ")**(1/2)",  # SymPy's evaluation factors the integer: 80 ms
    # f' vanishes within 1e-30 of 0 (beta = 0 on the class check's grid): math domain error
    "w + 10*w**2 - w**3*exp(w/0.5) + 1e-3*((" + "9" * 49 + ")*(-(w)))*w",
]


@pytest.mark.parametrize("text", HOLES, ids=[t[:24] for t in HOLES])
def test_former_holes_are_answered_fast(worker, text):
    answered_fast(worker, text)
