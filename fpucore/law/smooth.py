"""Any smooth hardening–softening law, from text: ``SmoothLaw("w + b*w**2 - c*w**3*exp(w/d)",
{"b": 10, "c": 1, "d": 50})`` (paper §2–3 for a general f).

Built in four steps, each refused with :class:`~fpucore.errors.ParameterError` (name
``"expression"``) and the reason:

1. parse only (:mod:`.smooth_parse`: allow-list, bounds) and the exact derivatives by SymPy;
2. the class check on the law's own convex interval (:mod:`.smooth_class`): f(0) = 0, f′(0) > 0,
   α, β (f′ = 0 around 0), exactly one inflection w* > 0 where f″ goes from + to −, and the
   computable range of :mod:`.scale`; a value that is not a finite real number inside (α, β)
   (log of a negative number, a fractional power of a negative number, exp overflow) names the
   operation and the strain;
3. the represented interval [lo, hi] = [α − W/2, β + W/2], W = β − α (α = −∞: α replaced by
   −β), shrunk to stay inside the domain of the expression: it holds every state of
   the QC and discrete waves (strains in [α, β]), of the Floquet spectra of those waves, and of
   simulations guarded by the convex interval; simulations with ``guard='bounded'`` are
   stopped at its ends;
4. the piecewise Chebyshev representation of f, f′, f″ on [lo, hi] (:mod:`.chebyshev`), the data
   of the one compiled kernel ``LAW_CHEB``, with its measured error
   (:attr:`SmoothLaw.representation_error`).

``f, df, ddf`` in Python evaluate the exact expression in float64 (the QC route's root finding
and quadrature use them: no representation error there); ``phi`` integrates the represented f
(consistent with the kernels' forces, so the simulations' energy is conserved to the
integrator's accuracy).  The kernels see only the representation.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.polynomial import chebyshev as C

from fpucore.errors import ParameterError
from fpucore.law import chebyshev as cheb
from fpucore.law.base import HardeningSofteningLaw, Strain
from fpucore.law.kernels import LAW_CHEB
from fpucore.law.smooth_build import MARGIN as MARGIN
from fpucore.law.smooth_build import check_and_represent
from fpucore.law.smooth_class import ClassFailure
from fpucore.law.smooth_parse import (
    VALID,
    abbreviate,
    check_constant_name,
    check_constant_value,
    parse_smooth,
)
from fpucore.law.smooth_tree import compile_node

EPS = float(np.finfo(float).eps)
MAX_QUAD_PANELS = 64  # composite Gauss–Legendre panels of the QC integrals (2048 nodes)


@functools.lru_cache(maxsize=64)
def symbolic(text: str, names: frozenset):
    """(w, symbols, (f, f′, f″)) — SymPy derivatives, cached per text."""
    import sympy as sp

    from fpucore.law.smooth_eval import UnsupportedNode, derivative

    expr, w, syms = parse_smooth(text, names)
    try:
        d1 = derivative(expr, w)
        d2 = derivative(d1, w) if d1 is not None else None
    except UnsupportedNode as exc:
        raise ParameterError("expression", abbreviate(text), VALID, str(exc)) from None
    zero = sp.Integer(0)
    return w, syms, (expr, d1 if d1 is not None else zero, d2 if d2 is not None else zero)


def checked_constants(constants) -> tuple[tuple[str, float], ...]:
    if constants is None:
        return ()
    if not hasattr(constants, "items"):
        raise ParameterError("constants", constants, "a mapping {name: value}, e.g. {'b': 10}")
    return tuple(
        sorted((check_constant_name(k), check_constant_value(k, v)) for k, v in constants.items())
    )


@dataclass(frozen=True)
class SmoothLaw(HardeningSofteningLaw):
    """A smooth hardening–softening law f(w) given as text with named constants.

    Parameters
    ----------
    text : the expression in w (module :mod:`.smooth_parse` for the grammar).
    constants : {name: value} of the named constants in the text (finite reals).

    Derived (refused if the hypotheses of paper §2 fail): ``alpha``, ``beta`` (α may be −∞),
    ``w_star`` with ``*_error`` bars, ``interval`` (the represented [lo, hi]),
    ``representation_error`` (:class:`~fpucore.law.chebyshev.RepresentationError`).
    """

    text: str = "w + b*w**2 - c*w**3*exp(w/d)"
    constants: tuple = ()
    alpha: float = field(init=False, default=math.nan)
    beta: float = field(init=False, default=math.nan)
    w_star: float = field(init=False, default=math.nan)
    alpha_error: float = field(init=False, default=math.nan)
    beta_error: float = field(init=False, default=math.nan)
    w_star_error: float = field(init=False, default=math.nan)
    interval: tuple = field(init=False, default=(math.nan, math.nan))
    _rep: cheb.Representation = field(init=False, repr=False, compare=False)
    _fns: tuple = field(init=False, repr=False, compare=False, default=())
    _trees: tuple = field(init=False, repr=False, compare=False, default=())

    def __post_init__(self):
        set_ = object.__setattr__
        consts = checked_constants(
            dict(self.constants) if isinstance(self.constants, tuple) else self.constants
        )
        set_(self, "constants", consts)
        set_(self, "law_id", LAW_CHEB)
        if not isinstance(self.text, str):
            raise ParameterError("expression", self.text, VALID, "the expression must be a string")
        w, syms, exprs = symbolic(self.text, frozenset(n for n, _ in consts))
        values = {syms[n]: v for n, v in consts}
        from fpucore.law.smooth_eval import UnsupportedNode, diagnose, to_node

        try:
            trees = tuple(to_node(e, w) for e in exprs)
        except UnsupportedNode as exc:
            self._refuse(str(exc))
        named = dict(consts)
        fl = tuple(compile_node(t, named, "float") for t in trees)
        # f, f′ and f″ share their common subtrees (evaluated once per argument)
        long_shared, mp_shared = {}, {}
        lg = tuple(compile_node(t, named, "long", long_shared) for t in trees)
        mp = tuple(compile_node(t, named, "mp", mp_shared) for t in trees)
        set_(self, "_fns", fl)
        set_(self, "_trees", trees)
        diag = lambda x: diagnose(exprs[1], w, x, values)  # noqa: E731
        try:
            check_and_represent(self, fl, lg, mp, diag, lambda x: diagnose(exprs[0], w, x, values))
        except ClassFailure as exc:
            self._refuse(str(exc))

    def __reduce__(self):
        # the evaluators are closures (not picklable): rebuilt from the plain-tuple trees, so a
        # law sent to another process (the explorer's server, an atlas worker) arrives as the
        # same law without SymPy and without a new class check
        state = {k: getattr(self, k) for k in _STATE}
        return (_restore, (state,))

    def _refuse(self, reason: str):
        shown = (
            self.text
            if not self.constants
            else (f"{self.text}; " + ", ".join(f"{n}={v:g}" for n, v in self.constants))
        )
        raise ParameterError("expression", abbreviate(shown, 120), VALID, reason)

    # ----- kernel handle
    @property
    def params(self) -> np.ndarray:
        """The piecewise Chebyshev data of ``LAW_CHEB`` (layout in :mod:`.chebyshev`)."""
        return self._rep.params.copy()

    @property
    def representation_error(self) -> cheb.RepresentationError:
        """Measured error of the kernels' f, f′, f″ on :attr:`interval` (absolute)."""
        return self._rep.error

    # ----- vectorised evaluation of the exact expression (float64)
    def _eval(self, k: int, w):
        w = np.asarray(w, dtype=float)
        with np.errstate(all="ignore"):
            out = np.asarray(self._fns[k](w), dtype=float)
        return np.broadcast_to(out, w.shape).copy() if out.shape != w.shape else out

    def f(self, w: Strain) -> np.ndarray:
        return self._eval(0, w)

    def df(self, w: Strain) -> np.ndarray:
        return self._eval(1, w)

    def ddf(self, w: Strain) -> np.ndarray:
        return self._eval(2, w)

    def represented(self, k: int, w: Strain) -> np.ndarray:
        """f (k = 0), f′ (1), f″ (2) as the kernels compute them (NaN outside :attr:`interval`)."""
        return self._rep.value(k, w)

    @functools.cached_property
    def _phi_tables(self):
        coef = self._rep.coef[0]
        lo, hi = self.interval
        npan = coef.shape[0]
        h = (hi - lo) / npan
        ci = np.array([C.chebint(c, lbnd=-1) for c in coef]) * (0.5 * h)  # ∫ over the panel
        full = np.array([C.chebval(1.0, c) for c in ci])
        start = np.concatenate([[0.0], np.cumsum(full)])
        return ci, start, h

    def phi(self, w: Strain) -> np.ndarray:
        """Φ(w) = ∫₀ʷ f, the represented f integrated exactly (NaN outside :attr:`interval`)."""
        ci, start, _h = self._phi_tables
        lo, hi = self.interval
        prim = lambda x: cheb.clenshaw(ci, lo, hi, x, start[:-1])  # noqa: E731
        return prim(np.asarray(w, dtype=float)) - prim(np.float64(0.0))

    @functools.cached_property
    def _quadrature(self) -> tuple[int, float]:
        """(panels, relative error) of the composite Gauss–Legendre rule (32 nodes a panel) for
        the QC route's integrals over t ∈ [0, 1] (:mod:`fpucore.qc.general_roots`): panels
        double from 1 until the rule agrees with the doubled one to 1e-14 relative to ∫|·| (or
        stops gaining near that level: its rounding floor) on the hardest of them over the whole
        convex interval, ∫₀¹ t(1−t) f″(a + t(β − a)) dt, a = max(α, lo); at most
        :data:`MAX_QUAD_PANELS`.  The error left (0 when converged) enters the QC root error
        bars (:func:`fpucore.qc.general_roots.bracketed_root`)."""
        a = max(self.alpha, self.interval[0])
        d = self.beta - a
        x0, w0 = np.polynomial.legendre.leggauss(32)

        def rule(P):
            t = ((np.arange(P)[:, None] + 0.5 * (x0[None, :] + 1.0)) / P).ravel()
            wt = np.tile(w0, P) / (2.0 * P)
            g = t * (1.0 - t) * self.ddf(a + t * d) * wt
            return float(np.sum(g)), float(np.sum(np.abs(g)))

        P, prev = 1, math.inf
        v1, s1 = rule(P)
        while True:
            v2, s2 = rule(2 * P)
            diff = abs(v1 - v2) / max(s1, s2)
            if diff <= 1e-14 or (diff <= 1e-11 and diff >= 0.5 * prev):
                return P, 0.0 if diff <= 1e-14 else diff
            if 2 * P >= MAX_QUAD_PANELS:
                return 2 * P, diff
            P, prev, v1, s1 = 2 * P, diff, v2, s2

    @property
    def quadrature_panels(self) -> int:
        return self._quadrature[0]

    @property
    def quadrature_error(self) -> float:
        """Relative error left in the QC route's t-integrals (0: converged to 1e-14)."""
        return self._quadrature[1]

    # ----- constants
    def with_constants(self, **values: float) -> SmoothLaw:
        """The same text with some constants changed, e.g. ``law.with_constants(d=40)``: again a
        smooth law (built here, not through :func:`~fpucore.law.law_from_expression`, which
        builds this class: no import cycle), even where the new values make the text a
        polynomial (then ``law_from_expression`` of the substituted text gives its exact
        polynomial kernel)."""
        names = dict(self.constants)
        for k in values:
            if k not in names:
                raise ParameterError(k, values[k], f"one of the law's constants {sorted(names)}")
        return SmoothLaw(self.text, checked_constants({**names, **values}))

    @property
    def constants_dict(self) -> dict:
        return dict(self.constants)

    @property
    def expression(self) -> str:
        """The text (constants separately, :attr:`constants_dict`)."""
        return self.text

    def describe(self) -> str:
        tail = ", ".join(f"{n}={v:g}" for n, v in self.constants)
        return f"f(w) = {self.text}" + (f" with {tail}" if tail else "")


_STATE = (
    "text",
    "constants",
    "alpha",
    "beta",
    "w_star",
    "alpha_error",
    "beta_error",
    "w_star_error",
    "interval",
    "_rep",
    "_trees",
)


def _restore(state: dict) -> SmoothLaw:
    law = object.__new__(SmoothLaw)
    for k, v in state.items():
        object.__setattr__(law, k, v)
    object.__setattr__(law, "law_id", LAW_CHEB)
    named = dict(state["constants"])
    object.__setattr__(law, "_fns", tuple(compile_node(t, named, "float") for t in state["_trees"]))
    return law
