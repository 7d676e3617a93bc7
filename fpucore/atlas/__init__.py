"""Stability atlas: waves, energies and Floquet multipliers over a grid of the existence region
(w₊, V) or along the superkink velocities, on a local process pool or a Dask cluster.

grid (rows × V, chunks = runs of V along a row)  →  point (one chunk on a worker: continuation
in grid order, wave + spectrum → records named as the CLI's JSON fields)  →  store (Zarr,
written chunk by chunk, locked, resumable)  →  run (submit through fpucore.parallel, gather,
AtlasResult)

    res = atlas.run(CubicLaw(-1, 10), "solitary", rows="0.2:6.5:40", V=40, N=500,
                    floquet=True, out="atlas.zarr")
"""

# floquet first: its sweeps are atlas runs (floquet.sweeps imports atlas.point and atlas.run),
# and atlas.point imports floquet.multipliers — loaded in this order, ``import fpucore.atlas`` as
# a process's first import (the ``fpu atlas`` command; fpucore/__init__ no longer imports the
# subpackages) finds every name it needs
import fpucore.floquet  # noqa: F401, I001
from fpucore.atlas.grid import Grid, make_grid, parse_values, velocity_span
from fpucore.atlas.point import FIELDS, solve_chunk
from fpucore.atlas.run import AtlasResult, run
from fpucore.atlas.store import StoreLock

__all__ = [
    "Grid",
    "make_grid",
    "parse_values",
    "velocity_span",
    "FIELDS",
    "solve_chunk",
    "AtlasResult",
    "run",
    "StoreLock",
]
