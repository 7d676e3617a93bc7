"""The JIT warm-up's partition (first start): every route compiles in exactly one group,
the essential set (what the server warms before it answers) covers the first page's kernels, and
``warm_all(lazy=False)`` runs exactly that set.  References: the route names themselves and the
server's warm-up (app/warm.py pre-renders the profiles scene: the discrete-wave kernels)."""

from __future__ import annotations

import json
import subprocess
import sys

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


# run in a fresh interpreter: in the test session earlier tests may have compiled everything
_SCENE_SCRIPT = """
import json
from fpucore import floquet, warm, wave
from fpucore.floquet import kernels, reversible_kernels
from fpucore.law import CubicLaw
from fpucore.wave import period_map

def signatures():
    return {f"{m.__name__}.{k}": len(v.signatures)
            for m in (kernels, reversible_kernels, period_map) for k, v in vars(m).items()
            if hasattr(v, "signatures") and hasattr(v, "py_func")}

law = CubicLaw(-1.0, 10.0)
warm.ROUTES["floquet"](law)
r = wave.solve_superkink(law, 5.2, N=100)  # unstable at N = 100: the finite-size test runs
before = signatures()
fr = floquet.spectrum(r)
print(json.dumps({"before": before, "after": signatures(), "n": int(fr.finite_size_N.size),
                  "cls": fr.classification}))
"""


def test_the_essential_floquet_route_compiles_what_the_floquet_scene_runs():
    """After the essential "floquet" warm-up, a spectrum with its finite-size test (the scene's
    computation: dense at N, the reversible route on up to 5 rings in [N/2, N]) adds no compiled
    signature, so no visitor waits for a compile (a new signature is a compile or a cache
    load).  Fails when the warm-up leaves the reversible route out."""
    out = subprocess.run([sys.executable, "-c", _SCENE_SCRIPT], capture_output=True, text=True,
                         timeout=600, check=True)  # fmt: skip
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert res["n"] >= 3 and res["cls"] != "stable"  # the window (it stops once decided)
    assert res["after"] == res["before"]
    assert all(n > 0 for k, n in res["before"].items() if "reversible_kernels" in k)
