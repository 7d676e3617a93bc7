"""Memory and time budgets shared by every solver of fpucore.

Memory: a request is estimated from *all* its sizes together, before anything is allocated, and
refused (:class:`~fpucore.errors.ParameterError`, with the estimate and the limit) above the
memory budget.  The budget is, in this order of precedence,

1. the ``budget`` argument of :func:`require_memory` / :func:`memory_budget` (callers expose it,
   e.g. ``simulate.riemann(..., memory_budget="2GiB")``);
2. the environment variable ``FPU_MEMORY_BUDGET``;
3. :data:`DEFAULT_FRACTION` (25 %) of the machine's physical memory (``os.sysconf``; 8 GiB when
   the platform does not say).

A budget is given as a number of bytes (``2e9``), with a unit (``"512MiB"``, ``"2GiB"``,
``"1.5GB"``) or as a share of the machine's memory (``"50%"``).

Time: :func:`work_clock` is the clock of the wave solvers' time budgets (CPU time of the
solving thread: their path does not depend on how busy the machine is); :class:`Deadline` is a
wall-clock budget started when it is made; long loops ask
:meth:`Deadline.expired` between chunks of work and stop cleanly with their partial result
(status ``"stopped"``, stop reason ``"time_budget"``, :meth:`Deadline.message`).

This module imports nothing from fpucore except :mod:`fpucore.errors`.
"""

from __future__ import annotations

import math
import os
import re
import time

from fpucore.errors import ParameterError, require_finite

ENV_VAR = "FPU_MEMORY_BUDGET"
DEFAULT_FRACTION = 0.25
FALLBACK_TOTAL = 8 * 2**30  # bytes, when os.sysconf cannot tell the machine's memory

_UNITS = {
    "": 1,
    "b": 1,
    "kb": 10**3,
    "mb": 10**6,
    "gb": 10**9,
    "tb": 10**12,
    "kib": 2**10,
    "mib": 2**20,
    "gib": 2**30,
    "tib": 2**40,
}
_SIZE = re.compile(r"^\s*([0-9.eE+-]+)\s*([a-zA-Z%]*)\s*$")


def total_memory() -> int:
    """Physical memory of the machine in bytes (``os.sysconf``), or :data:`FALLBACK_TOTAL`."""
    try:
        n = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError, AttributeError):
        return FALLBACK_TOTAL
    return int(n) if n > 0 else FALLBACK_TOTAL


def fmt_bytes(n: float) -> str:
    """``1.5 GiB``-style text for a byte count."""
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{int(n)} B"


def parse_size(text: str | float | int, name: str = "memory_budget") -> int:
    """Bytes from ``2e9``, ``"512MiB"``, ``"2GiB"``, ``"1.5GB"`` or ``"50%"`` (of the machine's
    memory).  ParameterError for anything else, or a size that is not positive."""
    valid = "a positive size: bytes (2e9), with a unit (512MiB, 2GiB, 1.5GB) or a share (50%)"
    if isinstance(text, bool):
        raise ParameterError(name, text, valid)
    if isinstance(text, (int, float)):
        x = require_finite(name, text)
        if x <= 0:
            raise ParameterError(name, x, valid)
        return _whole_bytes(name, text, x, valid)
    m = _SIZE.match(str(text))
    if not m:
        raise ParameterError(name, text, valid)
    try:
        x = float(m.group(1))
    except ValueError:
        raise ParameterError(name, text, valid) from None
    unit = m.group(2).lower()
    if not math.isfinite(x) or x <= 0:
        raise ParameterError(name, text, valid)
    if unit == "%":
        if x > 100:
            raise ParameterError(name, text, "a share in (0%, 100%]")
        return int(total_memory() * x / 100.0)
    if unit not in _UNITS:
        raise ParameterError(name, text, valid)
    return _whole_bytes(name, text, x * _UNITS[unit], valid)


def _whole_bytes(name: str, text, n: float, valid: str) -> int:
    """``int(n)`` for a size in bytes: at least 1 byte (0.5 would become a budget of 0 bytes,
    then blamed on whichever size is checked first) and finite (1e308TiB: OverflowError)."""
    if not math.isfinite(n):
        raise ParameterError(name, text, valid, "the size overflows")
    if n < 1.0:
        raise ParameterError(
            name,
            text,
            valid,
            f"{n:g} bytes: less than one byte (a share is written with %, e.g. 50%)",
        )
    return int(n)


