"""Stability atlas: waves, energies and Floquet multipliers over a grid of the existence region
(w₊, V) or along the superkink velocities, on a local process pool or a Dask cluster; sweeps
of the Floquet spectrum along a family are one-row atlases.

grid (rows × V, chunks = runs of V along a row)  →  point (one ChunkTask on a worker:
continuation in grid order, wave + spectrum → records read from the results' as_dict, named as
the CLI's JSON fields)  →  store (Zarr, written chunk by chunk, locked, resumable)  →  execute
(the chunks' tasks submitted through fpucore.parallel, gathered into the table)  →  run (checks,
plan, AtlasResult)  →  reader (a store or a run's table as AtlasData: typed arrays, no layout
names)  →  sweeps (max|μ| along V: one row, cached by its inputs and the code).  In use::

    res = atlas.run(CubicLaw(-1, 10), "solitary", rows="0.2:6.5:40", V=40, N=500,
                    floquet=True, out="atlas.zarr")
    data = atlas.open_atlas("atlas.zarr")        # data.w_plus, data.V, data.max_modulus, ...
    sw = atlas.sweep(CubicLaw(-1, 10), "superkink", [5.2, 5.5, 5.8], N=500)
"""

from fpucore.atlas.grid import Grid, make_grid, parse_values, velocity_span
from fpucore.atlas.point import FIELDS, ChunkTask, FloquetOptions, solve_chunk
from fpucore.atlas.reader import AtlasData, atlas_data, open_atlas
from fpucore.atlas.run import AtlasResult, run
from fpucore.atlas.store import StoreLock
from fpucore.atlas.sweeps import SweepResult, sweep

__all__ = [
    "Grid",
    "make_grid",
    "parse_values",
    "velocity_span",
    "FIELDS",
    "ChunkTask",
    "FloquetOptions",
    "solve_chunk",
    "AtlasResult",
    "run",
    "AtlasData",
    "atlas_data",
    "open_atlas",
    "StoreLock",
    "SweepResult",
    "sweep",
]
