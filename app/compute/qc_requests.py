"""The quasicontinuum (QC) requests: cheap closed forms or quadratures (§3–4), computed in the
server process and cached exactly (:class:`~app.compute.request_base.LocalRequest`, run by
:func:`app.compute.run` like every request).

    QCWaveRequest(mode, w_plus, V=None)       the QC superkink (from w₊) or solitary wave
    QCFamilyRequest(w_plus, n)                the QC solitary family of w₊ (amplitude, E_ren)
    ExistenceRequest(n)                       the existence diagram (w₊, c₊, V_SK, c₋)
    PhasePlaneRequest(w_plus, V, n_grid)      the phase plane of the traveling-wave ODE
    PhaseOrbitRequest(w_plus, V, w0, wp0, window)   the orbit through a point (w0, w0′)

Each one's :class:`~app.compute.request_base.Call` is the fpucore function with its arguments:
the job, the cache key and the "Copy as Python" line, as for the heavy requests.
"""

from __future__ import annotations

from dataclasses import dataclass

from fpucore import qc, wave
from fpucore.errors import ParameterError, require_finite, require_int
from fpucore.qc import diagram, phase

from .request_base import Call, LocalRequest

__all__ = [
    "QCWaveRequest",
    "QCFamilyRequest",
    "ExistenceRequest",
    "PhasePlaneRequest",
    "PhaseOrbitRequest",
]

MODES = ("solitary", "superkink")
#: grid sizes of the QC curves: at least a segment, at most what a plot could show
GRID = (2, 100_000)


@dataclass(frozen=True)
class QCWaveRequest(LocalRequest):
    """The QC superkink of w₊'s branch (mode "superkink": V follows from w₊; the field V is
    not used and set to None) or the QC solitary wave (w₊, V) (mode "solitary")."""

    mode: str
    w_plus: float
    V: float | None = None

    def __post_init__(self):
        if self.mode not in MODES:
            raise ParameterError("mode", self.mode, " | ".join(map(repr, MODES)))
        self._set("w_plus", require_finite("w_plus", self.w_plus))
        superkink = self.mode == "superkink"  # a held superkink has no V (None)
        self._set("V", None if superkink else require_finite("V", self.V))

    def call(self) -> Call:
        """fpucore.qc.superkink_from_w_plus or fpucore.qc.solitary."""
        if self.mode == "superkink":
            return Call("qc", qc.superkink_from_w_plus, (self.w_plus,))
        return Call("qc", qc.solitary, (self.w_plus, self.V))

    def job_key(self, lw) -> tuple:
        """The call's own inputs: superkinks at one w₊ share one entry whatever V says."""
        return ("qc", self.call().key())

    def spec(self, lw) -> wave.Spec:
        """fpucore.wave's description (Spec, with its law) of the wave the request defines."""
        if self.mode == "superkink":  # w₊ fixes V and the branch
            sk = qc.superkink_from_w_plus(lw, self.w_plus)
            return wave.spec_of(lw, "superkink", sk.branch, sk.V)
        return wave.spec_of(lw, "solitary", self.w_plus, self.V)

    def n_needed(self, lw, tol: float) -> int:
        """The chain size fpucore would choose itself for the discrete wave (``N=None``: tails
        resolved to 0.1·tol·scale, eq. fixedBCs), at least the smallest N it accepts (tails cut
        at 1e-6 of the amplitude).  Closed-form QC tails only: cheap, not cached."""
        spec = self.spec(lw)
        return int(max(spec.auto_N(tol), spec.smallest_N()))


@dataclass(frozen=True)
class QCFamilyRequest(LocalRequest):
    """fpucore.qc.diagram.solitary_family: amplitude (eq. SWQC_amp) and E_ren (eq. Eren_QC) of
    the QC solitary waves along both velocity intervals of w₊, n points each."""

    w_plus: float
    n: int = 160

    def __post_init__(self):
        self._set("w_plus", require_finite("w_plus", self.w_plus))
        self._set("n", require_int("n", self.n, *GRID))

    def call(self) -> Call:
        return Call("diagram", diagram.solitary_family, (self.w_plus,), (("n", self.n),))


@dataclass(frozen=True)
class ExistenceRequest(LocalRequest):
    """fpucore.qc.diagram.existence_diagram: arrays w_plus, c_plus, V_SK, c_minus (n points)."""

    n: int = 400

    def __post_init__(self):
        self._set("n", require_int("n", self.n, *GRID))

    def call(self) -> Call:
        return Call("diagram", diagram.existence_diagram, (), (("n", self.n),))


@dataclass(frozen=True)
class PhasePlaneRequest(LocalRequest):
    """fpucore.qc.phase.phase_plane of the wave (w₊, V) on an n_grid × n_grid grid."""

    w_plus: float
    V: float
    n_grid: int = 241

    def __post_init__(self):
        self._set("w_plus", require_finite("w_plus", self.w_plus))
        self._set("V", require_finite("V", self.V))
        self._set("n_grid", require_int("n_grid", self.n_grid, *GRID))

    def call(self) -> Call:
        kw = (("n_grid", self.n_grid),)
        return Call("phase", phase.phase_plane, (self.w_plus, self.V), kw)


@dataclass(frozen=True)
class PhaseOrbitRequest(LocalRequest):
    """fpucore.qc.phase.orbit_through: the orbit of the wave (w₊, V) through the point
    (w0, w0′), drawn over the strain window (lo, hi)."""

    w_plus: float
    V: float
    w0: float
    wp0: float
    window: tuple

    def __post_init__(self):
        for name in ("w_plus", "V", "w0", "wp0"):
            self._set(name, require_finite(name, getattr(self, name)))
        try:
            lo, hi = self.window
        except (TypeError, ValueError):
            raise ParameterError("window", self.window, "a pair (lo, hi) of strains") from None
        self._set("window", (require_finite("window", lo), require_finite("window", hi)))

    def call(self) -> Call:
        args = (self.w_plus, self.V, self.w0, self.wp0, self.window)
        return Call("phase", phase.orbit_through, args)
