"""The dashboard's laws: the cubic (a, b) or a typed expression (a polynomial, or a smooth law
with named constants), and their exact cache-key form.

A law with constants is one text, ``"<expression>; name=value, name=value"`` (the form
fpucore's refusals show it in): the state, the URL's ``law=``, the worker's memo and the scenes'
dependencies all carry that one string; :func:`split_law` / :func:`join_law` convert.

fpucore builds the laws; this module adds what the app needs around them: coefficients too
large for the closed forms are refused as a ParameterError (never an overflow on screen), a
typed expression is built once (memoised) in a worker process with a time and memory budget
(never in the server process: its text comes from a link), and :func:`law_key` is the law's
part of every cache key (:mod:`app.compute.cache`).
"""

from __future__ import annotations

import contextlib
import resource
import threading
import time
from collections import OrderedDict
from concurrent.futures import Future

import numpy as np

from fpucore import qc
from fpucore.errors import ParameterError
from fpucore.law import (
    CubicLaw,
    HardeningSofteningLaw,
    PiecewiseLinearLaw,
    PolynomialLaw,
    TrilinearLaw,
    law_from_expression,
)
from fpucore.law.smooth import SmoothLaw
from fpucore.parallel import Executor

from .cache import exact

__all__ = [
    "law",
    "expression_law",
    "trusted_expression_law",
    "lookup_law",
    "request_law",
    "build_law_job",
    "shutdown_law_executor",
    "building_page",
    "make_law",
    "law_key",
    "split_law",
    "join_law",
    "law_from_text",
    "qc_method",
]

CONSTANTS_VALID = "name=value pairs separated by commas after ';', e.g. 'w + b*w**2; b=10'"


def split_law(text: str) -> tuple[str, dict[str, float]]:
    """``"<expression>; b=10, c=1"`` → (expression, {"b": 10.0, "c": 1.0}); no ``;``: no
    constants.  Raises ParameterError (named ``constants``) for a malformed pair."""
    expr, sep, rest = text.partition(";")
    consts: dict[str, float] = {}
    if not sep:
        return text.strip(), consts
    for pair in (p.strip() for p in rest.split(",")):
        name, eq, value = (x.strip() for x in pair.partition("="))
        try:
            if not (eq and name.isidentifier()):
                raise ValueError
            consts[name] = float(value)
        except ValueError:
            # named as the law the user typed (a URL's law=, the law box), the pair in the reason
            raise ParameterError(
                "law",
                _short(text),
                CONSTANTS_VALID,
                f"{_short(pair)!r} after ';' is not a name=value pair",
            ) from None
    return expr.strip(), consts


def join_law(expression: str, constants: dict) -> str:
    """The one text of an expression with its constants (exact reprs), inverse of split_law."""
    if not constants:
        return expression
    return f"{expression}; " + ", ".join(f"{n}={float(v)!r}" for n, v in constants.items())


def law_from_text(text: str):
    """fpucore.law_from_expression of a law text with its constants (split_law)."""
    expr, consts = split_law(text)
    return law_from_expression(expr, consts or None)


def law(a: float, b: float) -> CubicLaw:
    """The cubic law f(w) = a w³ + b w² + w (raises ParameterError for a ≥ 0, b ≤ 0, or
    coefficients so large that its closed forms overflow)."""
    try:
        lw = CubicLaw(a=float(a), b=float(b))
        # the closed forms the scenes use first (α, β, w*, c_max) must be finite doubles
        if not all(np.isfinite([lw.alpha, lw.beta, lw.w_star, float(lw.f(lw.beta))])):
            raise OverflowError
        return lw
    except OverflowError:
        raise ParameterError(
            "b", float(b), "|b| small enough for double precision (e.g. b <= 1e100)", "overflow"
        ) from None


#: a typed law is built in a worker process within these budgets: the text comes from a link or
#: the law box, and a pathological one (``(w+1)**100000``, ``w*9**9**9``) once held the whole
#: server for minutes and gigabytes.  The time counts from the job's start in its worker (a
#: legitimate law takes milliseconds; SymPy's import on a fresh worker ~0.3 s).
LAW_TIME_S = 3.0
LAW_MEMORY_BYTES = 512 * 2**20
#: a worker killed for its budget is replaced; a law waits for a worker's start at most this long
LAW_START_S = 60.0
_MEMO_SIZE = 1024

