"""Reference runs for refactors: 20+ computations through the public API (waves — superkinks,
solitary and flat-top waves at a few V and N —, families, dense and structured spectra, a sweep,
a tiny atlas, simulations) whose numeric outputs are stored once and compared bit for bit later.

    python -m benchmarks.reference_runs save ref.pkl       # on the commit before the change
    python -m benchmarks.reference_runs compare ref.pkl    # after it: exit 1 on any difference

Every result is flattened to ``path → value`` (its ``as_dict()``, recursively); arrays compare
with ``np.array_equal`` (NaN = NaN), scalars and strings with ``==``.  A value renamed since the
reference was saved is compared under its new name (:data:`RENAMED`); a value added since then
(:data:`ADDED`) has nothing to compare with and is only counted; any other key present on one side
only is a difference.  Timing fields (names
ending in ``elapsed_s`` or ``_s`` of wall/CPU time) and run-time notes are left out: they differ
between any two runs.  Runs on one process (``workers=1``) so that it costs about a minute.
"""

from __future__ import annotations

import dataclasses
import math
import pickle
import re
import sys
import time

import numpy as np

from fpucore import floquet, qc, simulate, wave
from fpucore.atlas import run as atlas_run
from fpucore.atlas import sweep
from fpucore.law import CubicLaw, PolynomialLaw

LAW = CubicLaw(-1.0, 10.0)
QUARTIC = PolynomialLaw((1.0, 10.0, -1.0, -0.2))
V_SK6 = 7 * math.sqrt(5) / 3
TIMING = re.compile(r"(elapsed|wall|cpu|seconds|_time$|_s$|timings?)", re.I)  # wall-clock
# (runs, old key, new key): renamed since a reference was saved.  Sweeps took the atlas's names
# (their rows are atlas records; their arrays are fields of the result, so in as_dict), a
# family's per-wave flags became ``wave_converged`` (``converged``: the protocol's bool).
_ROW = r"^(rows\[\d+\]\.)"
RENAMED = [
    (r"^sweep_", r"^arrays\.error$", "max_modulus_error"),
    (r"^sweep_", r"^arrays\.converged$", "floquet_converged"),
    (r"^sweep_", r"^arrays\.(\w+)$", r"\1"),
    (r"^sweep_", _ROW + r"error$", r"\1max_modulus_error"),
    (r"^sweep_", _ROW + r"integrator_error$", r"\1floquet_integrator_error"),
    (r"^sweep_", _ROW + r"converged$", r"\1floquet_converged"),
    (r"^sweep_", _ROW + r"wave_converged$", r"\1converged"),
    (r"^sweep_", _ROW + r"wave_residual$", r"\1residual"),
    (r"^family_", r"^converged$", "wave_converged"),
]
# (runs, new key): added since a reference was saved (the sweep rows' other atlas fields, the
# result protocol's summary of sweeps and families)
ADDED = [
    (
        r"^sweep_",
        _ROW + r"(status|kind|amplitude|dropped_residual|tail_error|integrator_error|"
        r"qc_max_deviation|profile_error|amplitude_error|N|iterations)$",
    ),
    (r"^sweep_", r"^(status|converged|stopped)$"),
    (r"^family_", r"^(status|converged|message)$"),
]


def _waves() -> dict:
    sk, sw = wave.solve_superkink, wave.solve_solitary
    return {
        "sk_lower_5.0": lambda: sk(LAW, 5.0),
        "sk_lower_5.5": lambda: sk(LAW, 5.5),
        "sk_lower_5.8": lambda: sk(LAW, 5.8),
        "sk_upper_5.5": lambda: sk(LAW, 5.5, "upper"),
        "sk_lower_5.5_N200": lambda: sk(LAW, 5.5, N=200),
        "sk_lower_5.3_N64_tol1e-10": lambda: sk(LAW, 5.3, N=64, tol=1e-10),
        "sk_quartic_mid": lambda: sk(QUARTIC, _mid_sk(QUARTIC)),
        "sw_w1_below": lambda: sw(LAW, 1.0, 0.5 * sum(_sw_iv(LAW, 1.0)[0])),
        "sw_w1_above": lambda: sw(LAW, 1.0, 0.5 * sum(_sw_iv(LAW, 1.0)[1])),
        "sw_w6_V4.5": lambda: sw(LAW, 6.0, 4.5),
        "sw_w6_V4.5_N300": lambda: sw(LAW, 6.0, 4.5, N=300),
        "flat_top_w6_below_auto": lambda: sw(LAW, 6.0, 5.21749194749),
        "flat_top_w6_below_N300": lambda: sw(LAW, 6.0, 5.21749194749, N=300),
        "flat_top_w6_above": lambda: sw(LAW, 6.0, V_SK6 + 1e-6),
        "sw_quartic": lambda: sw(QUARTIC, 0.5, 0.5 * sum(_sw_iv(QUARTIC, 0.5)[0])),
    }


