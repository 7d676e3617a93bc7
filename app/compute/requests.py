"""The typed parameters of the heavy jobs and the fpucore calls they stand for.

A request is a frozen dataclass, checked when it is made (types, finite numbers, choices: a bad
value is a ParameterError naming it; ranges that depend on the law or on other arguments are
fpucore's, checked where the call runs) and hashable; :meth:`key` is its exact cache key (the
``repr`` of every float, :func:`~app.compute.cache.exact`).  Its :class:`Call` is the fpucore
function itself with its arguments: the job runs it, the cache key and "copy as Python" are
made from it, so the three never differ.

Each request is also the job itself: :meth:`Request.job` is what a worker process runs
(``job(law, progress=None)``, a bound method of a picklable frozen dataclass) and
:meth:`Request.job_key` the exact key of its result under a law; the one road from a scene to
a worker is :func:`app.compute.run` (``run(law, request)``), cached on that key.

    WaveRequest(mode, w_plus, V, N, tol)               a discrete traveling wave
    FamilyRequest(w_plus, V_values, N, tol)            discrete solitary waves at those V
    SweepRequest(kind, w_plus, V_values, N, branch)    max |μ| against V along a family
    RiemannRequest / GaussianRequest / SeededRequest   a direct simulation (SimulationRequest)
    AtlasRequest(w_lo, w_hi, n_w, n_V, N)              a small solitary atlas with Floquet

A new heavy computation is a new request here (its fields, ``call``, and ``job`` when the
worker does more than the call), not a new function of app.compute.
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import ClassVar

from fpucore import atlas, qc, wave
from fpucore import simulate as sim
from fpucore.errors import ParameterError, require_finite, require_int, require_tol
from fpucore.parallel import Executor
from fpucore.simulate.config import GUARDS, MAX_L, require_positive
from fpucore.wave.tails import N_MAX, N_MIN

from .request_base import Call, Request, fraction

#: the request classes (app.compute re-exports them: a new request needs no line there); the
#: Call and the atlas limits stay here (``compute.requests.SMALL_ATLAS_N``)
__all__ = [
    "WaveRequest",
    "FamilyRequest",
    "SweepRequest",
    "SimulationRequest",
    "RiemannRequest",
    "GaussianRequest",
    "SeededRequest",
    "AtlasRequest",
]

MODES = ("solitary", "superkink")


@dataclass(frozen=True)
class WaveRequest(Request):
    """A discrete traveling wave: the superkink of w₊'s branch (V follows from w₊) or the
    solitary wave (w₊, V), on N sites to the relative tolerance tol."""

    mode: str
    w_plus: float
    V: float
    N: int
    tol: float

    def __post_init__(self):
        if self.mode not in MODES:
            raise ParameterError("mode", self.mode, " | ".join(map(repr, MODES)))
        self._set("w_plus", require_finite("w_plus", self.w_plus))
        self._set("V", require_finite("V", self.V))
        self._set("N", require_int("N", self.N, N_MIN, N_MAX))
        self._set("tol", require_tol(self.tol))

    def call(self, lw) -> Call:
        """fpucore.wave.solve_superkink (V and branch from w₊; ParameterError outside the
        superkink's range) or fpucore.wave.solve_solitary."""
        if self.mode == "superkink":
            sk = qc.superkink_from_w_plus(lw, self.w_plus)
            kw = (("branch", sk.branch), ("N", self.N), ("tol", self.tol))
            return Call("wave", wave.solve_superkink, (float(sk.V),), kw)
        kw = (("N", self.N), ("tol", self.tol))
        return Call("wave", wave.solve_solitary, (self.w_plus, self.V), kw)

    def job_key(self, lw) -> tuple:
        """The solver's own inputs (a superkink's V and branch follow from w₊): two requests
        that make the same call share one result.  Raises ParameterError."""
        return ("wave", self.call(lw).key())

    def job(self, lw, progress=None):
        """Discrete traveling wave (fixed point of eq. nonlin_map): the WaveResult."""
        return self.call(lw).run(lw)


def _velocities(name: str, values) -> tuple[float, ...]:
    try:
        Vs = tuple(float(v) for v in values)
    except (TypeError, ValueError):
        raise ParameterError(name, values, "a sequence of velocities") from None
    if not Vs:
        raise ParameterError(name, values, "at least one velocity")
    return tuple(require_finite(name, v) for v in Vs)


@dataclass(frozen=True)
class FamilyRequest(Request):
    """Discrete solitary waves at the velocities ``V_values`` on the background w₊ (amplitude
    and energy dots of Figs. SWamp_cubic_DvsQC, SWenergy_cubic_DvsQC), each solve continued
    from its neighbour (fpucore.wave.solitary_family)."""

    w_plus: float
    V_values: tuple
    N: int
    tol: float

    def __post_init__(self):
        self._set("w_plus", require_finite("w_plus", self.w_plus))
        self._set("V_values", _velocities("V_values", self.V_values))
        self._set("N", require_int("N", self.N, N_MIN, N_MAX))
        self._set("tol", require_tol(self.tol))

    def call(self) -> Call:
        kw = (("N", self.N), ("tol", self.tol))
        return Call("wave", wave.solitary_family, (self.w_plus, list(self.V_values)), kw)

    def job(self, lw, progress=None) -> list:
        """The list of WaveResults (the family's ``results``)."""
        return list(self.call().run(lw, progress=fraction(progress)).results)


@dataclass(frozen=True)
class SweepRequest(Request):
    """max |μ| against V along a family (fpucore.atlas.sweep): ``kind`` "solitary" (on the
    background w₊) or "superkink" (w₊ None: each V's superkink on ``branch``), N sites."""

    kind: str
    w_plus: float | None
    V_values: tuple
    N: int
    branch: str = "lower"

    def __post_init__(self):
        if self.kind not in MODES:
            raise ParameterError("kind", self.kind, " | ".join(map(repr, MODES)))
        if self.w_plus is not None:
            self._set("w_plus", require_finite("w_plus", self.w_plus))
        self._set("V_values", _velocities("V_values", self.V_values))
        self._set("N", require_int("N", self.N, N_MIN, N_MAX))
        if self.branch not in ("lower", "upper"):
            raise ParameterError("branch", self.branch, "'lower' | 'upper'")

    def call(self) -> Call:
        kw = (
            ("kind", self.kind),
            ("V_values", list(self.V_values)),
            ("w_plus", self.w_plus),
            ("N", self.N),
            ("branch", self.branch),
        )
        return Call("atlas", atlas.sweep, (), kw)

    def job(self, lw, progress=None):
        """The SweepResult, computed inline in this worker: a pool worker is daemonic and may
        not start a pool of its own (the server's pool already spreads the sessions' jobs)."""
        return self.call().run(lw, progress=fraction(progress), executor=Executor(backend="inline"))


@dataclass(frozen=True, kw_only=True)
class SimulationRequest(Request):
    """What every direct simulation takes: L sites to time t_end, the run stopped when a strain
    leaves ``guard``'s interval (fpucore.simulate: "bounded" | "convex"), the histories of the
    1-based sites ``probes`` recorded."""

    L: int
    t_end: float
    guard: str = "bounded"
    probes: tuple = ()
    kind: ClassVar[str] = ""

    def __post_init__(self):
        self._set("L", require_int("L", self.L, 1, MAX_L))
        self._set("t_end", require_positive("t_end", self.t_end))
        if self.guard not in GUARDS:
            raise ParameterError("guard", self.guard, " | ".join(map(repr, GUARDS)))
        try:
            probes = tuple(self.probes)
        except TypeError:
            raise ParameterError("probes", self.probes, "a sequence of site numbers") from None
        self._set("probes", tuple(require_int("probes", p, 1, MAX_L) for p in probes))

    def options(self) -> tuple:
        """The run's keyword arguments, in the order the code shows them."""
        kw = (("L", self.L), ("t_end", self.t_end), ("guard", self.guard))
        kw += (("probes", self.probes),) if self.probes else ()
        # every site kept (fpucore's default keeps every k-th of 1000): the plots reduce the
        # field themselves, keeping its extremes (fpucore.simulate.extreme_blocks)
        return kw + (("max_sites_out", self.L),)

    def params(self) -> dict:
        """Every parameter by name, the run's options first (for a download's header)."""
        return {**dict(self.options()), **self.initial_data()}

    def initial_data(self) -> dict:
        raise NotImplementedError

    def call(self) -> Call:
        raise NotImplementedError

    def job(self, lw, progress=None):
        """Direct simulation via fpucore.simulate (the SimulationResult)."""
        extra = {} if progress is None else {"progress": progress}
        return self.call().run(self.first(lw), **extra)

    def first(self, lw):
        """The call's first argument: the law (a seeded run: its wave's result)."""
        return lw


@dataclass(frozen=True, kw_only=True)
class RiemannRequest(SimulationRequest):
    """Riemann data: w_left on the left half, w_right on the right (eq. Riemann_data)."""

    w_left: float
    w_right: float
    kind: ClassVar[str] = "riemann"

    def __post_init__(self):
        super().__post_init__()
        self._set("w_left", require_finite("w_left", self.w_left))
        self._set("w_right", require_finite("w_right", self.w_right))

    def initial_data(self) -> dict:
        return {"w_left": self.w_left, "w_right": self.w_right}

    def call(self) -> Call:
        return Call("simulate", sim.riemann, (self.w_left, self.w_right), self.options())


@dataclass(frozen=True, kw_only=True)
class GaussianRequest(SimulationRequest):
    """A Gaussian bump of height A on the background w_B (eq. GaussIC)."""

    w_B: float
    A: float
    kind: ClassVar[str] = "gaussian"

    def __post_init__(self):
        super().__post_init__()
        self._set("w_B", require_finite("w_B", self.w_B))
        self._set("A", require_finite("A", self.A))

    def initial_data(self) -> dict:
        return {"w_B": self.w_B, "A": self.A}

    def call(self) -> Call:
        return Call("simulate", sim.gaussian, (self.w_B, self.A), self.options())


@dataclass(frozen=True, kw_only=True)
class SeededRequest(SimulationRequest):
    """Data seeded by a discrete traveling wave (eq. fixedBCs): the call's first argument is the
    wave's result, not the law."""

    wave: WaveRequest
    kind: ClassVar[str] = "seeded"

    def __post_init__(self):
        super().__post_init__()
        if not isinstance(self.wave, WaveRequest):
            raise ParameterError("wave", self.wave, "a WaveRequest")

    def initial_data(self) -> dict:
        return {f.name: getattr(self.wave, f.name) for f in fields(self.wave)}

    def call(self) -> Call:
        return Call("simulate", sim.seeded, (), self.options())

    def first(self, lw):
        """The seeding wave, which must converge (ParameterError otherwise)."""
        r = self.wave.job(lw)
        if not r.converged:
            raise ParameterError(
                "N", self.wave.N, "a converged seeding wave", f"did not converge: {r.message}"
            )
        return r


#: the Atlas scene's small atlas: rows and velocities each in this range, N in SMALL_ATLAS_N
SMALL_ATLAS_POINTS = (2, 60)
SMALL_ATLAS_N = (40, 1000)


@dataclass(frozen=True)
class AtlasRequest(Request):
    """A small atlas of solitary waves with their Floquet spectra (no finite-size test): n_w
    rows of w₊ evenly over [w_lo, w_hi], n_V velocities spanning each row's existence
    interval, N sites."""

    w_lo: float
    w_hi: float
    n_w: int
    n_V: int
    N: int

    def __post_init__(self):
        self._set("w_lo", require_finite("w_lo", self.w_lo))
        self._set("w_hi", require_finite("w_hi", self.w_hi))
        if not self.w_lo < self.w_hi:
            raise ParameterError("w_hi", self.w_hi, f"a value above w_lo = {self.w_lo!r}")
        self._set("n_w", require_int("n_w", self.n_w, *SMALL_ATLAS_POINTS))
        self._set("n_V", require_int("n_V", self.n_V, *SMALL_ATLAS_POINTS))
        self._set("N", require_int("N", self.N, *SMALL_ATLAS_N))

    @property
    def n_points(self) -> int:
        return self.n_w * self.n_V

    def call(self) -> Call:
        """fpucore.atlas.run (rows "LO:HI:K": the floats by repr, read back exactly)."""
        kw = (
            ("rows", f"{self.w_lo!r}:{self.w_hi!r}:{self.n_w}"),
            ("V", self.n_V),
            ("N", self.N),
            ("floquet", True),
            ("finite_size", False),
        )
        return Call("atlas", atlas.run, ("solitary",), kw)

    def job(self, lw, progress=None):
        """The AtlasResult, its chunks (a row of the grid each) computed one after the other in
        this worker (a pool worker may not start a pool of its own); ``progress``: the
        fraction of points done, after each chunk."""
        return self.call().run(lw, executor=Executor(backend="inline"), progress=fraction(progress))
