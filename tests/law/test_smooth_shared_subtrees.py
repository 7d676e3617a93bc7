"""f, f′ and f″ of a smooth law share subtrees (sinh(w) occurs in all three of w·sinh(sinh(w))):
compiled with one ``shared`` dict, each distinct subtree is evaluated once per argument, and
the values are bit for bit those of the separate trees (the same operations on the same numbers).
The nested laws that need all 4096 panels were accepted in ~0.75 s before, ~0.3 s now (quiet
machine, best of five; 0.45-0.55 CPU s beside a CI run, so this law is not among the text-bounds
test's timed holes: its 0.5 s budget for smooth laws is not a margin it keeps under load)."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from fpucore.law import law_from_expression, smooth_tree

NESTED = "w + 10*w**2 - w**3 + 1e-30*(-(sinh(sinh(w))))*w"


def counted(monkeypatch, name: str) -> list:
    calls = [0]
    fn = smooth_tree.NUMPY_FNS[name]

    def counting(x):
        calls[0] += 1
        return fn(x)

    monkeypatch.setitem(smooth_tree.NUMPY_FNS, name, counting)
    return calls


def test_shared_subtrees_are_evaluated_once_per_argument(monkeypatch):
    trees = law_from_expression(NESTED)._trees  # f, f′, f″
    x = np.linspace(-1.0, 2.0, 101).astype(np.longdouble)
    sinh, cosh = counted(monkeypatch, "sinh"), counted(monkeypatch, "cosh")
    alone = [smooth_tree.compile_node(t, {}, "long")(x) for t in trees]
    n_alone = sinh[0] + cosh[0]
    sinh[0] = cosh[0] = 0
    shared: dict = {}
    fns = [smooth_tree.compile_node(t, {}, "long", shared) for t in trees]
    together = [g(x) for g in fns]
    # distinct: sinh(w), cosh(w), sinh(sinh(w)), cosh(sinh(w)): each once for the three
    assert sinh[0] == 2 and cosh[0] == 2, (sinh[0], cosh[0])
    assert n_alone > 4  # the separate trees repeat them
    for a, b in zip(alone, together, strict=True):
        assert a.dtype == b.dtype == np.longdouble
        assert np.array_equal(a, b)  # bit for bit
    # a new argument is evaluated anew (identity, not a stale value)
    y = x + np.longdouble(0.5)
    assert np.array_equal(fns[2](y), smooth_tree.compile_node(trees[2], {}, "long")(y))


def test_shared_mpmath_values_equal_the_separate_trees():
    trees = law_from_expression(NESTED)._trees
    shared: dict = {}
    fns = [smooth_tree.compile_node(t, {}, "mp", shared) for t in trees]
    with mpmath.workdps(30):
        for v in ("-0.7", "0.3", "1.9"):
            x = mpmath.mpf(v)
            for t, g in zip(trees, fns, strict=True):
                assert g(x) == smooth_tree.compile_node(t, {}, "mp")(x)


def test_the_float_back_end_does_not_share():
    # float64 closures are kept by the law and may get one buffer changed in place
    tree = law_from_expression(NESTED)._trees[0]
    with pytest.raises(ValueError, match="'long' and 'mp'"):
        smooth_tree.compile_node(tree, {}, "float", {})


def test_a_shared_mpmath_value_is_not_reused_at_another_precision():
    trees = law_from_expression(NESTED)._trees
    shared: dict = {}
    f, df = (smooth_tree.compile_node(t, {}, "mp", shared) for t in trees[:2])
    x = mpmath.mpf("0.3")  # one number, evaluated at 15 and then at 50 digits
    with mpmath.workdps(15):
        df(x)
    with mpmath.workdps(50):
        assert f(x) == smooth_tree.compile_node(trees[0], {}, "mp")(x)


def test_mpmath_constants_are_rounded_at_the_working_precision():
    # compiled at mpmath's default 15 digits, called at 50: 1/3 and 1e-30 to 50 digits
    tree = law_from_expression("w + 10*w**2 - w**3/3 - 1e-30*exp(w)*w**2")._trees[0]
    f = smooth_tree.compile_node(tree, {}, "mp")
    with mpmath.workdps(50):
        x = mpmath.mpf("0.3")
        exact = x + 10 * x**2 - x**3 / 3 - mpmath.mpf(10) ** -30 * mpmath.exp(x) * x**2
        assert abs(f(x) - exact) <= mpmath.mpf(10) ** -48 * abs(exact)
