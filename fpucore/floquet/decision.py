"""The one stability decision of a Floquet spectrum and every text about it (paper §6).

:func:`decide` turns the finite-size window's points (:mod:`fpucore.floquet.finite_size`:
which rings, and how their excesses are classified) into one :class:`Decision` record; the
headline, the sentence, the CLI lines, the JSON, the sweep rows and the explorer's status are all
generated from that record.

Words: every sentence prints the points it rests on and says only what they show — "decays"
with the measured fall from the largest excess to the one at N, an envelope exponent only with
an error bar smaller than itself (a two-point envelope has none), "not determined" with how far
the excess falls and why that is no decay, and what would decide it.
benchmarks/verdict_audit.py re-derives each claim from the printed numbers (tests:
tests/floquet/test_verdict_audit.py).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from fpucore.floquet.finite_size import (
    CONVERGED_SPREAD,
    DECAY_P,
    N_MIN,
    classify,
    min_window_N,
)


def _pct(x: float) -> str:
    """A percentage for a sentence: whole numbers from 10 %, two digits below."""
    x = 100.0 * x
    return f"{x:.0f} %" if abs(x) >= 10 else f"{x:.2g} %"


def _pct_apart(x: float, y: float) -> tuple[str, str]:
    """Two percentages compared in one sentence, with the digits that tell them apart ("29.0 %"
    against "29.3 %", not "29 %" against "29 %"; at most 3 decimals)."""
    for d in range(4):
        a, b = f"{100.0 * x:.{d}f} %", f"{100.0 * y:.{d}f} %"
        if a != b:
            break
    return a, b


def _cut(text: str, n: int = 160) -> str:
    """A quoted reason within n characters (the sentence must fit the atlas's verdict field)."""
    return text if len(text) <= n else text[: n - 3] + "..."


@dataclasses.dataclass(frozen=True)
class Decision:
    """The one stability decision of a spectrum; every text about it (headline, sentence, CLI,
    JSON, sweep rows, the explorer's status) is generated from this record.

    classification : one of CLASSES; reason : the test that decided it (see :func:`classify`;
    also "missing_rings": present and converged on the rings computed, but a ring of the window
    could not be computed, so "unstable" is not claimed).
    N : requested chain length; excess ± error : max|μ| − 1 there; growth_rate : V ln max|μ|.
    points_N / points_excess / points_error : the window's evidence, N ascending (only N when
    the test was not run); p ± p_error : upper-envelope exponent (NaN when not fitted; p_error
    NaN for a two-point envelope); envelope_N : the envelope's rings; peak_N : the ring with the
    largest excess; drop = 1 − excess/largest, drop_needed : the drop a decay must show;
    spread : (max e − min e)/e(N) over the window; absent_N : lengths with the excess within its
    error bar; missing_N : rings of the window that could not be computed; not_run : why the
    test was not (fully) run ("" if it was); next_step : what would decide an "undetermined"
    one ("" otherwise).
    """

    classification: str
    reason: str
    N: int
    excess: float
    error: float
    growth_rate: float
    points_N: tuple
    points_excess: tuple
    points_error: tuple
    p: float = math.nan
    p_error: float = math.nan
    spread: float = math.nan
    absent_N: tuple = ()
    dip_N: tuple = ()
    not_run: str = ""
    next_step: str = ""
    envelope_N: tuple = ()
    peak_N: int = 0
    drop: float = 0.0
    drop_needed: float = math.nan
    missing_N: tuple = ()

    @property
    def headline(self) -> str:
        """The classification in a few words (the explorer's bold headline)."""
        return {
            "stable": "stable",
            "finite_size": "finite-size artefact ("
            + ("decays as N grows)" if self.reason == "decays" else "comes and goes with N)"),
            "unstable": "unstable (the excess persists as N grows)",
            "undetermined": f"not determined at N = {self.N}",
        }[self.classification]

    def _pts(self) -> str:
        return ", ".join(
            f"{n}: {x:.2e}" for n, x in zip(self.points_N, self.points_excess, strict=True)
        )

    def fit_words(self, pm: str = "+/-") -> str:
        """The envelope exponent "p = 0.99 +/- 0.0031", only when it has an error bar smaller
        than its value ("" otherwise: a two-point envelope has none, and a fit whose error
        exceeds it says nothing)."""
        if math.isfinite(self.p) and math.isfinite(self.p_error) and self.p_error < abs(self.p):
            return f"p = {self.p:.2f} {pm} {self.p_error:.2g}"
        return ""

    def _fall(self) -> str:
        """The measured fall of the excess: from its largest value to the value at N."""
        k = list(self.points_N).index(self.peak_N) if self.peak_N in self.points_N else 0
        return (
            f"from {self.points_excess[k]:.2e} at N = {self.peak_N} to {self.excess:.2e} at "
            f"N = {self.N}, {_pct(self.drop)} lower"
        )

    def _why_not_decays(self) -> str:
        """Why an excess that is not converged is not called a decaying resonance either."""
        if self.peak_N == self.N:
            return "nor decays (it is largest on the longest ring)"
        if not self.drop >= self.drop_needed:
            got, needed = _pct_apart(self.drop, self.drop_needed)
            return (
                f"nor decays like a resonance of the ring (it falls {got} from its largest "
                f"value at N = {self.peak_N}, short of the {needed} required)"
            )
        fall = f"it falls {_pct(self.drop)} from its largest value at N = {self.peak_N}"
        fit = self.fit_words()
        env0 = self.envelope_N[0] if self.envelope_N else self.N
        if env0 > math.sqrt(self.points_N[0] * self.N):
            if env0 == self.peak_N:  # every shorter ring has a smaller excess
                return (
                    f"nor decays like a resonance of the ring (its largest value is at "
                    f"N = {env0}, late in the window, and it falls {_pct(self.drop)} only "
                    "after it: no trend over the window)"
                )
            return (
                f"nor decays like a resonance of the ring ({fall}, but only after "
                f"N = {env0}: the fall spans only the last rings of the window)"
            )
        return (
            f"nor decays like a resonance of the ring ({fall}, but its upper envelope "
            + (f"falls as N^-p with {fit} < {DECAY_P}" if fit else "has no steady slope")
            + ")"
        )

    @property
    def evidence(self) -> str:
        """The sentence without its first words where they repeat the headline's ("not
        determined at N = 64: " after the headline "not determined at N = 64"): what a text
        that shows the headline first appends to it."""
        head, sep, rest = self.sentence.partition(": ")
        return rest if sep and self.headline.startswith(head) else self.sentence

    @property
    def sentence(self) -> str:
        """The decision and its evidence in one sentence (FloquetResult.verdict)."""
        ex, n = self.excess, self.N
        out = f"{ex:.2e} at N = {n}"
        if self.classification == "stable":
            return (
                f"stable: every multiplier lies on the unit circle within the error bar "
                f"(max|mu|-1 = {ex:.1e} <= {self.error:.1e})"
            )
        if self.reason == "absent":
            gone = ", ".join(str(k) for k in self.absent_N)
            return (
                f"finite-size artefact: multipliers leave the unit circle by {out}, but lie "
                f"on it within the error bar at N = {gone} (max|mu|-1 at N = {self._pts()}) "
                "- a resonance of the finite ring that comes and goes with N; a mode of the "
                "wave would be present on every ring of the window"
            )
        if self.reason == "dips":
            low = min(self.points_excess)
            at = ", ".join(str(k) for k in self.dip_N)
            return (
                f"finite-size artefact: multipliers leave the unit circle by {out}, but the "
                f"excess falls to less than half its neighbours at N = {at} (max|mu|-1 at "
                f"N = {self._pts()}) - a resonance of the finite ring that comes and goes "
                "with N; the largest |mu| of a mode of the wave would not dip, so any "
                f"instability of the wave itself is below {low:.2e}"
            )
        if self.reason == "decays":
            fit = self.fit_words()
            return (
                f"finite-size artefact: multipliers leave the unit circle by {out}, and the "
                f"excess decays as the ring grows ({self._fall()}"
                + (f"; upper envelope ~ N^-p, {fit}" if fit else "")
                + f"; max|mu|-1 at N = {self._pts()}) - the ~1/N splitting of colliding "
                "phonon multipliers of the finite ring, not an instability of the wave"
            )
        if self.classification == "unstable":
            return (
                f"unstable: multipliers leave the unit circle by {out} (growth rate "
                f"{self.growth_rate:.3g} per unit time) and the excess stays within "
                f"{_pct(self.spread)} on every ring from N = {self.points_N[0]} to "
                f"{n} (max|mu|-1 at N = {self._pts()})"
            )
        if self.reason == "unresolved":
            return (
                f"not determined at N = {n}: multipliers leave the unit circle by {out} on "
                f"every ring of the window (max|mu|-1 at N = {self._pts()}), but the excess "
                f"has neither converged (it changes by {_pct(self.spread)} across the "
                f"window; a mode of the wave by at most {_pct(CONVERGED_SPREAD)}) "
                f"{self._why_not_decays()}; {self.next_step}"
            )
        if self.reason == "missing_rings":
            gone = ", ".join(str(k) for k in self.missing_N)
            return (
                f"not determined at N = {n}: multipliers leave the unit circle by {out} and "
                f"the excess stays within {_pct(self.spread)} on the rings computed "
                f"(max|mu|-1 at N = {self._pts()}), but the ring(s) N = {gone} of the "
                f"window could not be computed ({_cut(self.not_run)}); {self.next_step}"
            )
        if len(self.points_N) > 1:  # the test ran on too few rings: say which, and why
            return (
                f"not determined at N = {n}: multipliers leave the unit circle by {out}, but "
                f"the finite-size test has only {len(self.points_N)} chain lengths "
                f"(max|mu|-1 at N = {self._pts()}; {_cut(self.not_run)}), too few to "
                f"decide; {self.next_step}"
            )
        return (
            f"not determined at N = {n}: multipliers leave the unit circle by {out}, and the "
            f"finite-size test was not run ({_cut(self.not_run)}); {self.next_step}"
        )

    def as_dict(self) -> dict:
        """JSON-ready: every field, the headline and the sentence."""
        d = dataclasses.asdict(self)
        d.update(
            headline=self.headline,
            sentence=self.sentence,
            points_N=[int(x) for x in self.points_N],
            points_excess=[float(x) for x in self.points_excess],
            points_error=[float(x) for x in self.points_error],
            absent_N=[int(x) for x in self.absent_N],
            dip_N=[int(x) for x in self.dip_N],
            envelope_N=[int(x) for x in self.envelope_N],
            missing_N=[int(x) for x in self.missing_N],
        )
        return {
            k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in d.items()
        }


def decide(
    N: np.ndarray,
    e: np.ndarray,
    err: np.ndarray,
    growth_rate: float,
    not_run: str = "",
    n_min: int = N_MIN,
    missing_N=(),
) -> tuple[Decision, dict]:
    """The decision record from the window's points (requested N last after sorting) and the
    raw fit dict of :func:`classify`.  not_run : why the window is incomplete ("" when every
    length was computed; "finite_size=False" when the test was switched off); n_min : the
    shortest ring the base state can be rebuilt on (for the advice "compute at N ≥ …");
    missing_N : rings of the window that could not be computed (an excess that persists on the
    others is then "undetermined", not "unstable": the evidence is incomplete)."""
    fit = classify(N, e, err)
    cls, why = fit["classification"], fit["reason"]
    if cls == "unstable" and len(missing_N):
        cls, why = "undetermined", "missing_rings"
    n = int(N[-1])
    step = ""
    if cls == "undetermined":
        if not_run == "finite_size=False":
            step = "run the finite-size test (finite_size=True) to decide"
        elif why == "few_lengths" and n < min_window_N(n_min):
            step = (
                f"compute at N >= {min_window_N(n_min)} (the test needs rings in [N/2, N] "
                f"of at least {max(n_min, N_MIN)} sites)"
            )
        else:
            step = (
                f"compute at N >= {2 * n} (a ring resonance's envelope halves when N "
                "doubles, an instability's growth stays)"
            )
    if why == "few_lengths" and not not_run:
        not_run = f"only {len(N)} chain lengths"
    d = Decision(
        classification=cls,
        reason=why,
        N=n,
        excess=float(e[-1]),
        error=float(err[-1]),
        growth_rate=float(growth_rate),
        points_N=tuple(int(x) for x in N),
        points_excess=tuple(float(x) for x in e),
        points_error=tuple(float(x) for x in err),
        p=fit["p"],
        p_error=fit["p_error"],
        spread=fit["spread"],
        absent_N=tuple(fit["absent_N"]),
        dip_N=tuple(fit["dip_N"]),
        not_run=not_run if cls == "undetermined" else "",
        next_step=step,
        envelope_N=tuple(int(x) for x in fit["envelope_N"]),
        peak_N=int(fit["peak_N"]),
        drop=float(fit["drop"]),
        drop_needed=float(fit["drop_needed"]),
        missing_N=tuple(int(x) for x in missing_N),
    )
    return d, fit