def _mid_sk(law) -> float:
    lo, hi = qc.superkink_velocity_bounds(law)
    return 0.5 * (lo + hi)


def _sw_iv(law, w_plus):
    return qc.solitary_intervals(law, w_plus)


def _continued() -> dict:
    """Solitary waves next to V_SK that Newton from the QC guess misses: continuation in V from
    the family's easy end (wave.continuation.continue_to), also on stiff laws (b = 100, 1000,
    a = -0.01) where the round-off floor of the step count matters."""
    out = {}
    for a, b in ((-1.0, 10.0), (-1.0, 100.0), (-0.01, 1.0), (-1.0, 1000.0)):
        law = CubicLaw(a, b)
        for w_plus in (1.0, 6.0):
            _, (lo, hi) = qc.solitary_intervals(law, w_plus)
            for f in (1e-5, 1e-3):
                V = lo + f * (hi - lo)
                out[f"continued_{a:g}_{b:g}_w{w_plus:g}_{f:g}"] = (
                    lambda law=law, w_plus=w_plus, V=V: wave.solve_solitary(law, w_plus, V)
                )
    return out


def cases() -> dict:
    c = _waves() | _continued()
    sk64 = lambda: wave.solve_superkink(LAW, 5.6, N=64)  # noqa: E731
    sw80 = lambda: wave.solve_solitary(LAW, 1.0, 4.8, N=80)  # noqa: E731
    c |= {
        "spectrum_sk_dense": lambda: floquet.spectrum(sk64(), method="dense"),
        "spectrum_sk_structured": lambda: floquet.spectrum(sk64(), method="structured"),
        "spectrum_sw_dense": lambda: floquet.spectrum(sw80(), method="dense"),
        "spectrum_sw_structured": lambda: floquet.spectrum(sw80(), method="structured"),
        "family_superkink": lambda: wave.superkink_family(LAW, [5.2, 5.4, 5.6, 5.8]),
        "family_solitary": lambda: wave.solitary_family(LAW, 1.0, [4.5, 4.7, 4.9, 5.1]),
        "sweep_superkink": lambda: sweep(
            LAW, "superkink", [5.3, 5.6], N=64, use_cache=False, workers=1
        ),
        "atlas_solitary": lambda: atlas_run(
            LAW,
            "solitary",
            rows=[0.5, 1.0],
            V=[3.5, 4.5, 5.2],
            N=None,
            floquet=True,
            floquet_method="dense",  # the method it was saved with (the default until then)
            workers=1,
            chunk=3,
        ),  # fmt: skip
        "atlas_superkink": lambda: atlas_run(
            LAW, "superkink", rows=["lower"], V=[5.2, 5.5], N=64, workers=1
        ),
        "sim_riemann": lambda: simulate.riemann(LAW, 2.0, 0.5, 200, 20.0),
        "sim_gaussian": lambda: simulate.gaussian(LAW, 0.5, 0.3, 200, 10.0),
        "sim_seeded": lambda: simulate.seeded(sk64(), t_end=5.0),
    }
    return c


