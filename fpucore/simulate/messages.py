"""Status messages of the chain simulations: what happened, in words, and what to change — one
function per stop reason (:data:`MESSAGES`)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from fpucore.budget import Deadline
from fpucore.simulate.config import RunConfig


@dataclass(frozen=True)
class Outcome:
    """What the status message needs to know about a finished (or stopped) run."""

    status: str
    t: float
    n_steps: int
    n_rejected: int
    bad_value: float
    bad_site: int
    strain_range: tuple[float, float]
    convex: tuple[float, float]
    guard_interval: tuple[float, float]
    restoring: tuple[float, float]
    note: str = ""  # the smooth law's represented interval, when it bounds the run


def _msg_ok(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    msg = f"reached t = {o.t:.6g} in {o.n_steps} steps ({o.n_rejected} rejected)"
    (a, b), (w_min, w_max), (lo, hi) = o.convex, o.strain_range, o.guard_interval
    if w_min <= a or w_max >= b:
        msg += (
            f"; strains went outside the convex interval ({a:.6g}, {b:.6g}): "
            f"range [{w_min:.6g}, {w_max:.6g}] (guard 'bounded' allows ({lo:.6g}, {hi:.6g}))"
        )
    return msg


def _msg_left(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    lo, hi = o.guard_interval
    head = f"stopped at t = {o.t:.6g}: strain w_{o.bad_site + 1} = {o.bad_value:.6g} left the "
    if cfg.guard == "convex":
        r0, r1 = o.restoring
        return head + (
            f"convex interval (alpha, beta) = ({lo:.6g}, {hi:.6g}) (guard='convex'). "
            f"Beyond it f' < 0, and beyond the zeros of f ({r0:.6g}, {r1:.6g}) "
            "the cubic potential is unbounded. Suggestion: guard='bounded' to continue "
            "through transient excursions (stops only outside the zeros of f); for a "
            "Riemann run use boundary='fixed_particles' or 'fixed_strain'"
        )
    if o.note:
        return head + (
            f"represented interval of the smooth law ({lo:.6g}, {hi:.6g}) (guard='bounded' is "
            "bounded by it: beyond it the law's kernels are not defined). Suggestion: smaller "
            "data, boundary='fixed_particles' or 'fixed_strain', or a longer chain"
        )
    return head + (
        f"interval between the zeros of f ({lo:.6g}, {hi:.6g}); beyond it the "
        "cubic potential has no restoring force and the strain runs away. Suggestion: "
        "smaller data, boundary='fixed_particles' or 'fixed_strain', or a longer chain"
    )


def _msg_budget(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    return (
        f"step budget max_steps={cfg.max_steps} exhausted at t = {o.t:.6g}; suggestion: loosen "
        "rtol or raise max_steps"
    )


def _msg_time(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    est = f"~{cfg.work['seconds']:.3g} s"
    if cfg.pwl:  # each located breakpoint crossing ends a step: not in the estimate
        est = f"{est} before the steps its breakpoint crossings add"
    return deadline.message(
        f"at t = {o.t:.6g} of t_end = {cfg.t_end:.6g} ({o.n_steps} steps; the whole run was "
        f"estimated at {est}); the result holds the times reached",
        "raise time_budget_s (CLI: --time-budget), or shorten t_end / L",
    )


def _msg_failed(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    msg = f"integration failed ({o.status}) at t = {o.t:.6g}; suggestion: loosen rtol / reduce dt"
    iv = o.note and o.guard_interval
    return msg + (f"; a strain may have left the represented interval {iv}" if iv else "")


MESSAGES: dict[str, Callable[[Outcome, RunConfig, Deadline], str]] = {
    "ok": _msg_ok,
    "left_convex": _msg_left,
    "budget": _msg_budget,
    "time_budget": _msg_time,
}


def status_message(o: Outcome, cfg: RunConfig, deadline: Deadline) -> str:
    """The message of a run by its stop reason (what happened, and what to change)."""
    return MESSAGES.get(o.status, _msg_failed)(o, cfg, deadline)