def require_env_budget() -> None:
    """Refuse an invalid ``FPU_MEMORY_BUDGET`` up front (the ``fpu`` commands call it first):
    commands that never estimate memory would otherwise ignore it silently, and the others
    would report it only after their other checks."""
    env = os.environ.get(ENV_VAR)
    if env:  # set and empty counts as unset, as in memory_budget
        parse_size(env, ENV_VAR)


def memory_budget(budget: str | float | int | None = None) -> tuple[int, str]:
    """(limit in bytes, where it comes from) — the argument, else ``FPU_MEMORY_BUDGET``, else
    :data:`DEFAULT_FRACTION` of the machine's memory."""
    if budget is not None:
        return parse_size(budget), "memory_budget argument"
    env = os.environ.get(ENV_VAR)
    if env:
        return parse_size(env, ENV_VAR), f"{ENV_VAR}={env}"
    total = total_memory()
    share = f"{DEFAULT_FRACTION:.0%} of {fmt_bytes(total)} RAM"
    return int(DEFAULT_FRACTION * total), share


def require_memory(
    name: str,
    n_bytes: float,
    detail: str = "",
    value: object = None,
    budget: str | float | int | None = None,
) -> int:
    """Refuse a request estimated at ``n_bytes`` above the memory budget.

    name : the argument the refusal names (the one whose size dominates the estimate);
    value : its value (default: the estimate itself, as text); detail : what the estimate is made
    of (shown in the message).  Returns the limit in bytes when the request fits."""
    limit, source = memory_budget(budget)
    if n_bytes > limit:
        est = fmt_bytes(n_bytes)
        reason = f"the request needs about {est} of memory, above the budget"
        if detail:
            reason += f"; {detail}"
        raise ParameterError(
            name,
            est if value is None else value,
            f"sizes whose memory estimate is <= {fmt_bytes(limit)} ({source}; "
            f"set {ENV_VAR} or the memory_budget argument to change it)",
            reason,
        )
    return limit


def require_time_budget(
    value: float | None, name: str = "time_budget_s", none_ok: bool = True
) -> float | None:
    """``None`` (no limit; refused when not ``none_ok``) or a finite number of seconds in
    (0, 1e9]: the one time-budget rule of every solver."""
    valid = "None (no limit) or seconds in (0, 1e9]" if none_ok else "seconds in (0, 1e9]"
    if value is None and none_ok:
        return None
    if isinstance(value, bool):
        raise ParameterError(name, value, valid)
    try:
        x = require_finite(name, value)
    except ParameterError:  # NaN, inf, a string: the same rule in the refusal
        raise ParameterError(name, value, valid) from None
    if not (0.0 < x <= 1e9):
        raise ParameterError(name, x, valid)
    return x


def work_clock() -> float:
    """Seconds of CPU time of the calling thread: the clock of the discrete-wave solvers' time
    budgets (``time_budget_s`` of ``wave.solve_*``), whose rescues and continuations decide
    their path by the time left.  On the wall clock that path depended on the machine's load:
    at load 20 on 2 cores the paper's flat top (V_SK − 9.5e-12, 15 s of work) took 301 s and
    ran out of its 300 s in the start wave of the plateau route (a different, unconverged
    answer).  The work runs on this thread (one BLAS/Numba thread,
    :mod:`fpucore.parallel.threads`); with more threads the budget counts this thread's share
    only."""
    return time.thread_time()


class Deadline:
    """A wall-clock time budget, started when made.

    ``Deadline(None)`` never expires.  Loops call :meth:`expired` between chunks of work (the
    check costs one ``perf_counter`` call) and, when it is True, return their partial result with
    status ``"stopped"``, stop reason ``"time_budget"`` and :meth:`message` in its message."""

    def __init__(self, budget_s: float | None, name: str = "time_budget_s"):
        self.budget_s = require_time_budget(budget_s, name)
        self.name = name
        self.start = time.perf_counter()

    def elapsed(self) -> float:
        """Seconds since the deadline was made."""
        return time.perf_counter() - self.start

    def remaining(self) -> float:
        """Seconds left (``inf`` without a budget; negative once expired)."""
        return math.inf if self.budget_s is None else self.budget_s - self.elapsed()

    def expired(self) -> bool:
        return self.budget_s is not None and self.elapsed() >= self.budget_s

    def message(self, where: str = "", hint: str = "") -> str:
        """'time budget time_budget_s=60 s reached after 60.2 s <where>; <hint>'."""
        msg = f"time budget {self.name}={self.budget_s:g} s reached after {self.elapsed():.3g} s"
        if where:
            msg += f" {where}"
        if hint:
            msg += f"; {hint}"
        return msg
