"""``fpu warm``: compile (and cache) every Numba kernel so no user waits for the JIT."""

from __future__ import annotations

import time

from fpucore.warm import warm_all


def register(sub) -> None:
    p = sub.add_parser("warm", help="compile and cache all Numba kernels (run before serving)")
    p.set_defaults(func=run)


def run(args) -> int:
    t0 = time.perf_counter()
    done = warm_all()
    print(f"warmed {', '.join(done) or 'nothing'} in {time.perf_counter() - t0:.1f} s")
    return 0