_memo: OrderedDict[str, PolynomialLaw | ParameterError] = OrderedDict()
_pending: dict[str, Future] = {}
_lock = threading.Lock()
_executor: list[Executor] = []


def _law_executor() -> Executor:
    """The one worker process that builds typed laws (its own, not the heavy pool: a busy pool
    never delays a law, and a law stopped for its budget never kills a heavy job)."""
    with _lock:
        if not _executor:
            _executor.append(Executor(backend="process", workers=1))
        return _executor[0]


def shutdown_law_executor() -> None:
    with _lock:
        ex = _executor.pop() if _executor else None
    if ex is not None:
        ex.shutdown()


def _short(expression: str) -> str:
    return expression if len(expression) <= 60 else expression[:40] + "…"


def _refusal(expression: str, reason: str) -> ParameterError:
    valid = f"a law built within {LAW_TIME_S:g} s and {LAW_MEMORY_BYTES >> 20} MiB"
    return ParameterError("expression", _short(expression), valid, reason)


def build_law_job(expression: str, progress=None) -> PolynomialLaw | ParameterError:
    """Run in the law worker: fpucore.law_from_expression under an address-space limit of
    LAW_MEMORY_BYTES beyond the worker's current size (restored afterwards).  Returns the law or
    the ParameterError that refuses it (never raises).  ``progress(0)`` marks the start of the
    budgeted part: a fresh worker first imports SymPy (seconds on a loaded machine)."""
    import sympy  # noqa: F401 - in the worker, before the budget starts (never in the server)

    if progress is not None:
        progress(0.0)

    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as f:
        vm = int(f.read().split()[0]) * resource.getpagesize()
    limit = vm + LAW_MEMORY_BYTES
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    try:
        lw = law_from_text(expression)
        try:  # the law's characteristic strains, computed here rather than in the server
            lw.alpha, lw.beta, lw.w_star  # noqa: B018
        except ParameterError:
            pass
        return lw
    except ParameterError as exc:
        return exc
    except MemoryError:
        return _refusal(expression, f"needs more than {LAW_MEMORY_BYTES >> 20} MiB to build")
    except RecursionError:
        return _refusal(expression, "nested too deeply")
    except Exception as exc:  # noqa: BLE001 - any failure of the algebra is a refusal
        return _refusal(expression, f"could not be built: {type(exc).__name__}")
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _remember(expression: str, outcome) -> None:
    with _lock:
        _memo[expression] = outcome
        _memo.move_to_end(expression)
        while len(_memo) > _MEMO_SIZE:
            _memo.popitem(last=False)
        fut = _pending.pop(expression, None)
    if fut is not None:
        fut.set_result(outcome)


def _watch(expression: str, job) -> None:
    """Wait for the law job within its budgets; kill it past them; remember the outcome."""
    t_end = time.monotonic() + LAW_START_S
    # the budget starts when the job reports its start (a worker may be starting before it)
    while job.progress is None and not job.done() and time.monotonic() < t_end:
        time.sleep(0.005)
    try:
        outcome = job.result(timeout=LAW_TIME_S)
    except TimeoutError:
        job.cancel()  # the worker process is terminated (and replaced)
        outcome = _refusal(expression, f"took longer than {LAW_TIME_S:g} s to build: stopped")
    except Exception as exc:  # noqa: BLE001 - a dead worker, a cancelled job: a refusal
        outcome = _refusal(expression, f"could not be built: {type(exc).__name__}")
    _remember(expression, outcome)


def lookup_law(expression: str) -> PolynomialLaw | ParameterError | None:
    """The outcome of a law already built (or refused), else None (never blocks)."""
    with _lock:
        return _memo.get(expression)


