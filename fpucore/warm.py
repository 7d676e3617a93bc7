"""JIT warm-up: run one tiny problem through every jitted route (results are discarded).

With ``cache=True`` the compiled code lands in NUMBA_CACHE_DIR, so later processes (the server,
its worker threads, the tests) load it instead of compiling.
"""

from __future__ import annotations

import numpy as np

from .law import CubicLaw, ddforce, dforce, force


def warm_all() -> list[str]:
    law = CubicLaw()
    p = law.params
    force(law.law_id, p, 0.5), dforce(law.law_id, p, 0.5), ddforce(law.law_id, p, 0.5)
    done = ["law"]
    # Later routes register here as they land (discrete waves, Floquet, simulation).
    for name, fn in _ROUTES:
        fn(law)
        done.append(name)
    return done


_ROUTES: list = []
_ = np  # numpy is used by the routes appended below
