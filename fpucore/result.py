"""The result protocol shared by every result object of fpucore (waves, spectra, simulations, QC).

Every result is a frozen dataclass that mixes in :class:`Result` and has

* ``converged`` (bool): the result passed its own accuracy / success check;
* ``status`` (str): one of :data:`STATUSES` — ``"ok"`` (converged), ``"not_converged"`` (the
  solver finished without meeting its check; the numbers are reported, not hidden) or
  ``"stopped"`` (a budget or guard ended the computation early: a partial result);
* ``message`` (str): what happened, in words (why it failed, what to change);
* ``elapsed_s`` (float): wall time of the computation in seconds;
* its error fields, named in the class attribute ``ERROR_FIELDS`` (absolute unless the field's
  docstring says otherwise).

``as_dict()`` is generated from the dataclass fields (plus the names in ``DERIVED``), so a field
added to a result appears in the CLI's JSON without a hand-kept list; :func:`jsonable` turns it
(or any nest of dicts, lists, NumPy scalars and arrays) into what ``json.dumps`` takes — the one
conversion used by the CLI, the dashboard's downloads, the sweeps' rows and the atlas store.
A caller that wants strictness calls :meth:`Result.require_converged`, which raises
:class:`fpucore.errors.ConvergenceError` with the result's message.  This module imports only
:mod:`fpucore.errors` (it is imported by all).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any, ClassVar, Self

import numpy as np

from fpucore.errors import ConvergenceError

STATUSES = ("ok", "not_converged", "stopped")


def status_of(converged: bool, stopped: bool = False) -> str:
    """The status word for a result (see :data:`STATUSES`)."""
    if converged:
        return "ok"
    return "stopped" if stopped else "not_converged"


def jsonable(obj: Any) -> Any:
    """Recursively convert NumPy scalars and arrays to Python values, tuples to lists and
    non-finite floats to None, for ``json.dumps`` (and for comparing stored with fresh values)."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, np.str_):
        return str(obj)
    return obj


def _field_value(value: Any, arrays: bool) -> tuple[bool, Any]:
    """(keep, value) for one field: nested results become dicts, law objects their description,
    complex arrays are split by the caller; arrays are dropped when ``arrays`` is False."""
    if isinstance(value, Result):
        return True, value.as_dict(arrays=arrays)
    if dataclasses.is_dataclass(value) and hasattr(value, "as_dict"):  # a plain record
        return True, value.as_dict()
    if isinstance(value, np.ndarray):
        return arrays, value
    if isinstance(value, (list, tuple)) and value and hasattr(value[0], "as_dict"):
        return True, [v.as_dict() for v in value]
    if hasattr(value, "constants_dict") and hasattr(value, "representation_error"):  # smooth law
        err = value.representation_error
        return True, {
            "law": value.describe(),
            "text": value.text,
            "constants": value.constants_dict,
            "represented_interval": list(value.interval),
            "representation_error": [err.f, err.df, err.ddf],
        }
    if hasattr(value, "law_id") and hasattr(value, "params"):  # a force law
        return True, {"law": value.describe(), "params": np.asarray(value.params).tolist()}
    if callable(value):
        return False, None
    return True, value


class Result:
    """Mixin for result dataclasses: the common vocabulary and a generated :meth:`as_dict`."""

    ERROR_FIELDS: ClassVar[tuple[str, ...]] = ()
    DERIVED: ClassVar[tuple[str, ...]] = ("status",)  # properties included in as_dict
    EXCLUDE: ClassVar[tuple[str, ...]] = ()  # fields never serialised (internal objects)

    def as_dict(self, arrays: bool = True) -> dict:
        """Every field (and ``DERIVED`` property) as a JSON-ready value; complex arrays become
        ``<name>_re`` / ``<name>_im``; ``arrays=False`` leaves the arrays out (a summary)."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            if f.name in self.EXCLUDE:
                continue
            keep, v = _field_value(getattr(self, f.name), arrays)
            if not keep:
                continue
            if isinstance(v, np.ndarray) and np.iscomplexobj(v):
                out[f"{f.name}_re"], out[f"{f.name}_im"] = v.real, v.imag
            else:
                out[f.name] = v
        for name in self.DERIVED:
            out[name] = getattr(self, name)
        return out

    def require_converged(self) -> Self:
        """Return self if converged, else raise ConvergenceError (status and message)."""
        if not getattr(self, "converged", True):
            name = type(self).__name__
            raise ConvergenceError(f"{name} {self.status}: {getattr(self, 'message', '')}")  # type: ignore[attr-defined]  # every result defines it
        return self

    def errors(self) -> dict[str, float]:
        """The error fields of this result by name; a field holding one bar per row (sweeps,
        families) gives its largest finite entry (NaN if none)."""
        out = {}
        for k in self.ERROR_FIELDS:
            v = np.asarray(getattr(self, k), dtype=float)
            if v.ndim:
                v = v[np.isfinite(v)]
                v = v.max() if v.size else np.nan  # type: ignore[assignment]  # a scalar now
            out[k] = float(v)
        return out