def request_law(expression: str) -> Future:
    """A future of the law's outcome (the PolynomialLaw, or the ParameterError refusing it),
    built in the law worker within LAW_TIME_S and LAW_MEMORY_BYTES.  Never blocks."""
    with _lock:
        fut = _pending.get(expression)
        if fut is not None:
            return fut
        fut = Future()
        if expression in _memo:
            fut.set_result(_memo[expression])
            return fut
        _pending[expression] = fut
    try:
        job = _law_executor().submit(build_law_job, expression)
    except Exception as exc:  # noqa: BLE001
        _remember(expression, _refusal(expression, f"no law worker: {type(exc).__name__}"))
        return fut
    threading.Thread(target=_watch, args=(expression, job), daemon=True, name="law").start()
    return fut


_page = threading.local()


@contextlib.contextmanager
def building_page():
    """Around a page build (app/main.py, on the server's event loop): meanwhile
    :func:`expression_law` never waits for a law in this thread."""
    _page.building = True
    try:
        yield
    finally:
        _page.building = False


def _on_event_loop() -> bool:
    return getattr(_page, "building", False)


def expression_law(expression: str) -> PolynomialLaw:
    """The PolynomialLaw of a typed expression (fpucore.law_from_expression, built in the law
    worker within its budgets, memoised).  Raises its ParameterError.

    Never blocks the server's event loop: there, a law not built yet raises a ParameterError
    saying it is being checked (the explorer re-renders once it is, see app.law_editor);
    elsewhere (a websocket handler thread, a scene's thread, a script) it waits for the outcome,
    at most LAW_START_S + LAW_TIME_S."""
    outcome = lookup_law(expression)
    if outcome is None:
        fut = request_law(expression)
        if _on_event_loop() and not fut.done():
            raise ParameterError(
                "law",
                _short(expression),
                "a law whose check has finished",
                f"still being checked in a worker process (at most {LAW_TIME_S:g} s)",
            )
        outcome = fut.result()
    if isinstance(outcome, ParameterError):
        # a fresh exception: re-raising the stored one would grow its traceback
        raise ParameterError(outcome.name, outcome.value, outcome.valid, outcome.reason)
    return outcome


def trusted_expression_law(expression: str) -> PolynomialLaw:
    """The law of an expression the app wrote itself (``expression_of`` of at most
    MAX_COEFF_SLIDERS finite coefficients, a cubic's ``as_polynomial``): bounded, so parsed in
    this process at once (a coefficient slider needs no worker round trip).  Memoised."""
    outcome = lookup_law(expression)
    if outcome is None:
        try:
            outcome = law_from_text(expression)
        except ParameterError as exc:
            outcome = exc
        _remember(expression, outcome)
    if isinstance(outcome, ParameterError):
        raise ParameterError(outcome.name, outcome.value, outcome.valid, outcome.reason)
    return outcome


def make_law(a: float, b: float, expression: str = "") -> HardeningSofteningLaw:
    """The explorer's law: the cubic (a, b) when ``expression`` is empty, else the polynomial
    law of the expression (fpucore.law_from_expression).  Raises ParameterError."""
    if expression:
        return expression_law(expression)
    return law(a, b)


def law_key(lw: HardeningSofteningLaw) -> tuple:
    """Exact cache-key form of a law: its kind and coefficients (repr).  The cubic and the same
    cubic as a PolynomialLaw are different keys: different routes (closed forms vs numerical)."""
    if isinstance(lw, CubicLaw):
        return ("cubic", exact(lw.a), exact(lw.b))
    if isinstance(lw, PolynomialLaw):
        return ("poly", *(exact(c) for c in lw.coeffs))
    if isinstance(lw, SmoothLaw):
        return ("smooth", lw.text, *((n, exact(v)) for n, v in lw.constants))
    if isinstance(lw, (TrilinearLaw, PiecewiseLinearLaw)):  # PL: breakpoints and slopes
        return ("pl", tuple(exact(b) for b in lw.breakpoints), tuple(exact(s) for s in lw.slopes))
    raise ParameterError("law", lw, "a CubicLaw, PolynomialLaw, SmoothLaw or piecewise-linear law")


def qc_method(lw) -> str:
    """How fpucore computes this law's QC waves: "closed form" (the cubic, paper §4) or
    "quadrature" (any other law, §3) — for the timing labels."""
    return "closed form" if qc.is_closed_form(lw) else "quadrature"
