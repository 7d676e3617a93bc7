"""Formatting of what the scenes show and write: times, numbers, CSV and JSON files, and the
state's provenance lines (a data file's header, the parameters under every status).

Kept apart from the Scene machinery (:mod:`.scene`): pure functions of values and the state,
used by every scene's render and download code, testable without a page.
"""

from __future__ import annotations

import functools
import io
import json
import math

import numpy as np

import fpucore
from fpucore.errors import ParameterError
from fpucore.result import jsonable

from ..compute import Computed
from ..state import ExplorerState
from .untrusted import md_literal


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


def comparison_parts(comparisons) -> list[str]:
    """Each printed number beside ours ± error, with its verdict mark (Comparison objects or the
    docs JSON's dicts)."""
    parts = []
    for c in comparisons:
        get = c.get if isinstance(c, dict) else functools.partial(getattr, c)
        ours, err = get("ours"), get("error")
        ours_s = "—" if ours is None else fmt_num(ours, 8)
        err_s = "?" if err is None else f"{err:.1g}"
        parts.append(
            f"{'✓' if get('agrees') else '✗'} {md_literal(get('quantity'))}: paper "
            f"{md_literal(get('printed'))}, ours {ours_s} ± {err_s}"
        )
    return parts


def ranges_markdown(st: ExplorerState, s: dict) -> str:
    """The sidebar's ranges of the theory for the state ``st`` and its summary ``s``
    (ExplorerState.summary): where w₊ and V may go, V_SK, the current kind and the state's note."""
    if "alpha" not in s:
        return f"**invalid law:** {md_literal(st.problem() or '')}"
    same = all(  # the superkink range of the cubic is (α, β); a root finder's last ulp
        math.isclose(s[k], s[e], rel_tol=1e-9, abs_tol=1e-12)  # is not another range
        for k, e in (("w_lo", "alpha"), ("w_hi", "beta"))
    )
    if same:
        where = f"w₊ ∈ (α, β) = ({s['alpha']:.5g}, {s['beta']:.5g})"
    else:  # another law: w₋ must stay inside (α, β) too
        where = (
            f"w₊ ∈ ({s['w_lo']:.5g}, {s['w_hi']:.5g}) (where w₋ stays inside (α, β) = "
            f"({s['alpha']:.5g}, {s['beta']:.5g}))"
        )
    if "hard" in s:  # a piecewise-linear law: no wave from its hard regime
        lines = [
            f"{where}, the hard regime **[w₁, w₂] = [{s['hard'][0]:.6g}, "
            f"{s['hard'][1]:.6g}]** excluded"
        ]
    else:
        lines = [f"{where}, **w\\* = {s['w_star']:.6g}** excluded"]
    if "V_SK" in s:
        lines.append(
            "solitary-wave velocities (tensile or compressive): "
            f"(c₊, V_SK) = ({s['c_plus']:.6g}, {s['V_SK']:.6g}) and "
            f"(V_SK, c₋) = ({s['V_SK']:.6g}, {s['c_minus']:.6g})"
        )
        lines.append(f"**V_SK = {s['V_SK']:.10g}** (superkink)")
        if "V_lo" in s:  # (not for a piecewise-linear law: fpucore refuses them for now)
            lines.append(f"superkink V bounds ({s['V_lo']:.6g}, {s['V_hi']:.6g})")
    kind = st.kind()
    lines.append(f"current: **{kind}**" if kind != "invalid" else f"⚠ {md_literal(st.problem())}")
    if st.note:
        lines.append(f"_{md_literal(st.note)}_")
    return "\n\n".join(lines)
