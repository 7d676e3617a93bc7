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
from fpucore.law.scale import require_computable
from fpucore.law.smooth_class import ClassFailure, convex_end, inflection
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
MARGIN = 0.5  # represented interval: W/2 beyond each end of the convex interval


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
        lg = tuple(compile_node(t, named, "long") for t in trees)
        mp = tuple(compile_node(t, named, "mp") for t in trees)
        set_(self, "_fns", fl)
        set_(self, "_trees", trees)
        diag = lambda x: diagnose(exprs[1], w, x, values)  # noqa: E731
        try:
            self._check(fl, lg, mp, diag, lambda x: diagnose(exprs[0], w, x, values))
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

    def _check(self, fl, lg, mp, diag_df, diag_f):
        import mpmath

        set_ = object.__setattr__
        f, df, ddf = fl
        with np.errstate(all="ignore"):
            d0 = float(df(np.float64(0.0)))
        if not math.isfinite(d0):
            raise ClassFailure(f"f' is not finite at w = 0: {diag_df(0.0)}")
        with mpmath.workdps(40):
            try:
                f0 = mp[0](mpmath.mpf(0))
                f0 = abs(complex(f0))
            except (ValueError, ZeroDivisionError, TypeError):
                raise ClassFailure(f"f(0) is not defined: {diag_f(0.0)}") from None
        if not f0 <= 1e-25 * max(1.0, abs(d0)):
            raise ClassFailure(f"f(0) = {f0:.6g} is not 0 (the unstrained spring carries no force)")
        if not d0 > 0:
            raise ClassFailure(
                f"f'(0) = {d0:.6g} must be positive: the unstrained chain must be "
                "stable (0 inside the convex interval (alpha, beta))"
            )
        # the class is decided on float64 roots; only a law that passes pays for the 30-digit
        # polish and the representation (a refusal stays within ~10 ms of float64 scans)
        beta_root = convex_end(df, 1.0, diag_df)
        alpha_root = convex_end(df, -1.0, diag_df)
        assert beta_root is not None  # no upper end is refused inside convex_end
        for r, side in ((beta_root, 1.0), (alpha_root, -1.0)):
            self._not_a_pole(r, side, f, df, diag_f, diag_df)
        beta = beta_root.x
        alpha = alpha_root.x if alpha_root is not None else -math.inf
        # a lower end that overflows/leaves the domain close to 0 is a domain error in (α, β)
        lo_probe = -np.logspace(-30, math.log10(4 * beta), 400)
        with np.errstate(all="ignore"):
            pv = np.asarray(df(lo_probe), dtype=float)
        pv_bad = ~np.isfinite(pv) & (lo_probe > alpha)
        if np.any(pv_bad):
            x = float(lo_probe[pv_bad][0])
            raise ClassFailure(
                f"f' is not finite at w = {x:.6g} inside the convex interval: {diag_df(x)}"
            )
        lo, hi = self._domain(fl, *self._margins(alpha, beta), alpha, beta, diag_f)
        n_grid = 8 * cheb.MAX_PANELS
        w_star_root = inflection(ddf, alpha if math.isfinite(alpha) else lo, beta, n_grid)
        try:  # too steep: refused before any longdouble or 30-digit work
            start = cheb.first_level(fl[2], lo, hi)
        except ValueError as exc:
            raise ClassFailure(
                f"the law cannot be represented on [{lo:.6g}, {hi:.6g}]: {exc}"
            ) from None
        # in the class: the 30-digit roots, and the represented interval from them
        beta, beta_err = beta_root.polished(mp[1])
        alpha, alpha_err = alpha_root.polished(mp[1]) if alpha_root else (-math.inf, 0.0)
        w_star, w_star_err = w_star_root.polished(mp[2])
        lo, hi = self._domain(fl, *self._margins(alpha, beta), alpha, beta, diag_f)
        set_(self, "alpha", alpha)
        set_(self, "beta", beta)
        set_(self, "alpha_error", alpha_err)
        set_(self, "beta_error", beta_err)
        set_(self, "w_star", w_star)
        set_(self, "w_star_error", w_star_err)
        c2 = float(df(np.float64(w_star)))
        require_computable("expression", self.text, alpha, beta, w_star, c2, "f'(w*)")
        try:
            rep = cheb.build(lg, mp, lo, hi, start)
        except ValueError as exc:
            raise ClassFailure(
                f"the law cannot be represented on [{lo:.6g}, {hi:.6g}]: {exc}"
            ) from None
        set_(self, "interval", (float(lo), float(hi)))
        set_(self, "_rep", rep)

    @staticmethod
    def _not_a_pole(r, side, f, df, diag_f, diag_df) -> None:
        """A sign change of f′ through a singularity (|f′| → ∞ at the float root, e.g. the
        1/(w + 1/2) of log(w + 1/2)) is no end of the convex interval: refused as the domain
        error it is (f beyond it), or as the singularity."""
        if r is None or r.a == r.b:
            return
        with np.errstate(all="ignore"):
            at = abs(float(df(np.float64(r.x))))
            ends = max(abs(float(df(np.float64(r.a)))), abs(float(df(np.float64(r.b)))))
        if at <= ends:
            return
        xb = r.x + side * 1e-6 * max(1.0, abs(r.x))
        with np.errstate(all="ignore"):
            if not math.isfinite(float(f(np.float64(xb)))):
                raise ClassFailure(
                    f"f is not a finite real number at w = {xb:.6g} inside the "
                    f"convex interval: {diag_f(xb)}"
                )
        raise ClassFailure(
            f"f' changes sign through a singularity at w = {r.x:.6g} (|f'| is "
            f"unbounded there), not through a zero: {diag_df(r.x)}"
        )

    @staticmethod
    def _margins(alpha: float, beta: float) -> tuple[float, float]:
        """[α − W/2, β + W/2], W = β − α (α = −∞: −β in its place)."""
        w_ref = alpha if math.isfinite(alpha) else -beta
        W = beta - w_ref
        return w_ref - MARGIN * W, beta + MARGIN * W

    @staticmethod
    def _domain(fl, lo, hi, alpha, beta, diag_f):
        """[lo, hi] shrunk to where f, f′, f″ are finite (a gap kept to the first bad point);
        a bad point inside [α, β] is a domain error."""
        for _ in range(4):
            x = np.linspace(lo, hi, 8193)
            with np.errstate(all="ignore"):
                ok = np.ones(x.size, bool)
                for g in fl[:3]:
                    ok &= np.isfinite(np.asarray(g(x), dtype=float))
            if np.all(ok):
                return float(lo), float(hi)
            bad = x[~ok]
            inside = bad[(bad >= alpha) & (bad <= beta)]
            if inside.size:
                xb = float(inside[0])
                raise ClassFailure(
                    f"f is not a finite real number at w = {xb:.6g} inside the "
                    f"convex interval: {diag_f(xb)}"
                )
            above, below = bad[bad > beta], bad[bad < alpha]
            if above.size:
                hi = beta + 0.5 * (above[0] - beta)
            if below.size:
                lo = alpha - 0.5 * (alpha - below[-1])
        return float(lo), float(hi)

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