def flatten(obj, path: str = "", out: dict | None = None) -> dict:
    out = {} if out is None else out
    if hasattr(obj, "as_dict"):
        obj = obj.as_dict()
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):  # a record: its fields
        obj = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
    if hasattr(obj, "dataset"):  # AtlasResult: its table
        obj = {k: obj.dataset[k].values for k in obj.dataset.data_vars}
    if isinstance(obj, dict):
        for k, v in obj.items():
            if TIMING.search(str(k)):
                continue
            flatten(v, f"{path}.{k}" if path else str(k), out)
    elif (
        isinstance(obj, (list, tuple))
        and obj
        and isinstance(obj[0], (dict,))
        or (isinstance(obj, (list, tuple)) and obj and hasattr(obj[0], "as_dict"))
    ):
        for i, v in enumerate(obj):
            flatten(v, f"{path}[{i}]", out)
    else:
        out[path] = np.asarray(obj) if isinstance(obj, (list, tuple, np.ndarray)) else obj
    return out


def _results(obj) -> dict:
    """Families carry their WaveResults in ``results`` (a sweep's arrays are in its as_dict)."""
    return {"results": list(obj.results)} if hasattr(obj, "results") else {}


def compute(names=None) -> dict:
    out = {}
    for name, fn in cases().items():
        if names and name not in names:
            continue
        t0 = time.perf_counter()
        res = fn()
        flat = flatten(res)
        for k, v in _results(res).items():
            flatten(v, k, flat)
        if hasattr(res, "dataset"):  # an atlas: its table, not only the summary
            for k in res.dataset.data_vars:
                if not TIMING.search(k):
                    flat[f"table.{k}"] = res.dataset[k].values
        out[name] = flat
        print(f"{name}: {len(flat)} values, {time.perf_counter() - t0:.1f} s", flush=True)
    return out


def same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        return bool(np.array_equal(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def renamed(name: str, r: dict) -> dict:
    """The reference's values of run ``name`` under today's names (:data:`RENAMED`: every key
    renamed at once, by its first matching rule).  A reference saved after a rename has its
    values under today's names already: a key whose new name it holds too is today's own key
    (a family's ``converged`` beside its ``wave_converged``, a sweep row's ``converged`` beside
    its ``floquet_converged``), not an old name, and keeps its name — unless that new name is
    itself an old one renamed away (an old sweep row's ``wave_converged`` → ``converged`` →
    ``floquet_converged``)."""
    rules = [(re.compile(old), new) for runs, old, new in RENAMED if re.search(runs, name)]

    def new_name(k: str) -> str | None:
        return next((old.sub(new, k) for old, new in rules if old.search(k)), None)

    out = {}
    for k, v in r.items():
        target = new_name(k)
        if target is not None and not (target in r and new_name(target) is None):
            k = target  # an old name (its new name is free, or itself renamed away)
        out[k] = v
    return out


def added(name: str, key: str) -> bool:
    return any(re.search(runs, name) and re.search(k, key) for runs, k in ADDED)


def compare(ref: dict, new: dict, extra: list | None = None) -> list[str]:
    """Differences between two computations (``extra`` collects the keys of :data:`ADDED`)."""
    bad = []
    for name in ref:
        if name not in new:
            bad.append(f"{name}: missing")
            continue
        r, n = renamed(name, ref[name]), new[name]
        for k in sorted(set(r) | set(n)):
            if TIMING.search(k.rsplit(".", 1)[-1]):
                continue
            if k not in r and added(name, k):
                if extra is not None:
                    extra.append(f"{name}.{k}")
                continue
            if k not in r or k not in n:
                bad.append(f"{name}.{k}: only in {'ref' if k in r else 'new'}")
            elif not same(r[k], n[k]):
                bad.append(f"{name}.{k}: {str(r[k])[:200]!s} != {str(n[k])[:200]!s}")
    return bad


def main(argv: list[str]) -> int:
    mode, path = argv[0], argv[1]
    names = argv[2:] or None
    new = compute(names)
    if mode == "save":
        with open(path, "wb") as f:
            pickle.dump(new, f)
        print(f"saved {len(new)} runs, {sum(len(v) for v in new.values())} values to {path}")
        return 0
    with open(path, "rb") as f:
        ref = pickle.load(f)
    if names:
        ref = {k: v for k, v in ref.items() if k in names}
    extra: list = []
    bad = compare(ref, new, extra)
    n_vals = sum(len(v) for v in ref.values())
    print(
        f"compared {len(ref)} runs, {n_vals} values: {len(bad)} differences"
        + (f" ({len(extra)} values added since the reference, not compared)" if extra else "")
    )
    for line in bad:
        print("  " + line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
