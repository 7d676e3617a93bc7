"""Server warm-up (``fpu serve``, i.e. ``panel serve --setup app/warm.py``, which calls
:func:`setup`): runs once before the server accepts
connections, so no visitor waits for Numba compilation or for the default view.

1. fpucore's JIT warm-up (loads or compiles every Numba kernel; with cache=True and a writable
   NUMBA_CACHE_DIR the compiled code is reused from disk across restarts), in the server process
   and in every worker process of the heavy computations (app.compute.workers.warm_workers);
2. renders every scene once for the default parameters, which fills the process-wide result
   cache (QC scenes, the default discrete wave and its Floquet spectrum) and imports/initializes
   HoloViews' Bokeh backend.
"""

from __future__ import annotations

import atexit
import logging
import os
import subprocess
import sys
import threading
import time

log = logging.getLogger("fpu-explorer")


os.environ.setdefault("BOKEH_RESOURCES", "server")  # see app/main.py; before panel is imported

from fpucore.parallel import apply_thread_policy  # noqa: E402
from fpucore.warm import warm_all  # noqa: E402

from . import compute  # noqa: E402
from .content_policy import install_content_security_policy  # noqa: E402
from .explorer import Explorer  # noqa: E402
from .law_presets import preset_texts  # noqa: E402
from .resources import serve_locally  # noqa: E402
from .scene_registry import WARM_SCENES  # noqa: E402

# the thread budget (fpucore/parallel/threads.py): the server computes for several sessions at
# once, so one BLAS/OpenMP thread per computation; parallelism comes from processes (Executor)
apply_thread_policy(1)

#: the scenes rendered by default: those the registry marks warm (app/scene_registry.py)
DEFAULT_SCENES = WARM_SCENES
WARM_LAW = "w + 10*w**2 - w**3 - 0.01*w**4"


def _warm_background() -> None:
    t = time.perf_counter()
    compute.workers.warm_workers()
    log.info("fpu-explorer: workers warm in %.2f s", time.perf_counter() - t)
    try:  # lowest priority: it must not slow the first pages (measured 4.6 s -> 15 s at load 6)
        p = subprocess.Popen(
            [sys.executable, "-m", "fpucore", "warm", "--serial"], stdout=subprocess.DEVNULL
        )
        os.setpriority(os.PRIO_PROCESS, p.pid, 19)
    except OSError as exc:
        log.warning("background JIT warm-up not started: %s", exc)


def request_preset_laws() -> list[str]:
    """Every preset's law (app.law_presets) requested from the law worker (never waited for
    here); returns their texts."""
    texts = preset_texts()
    for text in texts:
        compute.laws.request_law(text)
    return texts


def warm(verbose: bool = True, scenes: str | None = None) -> dict[str, float]:
    """Warm the JIT and the cache; returns seconds spent per step.

    ``scenes``: comma-separated scene keys to pre-render, "all" or "none"; default (environment
    variable FPU_WARM_SCENES) the scenes the registry marks ``warm`` (app/scene_registry.py):
    not the Floquet spectrum, whose eigenvalue calls (0.2–0.8 s alone at N = 500, many times
    that on a loaded machine) would hold the server's start: it is computed when the tab is
    first shown.  The browser tests use "force,phase" to
    start fast.
    """
    scenes = scenes or os.environ.get("FPU_WARM_SCENES", DEFAULT_SCENES)
    times: dict[str, float] = {}
    t0 = time.perf_counter()
    try:
        # the essential kernels: compiled here on a fresh clone (make serve), loaded from the
        # cache in ~0.5 s otherwise (container, restarts); one process, since the parallel path
        # spawned two processes only to reload a warm cache (7-8 s) and compiled 2.7x slower
        warm_all(parallel=False, lazy=False)
    except Exception as exc:  # warm-up must never keep the server from starting
        log.warning("fpucore warm-up skipped: %s", exc)
    times["jit"] = time.perf_counter() - t0
    # the worker processes start and load the cache while the server starts serving (they were
    # ~10 s of the wait for /liveness); a heavy job submitted meanwhile queues behind their
    # warm-up.  Then the lazy routes (fpucore.warm.LAZY) compile on one core.
    threading.Thread(target=_warm_background, name="fpu-warm-workers", daemon=True).start()
    # the law worker starts and imports SymPy now, not at the first typed law or law link; then
    # it builds every preset's law (0.04-0.5 s each), so a preset chosen is applied at once
    compute.laws.request_law(WARM_LAW)
    request_preset_laws()

    explorer = Explorer()
    for scene in explorer.scenes:
        if scenes != "all" and scene.key not in scenes.split(","):
            continue
        t = time.perf_counter()
        explorer.state.tab = scene.key
        scene.refresh()
        times[scene.key] = time.perf_counter() - t
    if verbose:
        print(
            "fpu-explorer warm-up:",
            ", ".join(f"{k} {v:.2f}s" for k, v in times.items()),
            flush=True,
        )
    return times


def setup() -> None:
    """The server's set-up (app/warm.py): local resources, shutdown order, :func:`warm`."""
    serve_locally()
    install_content_security_policy()  # before the server's first page
    # On exit (Bokeh stops its loop on SIGTERM and Ctrl-C) the worker pool stops first: a worker
    # start cut short by the exit would make the fork server print a traceback.
    atexit.register(compute.workers.shutdown_executor)
    atexit.register(compute.laws.shutdown_law_executor)
    warm()
