"""The JIT warm-up's partition (issue 17, first start): every route compiles in exactly one group,
the essential set (what the server warms before it answers) covers the first page's kernels, and
``warm_all(lazy=False)`` runs exactly that set.  References: the route names themselves and the
server's warm-up (app/warm.py pre-renders the profiles scene: the discrete-wave kernels)."""

from __future__ import annotations

from fpucore import warm


def test_every_route_in_exactly_one_group():
    names = [n for g in warm.GROUPS for n in g]
    assert sorted(names) == sorted(warm.ROUTES) and len(names) == len(set(names))
    assert set(warm.LAZY) <= set(warm.ROUTES)


def test_essential_routes_cover_the_first_page():
    essential = set(warm.ROUTES) - set(warm.LAZY)
    assert {"law", "wave", "floquet"} <= essential
    assert "simulate" in warm.LAZY  # the largest compile (RKN12 stepper) is not waited for


def test_warm_all_without_lazy_runs_only_the_essential_routes(monkeypatch):
    ran: list[str] = []
    fake = {name: (lambda law, n=name: ran.append(n)) for name in warm.ROUTES}
    monkeypatch.setattr(warm, "ROUTES", fake)
    done = warm.warm_all(parallel=False, lazy=False)
    assert sorted(done) == sorted(ran) == sorted(set(warm.ROUTES) - set(warm.LAZY))
    ran.clear()
    warm.warm_lazy()
    assert sorted(ran) == sorted(warm.LAZY)
