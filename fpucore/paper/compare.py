"""One printed number of the paper against ours: :class:`Comparison`.

The verdict rule (no tolerance chosen per case): a printed *value* agrees when
``|ours − paper| ≤ our error bar + the paper's printed rounding`` (half a unit of its last printed
digit; 0 for an exact closed form such as 2√65/3).  A printed *bound* ("< 1.005", "≤ 1 + 1e-8")
holds when ours plus its error bar is on the stated side.  Anything else is a disagreement, and
``why`` says by how much.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from fpucore.errors import ParameterError
from fpucore.result import Result

KINDS = ("value", "upper_bound", "lower_bound")


def printed_rounding(printed: str) -> float:
    """Half a unit of the last digit of a decimal as printed ("−5.7209" → 5e-5, "1e-8" → 0.5e-8)."""
    s = printed.strip().lstrip("+-−±")
    mant, _, exp = s.lower().partition("e")
    decimals = len(mant.partition(".")[2])
    return 0.5 * 10.0 ** (-decimals + (int(exp) if exp else 0))


@dataclass(frozen=True)
class Comparison(Result):
    """A number the paper prints beside ours.

    quantity : what is compared, in words (with the paper's symbol).
    printed : the paper's text ("2√65/3", "−5.7209", "< 1.005").
    paper : its value as a float.
    ours : our value; ``error`` its error bar (absolute, same units).
    rounding : the paper's printed rounding (0 for exact closed forms).
    kind : "value", "upper_bound" (ours must be < paper) or "lower_bound" (ours > paper).
    source : the fpucore call that produced ``ours``.
    agrees : the verdict; ``why`` explains it with the numbers.
    elapsed_s : time of the computation behind ``ours`` (s).
    """

    figure: str
    quantity: str
    printed: str
    paper: float
    ours: float
    error: float
    rounding: float
    kind: str
    source: str
    agrees: bool
    why: str
    elapsed_s: float

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = ("error",)
    DERIVED: ClassVar[tuple[str, ...]] = ("status", "verdict")

    @property
    def converged(self) -> bool:
        return math.isfinite(self.ours) and math.isfinite(self.error)

    @property
    def status(self) -> str:
        return "ok" if self.converged else "not_converged"

    @property
    def message(self) -> str:
        return self.why

    @property
    def verdict(self) -> str:
        return "agrees" if self.agrees else "disagrees"


def compare(
    figure: str,
    quantity: str,
    printed: str,
    paper: float,
    ours: float,
    error: float,
    *,
    source: str,
    elapsed_s: float,
    kind: str = "value",
    rounding: float | None = None,
) -> Comparison:
    """Build a :class:`Comparison` and its verdict (rule in the module docstring).

    ``rounding`` defaults to :func:`printed_rounding` of ``printed`` for a value and 0 for a bound
    or a closed form (pass 0 explicitly for exact printed expressions like "2√65/3").
    """
    if kind not in KINDS:
        raise ParameterError("kind", kind, f"one of {KINDS}")
    ours, error, paper = float(ours), abs(float(error)), float(paper)
    if rounding is None:
        rounding = printed_rounding(printed) if kind == "value" else 0.0
    if not (math.isfinite(ours) and math.isfinite(error)):
        agrees, why = False, f"no finite value computed (ours = {ours}, error = {error})"
    elif kind == "value":
        diff = abs(ours - paper)
        allowed = error + rounding
        agrees = diff <= allowed
        why = (
            f"|ours − paper| = {diff:.3g} {'≤' if agrees else '>'} error {error:.2g}"
            f" + printed rounding {rounding:.2g}"
        )
    elif kind == "upper_bound":
        agrees = ours + error < paper
        why = f"ours + error = {ours + error:.10g} {'<' if agrees else '≥'} {paper:.10g}"
    else:
        agrees = ours - error > paper
        why = f"ours − error = {ours - error:.10g} {'>' if agrees else '≤'} {paper:.10g}"
    return Comparison(
        figure=figure,
        quantity=quantity,
        printed=printed,
        paper=paper,
        ours=ours,
        error=error,
        rounding=float(rounding),
        kind=kind,
        source=source,
        agrees=bool(agrees),
        why=why,
        elapsed_s=float(elapsed_s),
    )
