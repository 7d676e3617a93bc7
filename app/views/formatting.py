"""Formatting of what the scenes show and write: times, numbers, CSV and JSON files, and the
state's provenance lines (a data file's header, the parameters under every status).

Kept apart from the Scene machinery (:mod:`.scene`): pure functions of values and the state,
used by every scene's render and download code, testable without a page.
"""

from __future__ import annotations

import io
import json

import numpy as np

import fpucore
from fpucore.errors import ParameterError
from fpucore.result import jsonable

from ..compute import Computed
from ..state import ExplorerState


def fmt_time(s: float) -> str:
    return f"{s * 1e3:.1f} ms" if s < 1.0 else f"{s:.2f} s"


def fmt_num(x: float, digits: int = 6) -> str:
    return f"{x:.{digits}g}"


def as_csv(columns: dict[str, np.ndarray], header: str = "") -> io.StringIO:
    """CSV text of equal-length columns (header lines start with '#')."""
    names = list(columns)
    arrays = [np.asarray(columns[n]) for n in names]
    n = max((len(a) for a in arrays), default=0)
    buf = io.StringIO()
    for line in header.splitlines():
        buf.write(f"# {line}\n")
    buf.write(",".join(names) + "\n")
    for i in range(n):
        row = []
        for a in arrays:
            if i < len(a):
                v = a[i]
                row.append(repr(float(v)) if np.isrealobj(v) else str(v))
            else:
                row.append("")
        buf.write(",".join(row) + "\n")
    buf.seek(0)
    return buf


def as_json(obj) -> io.StringIO:
    buf = io.StringIO(json.dumps(jsonable(obj), indent=1))
    buf.seek(0)
    return buf


def law_line(state: ExplorerState) -> str:
    """The law in a data file's header: the cubic's a, b or the expression (exactly as given to
    fpucore.law_from_expression) with its coefficients c_1, c_2, ... (f = Σ c_k w^k)."""
    if not state.expression:
        return f"law: f(w) = a w^3 + b w^2 + w with a={state.a!r}, b={state.b!r}"
    line = f"law: f(w) = {state.expression} (law={state.expression!r}"
    try:
        lw = state.law()
        if hasattr(lw, "coeffs"):
            line += f", coefficients c_1...={lw.coeffs!r}"
        else:  # a smooth law: where its kernel represents f, and how well
            line += f", {lw.representation_error}"
    except ParameterError as exc:
        line += f", invalid: {exc}"
    return line + ")"


def provenance(state: ExplorerState, what: str, **extra) -> str:
    """Header of a data file: what it holds and everything needed to reproduce it."""
    lines = [
        what,
        f"fpu-explorer / fpucore {fpucore.__version__}",
        law_line(state),
        f"mode={state.mode} w_plus={state.w_plus!r} V={state.V!r} N={state.N} tol={state.tol!r}",
    ]
    lines += [f"{k}={v!r}" for k, v in extra.items()]
    return "\n".join(lines)


def state_stamp(state: ExplorerState) -> str:
    """The parameters a render used, exactly as in the URL (shown under every status, so a
    reader — and the browser tests — can tell which state is on screen)."""
    rest = f"w_plus={state.w_plus!r} V={state.V!r} N={state.N} tol={state.tol!r} mode={state.mode}"
    # an expression law replaces a, b (which it does not use); last, as it has spaces
    if state.expression:
        return f"{rest} law={state.expression}"
    return f"a={state.a!r} b={state.b!r} {rest}"


def fmt_timing(label: str, c: Computed | float) -> str:
    """'discrete N=500 1.20 s'; a cached result keeps the cost of its computation:
    'discrete N=500 1.20 s (computed earlier, now from the cache)'."""
    if isinstance(c, Computed):
        return f"{label} {fmt_time(c.elapsed_s)}" + (
            " (computed earlier, now from the cache)" if c.cached else ""
        )
    return f"{label} {fmt_time(float(c))}"
