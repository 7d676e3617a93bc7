"""An atlas point's record is read from the results' ``as_dict()`` (the result protocol) through
the one column list :data:`fpucore.atlas.point.COLUMNS`, which also gives the store's schema
(:data:`~fpucore.atlas.point.FIELDS`): each column must name a field of its result whose type
fits the column's dtype, and a record must hold exactly what the results say."""

from __future__ import annotations

import dataclasses
import inspect
import math
import pickle

import numpy as np
import pytest

from fpucore import atlas, floquet, wave
from fpucore.atlas.point import (
    COLUMNS,
    FIELDS,
    ChunkTask,
    FloquetOptions,
    add_floquet,
    solve_chunk,
    wave_record,
)
from fpucore.floquet.decision import Decision
from fpucore.floquet.multipliers import FloquetResult
from fpucore.law import CubicLaw
from fpucore.wave.driver import WaveResult

LAW = CubicLaw(-1.0, 10.0)
SOURCES = {"wave": WaveResult, "floquet": FloquetResult}
KIND = {"float": "f", "int": "i", "bool": "b", "str": "U"}  # annotation → numpy dtype kind


def _annotation(cls: type, name: str) -> str:
    """The annotated type of a dataclass field or a property of ``cls`` (as written)."""
    fields = {f.name: f.type for f in dataclasses.fields(cls)}
    if name in fields:
        return str(fields[name])
    prop = getattr(cls, name, None)
    assert isinstance(prop, property), f"{cls.__name__} has no field or property {name!r}"
    return str(inspect.signature(prop.fget).return_annotation)


def test_every_column_is_a_field_of_its_result_with_a_fitting_dtype():
    assert set(FIELDS) == set(COLUMNS) and len(FIELDS) == 31
    assert all(FIELDS[k] == (c.dtype, c.fill) for k, c in COLUMNS.items())
    seen = set()
    for name, col in COLUMNS.items():
        assert col.source in ("point", "wave", "floquet"), name
        if col.source == "point":
            assert name in ("status", "message", "elapsed_s"), name
            continue
        cls, *path = [SOURCES[col.source], *col.key.split(".")]
        if len(path) == 2:  # a nested record: the decision's headline
            assert path[0] == "decision" and cls is FloquetResult
            cls, path = Decision, path[1:]
        ann = _annotation(cls, path[0])
        assert np.dtype(col.dtype).kind == KIND[ann], (name, ann, col.dtype)
        seen.add((col.source, col.key))
    assert len(seen) == len(COLUMNS) - 3  # no result field stored twice


def test_a_record_holds_what_the_results_say():
    r = wave.solve_superkink(LAW, 5.6, N=64)
    fr = floquet.spectrum(r)
    rec = wave_record(r)
    add_floquet(rec, fr)
    assert set(rec) == set(FIELDS)
    d = {"wave": r, "floquet": fr}
    for name, col in COLUMNS.items():
        if col.source == "point":
            continue
        obj = d[col.source]
        for part in col.key.split("."):
            obj = getattr(obj, part)
        assert rec[name] == obj or (math.isnan(obj) and math.isnan(rec[name])), name
    assert rec["status"] == "ok" and rec["max_modulus_error"] == fr.error
    assert rec["floquet_integrator_error"] == fr.integrator_error != rec["integrator_error"]
    assert rec["elapsed_s"] == r.elapsed_s + fr.elapsed_s


def test_one_typed_task_reaches_the_worker_and_places_its_records():
    """The task crosses a process boundary (pickled) whole, and knows where its records go."""
    grid = atlas.make_grid(LAW, "superkink", ["lower"], [5.4, 5.6, 5.8], 3)
    base = ChunkTask(LAW, "superkink", N=64, tol=1e-12, floquet=FloquetOptions(True, m=300))
    task = base.at(grid, 0, 1, 3)
    assert (task.row, task.V, task.row_index, task.start, task.stop) == ("lower", (5.6, 5.8), 0,
                                                                         1, 3)  # fmt: skip
    assert pickle.loads(pickle.dumps(task)) == task
    with pytest.raises(dataclasses.FrozenInstanceError):
        task.N = 8  # type: ignore[misc]
    recs = solve_chunk(task)
    assert [r["status"] for r in recs] == ["ok", "ok"] and all(r["N"] == 64 for r in recs)
    fr = floquet.spectrum(wave.solve_superkink(LAW, 5.6, N=64), m=300)  # the first: no neighbour
    assert recs[0]["max_modulus"] == fr.max_modulus  # the options reached the spectrum
    off = solve_chunk(ChunkTask(LAW, "superkink", N=64, tol=1e-12, row="lower", V=(5.6,)))
    assert math.isnan(off[0]["max_modulus"]) and off[0]["classification"] == ""
