"""Compute many figures (cached, in the process pool, under a time budget) and write the
comparison table (Markdown).  The HTML report itself is drawn by :mod:`fpucore.paper.plot`.

Cache: one pickle per (label, reduced) in ``$FPU_CACHE_DIR/paper`` (default ``./.fpu_cache/paper``,
as the Floquet sweeps' store), keyed by a hash of fpucore's source so that any code change
recomputes.  A re-run reuses every figure computed before.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from fpucore.errors import ParameterError
from fpucore.paper import registry, registry_trilinear
from fpucore.paper.figure import FigureResult
from fpucore.parallel import Executor

# the figure families: the paper's figures, and the trilinear family's (a second registry)
FAMILIES = {"paper": registry, "trilinear": registry_trilinear}

PKG = Path(__file__).resolve().parents[1]


def cache_dir() -> Path:
    """$FPU_CACHE_DIR/paper, or ./.fpu_cache/paper."""
    root = os.environ.get("FPU_CACHE_DIR") or os.path.join(os.getcwd(), ".fpu_cache")
    return Path(root) / "paper"


def code_version() -> str:
    """sha256 (16 hex digits) of every fpucore source file: a cached figure is reused only with
    exactly the code that computed it."""
    h = hashlib.sha256()
    for p in sorted(PKG.rglob("*.py")):
        h.update(p.relative_to(PKG).as_posix().encode())
        h.update(p.read_bytes())
    return h.hexdigest()[:16]


def cache_path(label: str, reduced: bool, version: str) -> Path:
    return cache_dir() / f"{label}{'-reduced' if reduced else ''}-{version}.pickle"


def load_cached(label: str, reduced: bool, version: str) -> FigureResult | None:
    p = cache_path(label, reduced, version)
    try:
        with p.open("rb") as fh:
            r = pickle.load(fh)
    except (OSError, pickle.UnpicklingError, EOFError, AttributeError):
        return None
    return r if isinstance(r, FigureResult) and r.label == label else None


def store(r: FigureResult, version: str) -> None:
    p = cache_path(r.label, r.reduced, version)
    p.parent.mkdir(parents=True, exist_ok=True)
    tmp = p.with_suffix(".tmp")
    with tmp.open("wb") as fh:
        pickle.dump(r, fh)
    tmp.replace(p)  # atomic: a concurrent reader never sees half a file


def family(name: str):
    """The registry module of a figure family ("paper" or "trilinear"): its FIGURES, LABELS and
    figure(label); a ParameterError naming the families otherwise."""
    if not isinstance(name, str) or name not in FAMILIES:
        raise ParameterError("family", name, "one of " + ", ".join(FAMILIES))
    return FAMILIES[name]


def entry(label: str):
    """The registry entry of ``label`` in whichever family holds it (labels are unique across
    families: the trilinear ones start with ``tri_``)."""
    for reg in FAMILIES.values():
        if label in reg.FIGURES:
            return reg.FIGURES[label]
    return registry.figure(label)  # the paper's error, naming its labels


def compute_job(item: tuple) -> FigureResult:
    """One figure (module-level: picklable for the pool): (label, reduced[, family])."""
    label, reduced, fam = (*item, "paper")[:3]
    return family(fam).FIGURES[label].compute(reduced)


def compute_many(
    labels: Sequence[str] | None = None,
    reduced: bool = False,
    use_cache: bool = True,
    workers: int | None = None,
    time_budget_s: float = 3600.0,
    progress: Callable[[int, int, str], None] | None = None,
    family_name: str = "paper",
) -> tuple[list[FigureResult], list[str], float]:
    """Figures ``labels`` (default all 17) in paper order: (results, labels not computed within
    ``time_budget_s`` or failed — with why, wall time s).  Cached figures are read, the others
    computed in a process pool of ``workers`` (default all cores; 1: in this process), the most
    expensive first.  The budget is checked between figures (a running one is not interrupted).
    ``family_name``: "paper" (default) or "trilinear" (fpucore.paper.registry_trilinear).
    """
    reg = family(family_name)
    FIGURES = reg.FIGURES
    labels = list(reg.LABELS if labels is None else labels)
    for lab in labels:
        reg.figure(lab)
    if not (isinstance(time_budget_s, (int, float)) and time_budget_s > 0):
        raise ParameterError("time_budget_s", time_budget_s, "> 0 seconds")
    t0 = time.perf_counter()
    version = code_version()
    done: dict[str, FigureResult] = {}
    if use_cache:
        for lab in labels:
            r = load_cached(lab, reduced, version)
            if r is not None:
                done[lab] = r
    todo = sorted((lab for lab in labels if lab not in done), key=lambda s: -FIGURES[s].cost)
    missing: list[str] = []
    total, count = len(labels), len(done)
    if progress:
        progress(count, total, "cache")

    def take(lab: str, val) -> bool:
        """Record one figure; False once the budget is spent."""
        nonlocal count
        if isinstance(val, BaseException):
            missing.append(f"{lab}: {type(val).__name__}: {val}")
        else:
            done[lab] = val
            if use_cache:
                store(val, version)
        count += 1
        if progress:
            progress(count, total, lab)
        return time.perf_counter() - t0 <= time_budget_s

    items = [(lab, reduced, family_name) for lab in todo]
    if todo and workers == 1:  # this process, one figure after the other
        for item in items:
            try:
                val: FigureResult | Exception = compute_job(item)
            except Exception as exc:  # noqa: BLE001  (reported in `missing`, the others go on)
                val = exc
            if not take(item[0], val):
                break
    elif todo:
        ex = Executor(backend="process", workers=workers, caller_runs=True)
        try:
            for i, val in ex.map(compute_job, items):
                if not take(todo[i], val):
                    break
        finally:
            ex.shutdown()
    if todo:
        missing += [
            f"{lab}: not computed within the time budget ({time_budget_s:g} s)"
            for lab in todo
            if lab not in done and not any(m.startswith(lab + ":") for m in missing)
        ]
    results = [done[lab] for lab in labels if lab in done]
    return results, missing, time.perf_counter() - t0


def _md(x: str) -> str:
    return str(x).replace("|", "\\|")


def markdown_table(results: Sequence[FigureResult], missing: Sequence[str] = ()) -> str:
    """The comparison table, paper vs fpu-explorer, one row per printed number."""
    lines = [
        "| Fig. | quantity | paper | fpu-explorer | error bar | verdict | why | time (s) |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        fig = entry(r.label)
        for c in r.comparisons:
            verdict = "agrees" if c.agrees else "**disagrees**"
            lines.append(
                f"| {fig.number} `{r.label}` | {_md(c.quantity)} | {_md(c.printed)} | "
                f"{c.ours:.10g} | {c.error:.2g} | {verdict} | {_md(c.why)} | {c.elapsed_s:.2f} |"
            )
    n = sum(len(r.comparisons) for r in results)
    ok = sum(r.n_agree for r in results)
    lines.append("")
    lines.append(f"{ok} of {n} printed numbers agree; figures computed: {len(results)}.")
    for m in missing:
        lines.append(f"- not computed: {m}")
    notes = [f"- `{r.label}`: {r.notes}" for r in results if r.notes]
    if notes:
        lines += ["", "Notes:", *notes]
    return "\n".join(lines) + "\n"
