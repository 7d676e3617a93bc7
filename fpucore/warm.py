"""JIT warm-up: run one tiny problem through every jitted route (results are discarded).

With ``cache=True`` the compiled code lands in NUMBA_CACHE_DIR, so later processes (the server,
its workers, the tests) load it from disk (~1 s) instead of compiling (~30 s in all).

First start (measured in benchmarks/README.md, "First start"):

* ``parallel=True`` compiles one spawned process per group in :data:`GROUPS` (balanced by
  measured compile time: the RKN12 chain stepper alone is ~40 % of the total) and the parent
  then loads the cached code.  On the shared 2-core machine this measured 2.7× *slower* than one
  process for the essential set (35.8 s against 13.5 s, same load), so ``make serve`` and the
  server use ``parallel=False``; the option stays for idle multi-core machines (``fpu warm``);
* the chain simulation's integrators (:data:`LAZY`: the default RKN12 stepper, DOPRI5, the
  symplectic stepper) are not needed to serve the first page: ``warm_all(lazy=False)`` leaves
  them out and :func:`warm_lazy` (``fpu warm --serial`` in the server's background) compiles
  them later, after the server is up.

Processes are spawned, never forked: a process forked after Numba's OpenMP layer has run
deadlocks (see fpucore.parallel).
"""

from __future__ import annotations

import multiprocessing as mp
import signal
import time
from collections.abc import Callable

from fpucore import floquet, simulate, wave
from fpucore.law import CubicLaw, TrilinearLaw, ddforce, dforce, force


def _law_kernels(law) -> None:
    p = law.params
    force(law.law_id, p, 0.5), dforce(law.law_id, p, 0.5), ddforce(law.law_id, p, 0.5)


def _wave(law) -> None:
    wave.warm(law)


def _floquet(law) -> None:
    # the quarter-size reversible route (the default method: the Floquet scene's spectrum and the
    # finite-size test's shorter rings for every reversible wave, the paper's families; the
    # constant state is reversible) and dense (the reference, `--method dense`), so a visitor of
    # the Floquet scene waits for no compile
    state = floquet.HomogeneousState(law, 1.0, 5.0, 16)
    floquet.spectrum(state, method="structured")
    floquet.spectrum(state, method="dense")


def _floquet_structured(law) -> None:
    # the half-size isotropic Arnoldi route: only non-reversible waves take it (e.g. the superkinks
    # of a general polynomial law), forced here with reversor=None
    state = floquet.HomogeneousState(law, 1.0, 5.0, 16)
    mono = floquet.monodromy(state)
    floquet.structured_multipliers(mono.matrix, 16, mono.K, reversor=None)


def _wave_pwl(law) -> None:
    # piecewise-linear laws: the event-located period map (base, with stored sub-steps) and the
    # tangent on it, through one superkink and its spectrum (the law argument is the cubic's)
    pl = TrilinearLaw(0.5, 1.5, 1.0, 4.0, 0.2)
    floquet.spectrum(wave.solve_superkink(pl, 1.6, N=64), finite_size=False)


def _riemann(law, **kw) -> None:
    simulate.riemann(law, 4.6, 0.0, L=40, t_end=0.5, n_snapshots=4, **kw)


def _simulate(law) -> None:
    _riemann(law)  # the default method (rkn12; rkn8 shares its kernel)


def _simulate_dopri5(law) -> None:
    _riemann(law, method="dopri5")  # dop853 shares the embedded-RK kernel


def _simulate_symplectic(law) -> None:
    _riemann(law, method="symplectic", dt=0.01)


ROUTES: dict[str, Callable] = {
    "law": _law_kernels,
    "wave": _wave,
    "floquet": _floquet,
    "floquet-structured": _floquet_structured,
    "wave-pwl": _wave_pwl,
    "simulate": _simulate,
    "simulate-dopri5": _simulate_dopri5,
    "simulate-symplectic": _simulate_symplectic,
}
# compile groups of about equal cost (measured cold: simulate 12 s, wave 8 s, floquet-structured
# 7 s, dopri5 4.7 s, floquet 2.3 s, symplectic 2 s, law 0.6 s); the essential routes alone split
# 8 s / 2.9 s
GROUPS: tuple[tuple[str, ...], ...] = (
    ("wave", "simulate-dopri5", "simulate-symplectic"),
    ("law", "floquet", "floquet-structured", "wave-pwl", "simulate"),
)
# not needed before the first page: compiled in the background once the server is up, the
# half-size Arnoldi Floquet route first (non-reversible waves' finite-size test uses it;
# essential, it pushed the first page from 13.5 to 22.7 s; the reversible route, which the
# paper's waves take, is in "floquet": 1.3 s cold), then the chain simulation (its tab runs
# nothing until asked; the RKN12 stepper is ~40 % of all compile time).  "wave-pwl": the
# event-located map of piecewise-linear laws (a preset of the explorer, not the first page).
LAZY = ("floquet-structured", "wave-pwl", "simulate", "simulate-dopri5", "simulate-symplectic")


def _ignore_interrupt() -> None:
    """Worker initializer: Ctrl-C is the parent's to handle (one line, exit 130), not a traceback
    from each compiling child.  The parent terminates the children on Ctrl-C; "spawn" as their
    own start method keeps Numba from guarding its threading layer with a named semaphore, which
    a terminated child would leave to the resource tracker ("leaked semaphore", as in
    fpucore.parallel.worker)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    mp.set_start_method("spawn", force=True)


def warm_routes(names: tuple[str, ...]) -> float:
    """Run the named routes in this process; returns the seconds spent."""
    t0 = time.perf_counter()
    law = CubicLaw()
    for name in names:
        ROUTES[name](law)
    return time.perf_counter() - t0


def warm_all(parallel: bool = True, lazy: bool = True) -> list[str]:
    """Compile (or load) every route on the paper's law; returns the names of the routes warmed.

    parallel : compile the :data:`GROUPS` in spawned processes at once, then load in this one.
    lazy : include the chain simulation's integrators, :data:`LAZY` (False: leave them to
    :func:`warm_lazy`).
    """
    groups = [tuple(n for n in g if lazy or n not in LAZY) for g in GROUPS]
    groups = [g for g in groups if g]
    if parallel and len(groups) > 1:
        # a Pool, not a ProcessPoolExecutor: on Ctrl-C the executor's exit waited for the
        # children (which ignore SIGINT) to finish compiling — over a minute on a loaded
        # machine before `fpu: interrupted`; the Pool's exit terminates them at once
        with mp.get_context("spawn").Pool(len(groups), initializer=_ignore_interrupt) as pool:
            pool.map(warm_routes, groups)
    # the essential routes first, then LAZY in its order (the serial background warm-up: the
    # half-size Floquet route before the simulation)
    names = tuple(n for g in groups for n in g if n not in LAZY) + (LAZY if lazy else ())
    warm_routes(names)  # compiled above (parallel): loads from the on-disk cache
    return list(names)


def warm_lazy() -> None:
    """Compile the routes of :data:`LAZY` (background thread or process)."""
    warm_routes(LAZY)
