"""JIT warm-up: run one tiny problem through every jitted route (results are discarded).

With ``cache=True`` the compiled code lands in NUMBA_CACHE_DIR, so later processes (the server,
its worker threads, the tests) load it from disk instead of compiling.
"""

from __future__ import annotations

from fpucore import floquet, simulate, wave
from fpucore.law import CubicLaw, ddforce, dforce, force


def _law_kernels(law) -> None:
    p = law.params
    force(law.law_id, p, 0.5), dforce(law.law_id, p, 0.5), ddforce(law.law_id, p, 0.5)


def _wave(law) -> None:
    wave.warm(law)


def _floquet(law) -> None:
    floquet.spectrum(floquet.HomogeneousState(law, 1.0, 5.0, 16))


def _simulate(law) -> None:
    simulate.riemann(law, 4.6, 0.0, L=40, t_end=0.5, n_snapshots=4)
    simulate.riemann(law, 4.6, 0.0, L=40, t_end=0.5, n_snapshots=4, method="symplectic", dt=0.01)
    simulate.riemann(law, 4.6, 0.0, L=40, t_end=0.5, n_snapshots=4, method="dopri5")


ROUTES = [("law", _law_kernels), ("wave", _wave), ("floquet", _floquet), ("simulate", _simulate)]


def warm_all() -> list[str]:
    """Compile every route on the paper's law; returns the names of the routes warmed."""
    law = CubicLaw()
    for _, fn in ROUTES:
        fn(law)
    return [name for name, _ in ROUTES]
