"""Every public entry point's numeric parameters, drawn by hypothesis from the values that once
escaped ``ParameterError`` (huge Python ints: OverflowError; NaN: "cannot convert float NaN to
integer"; None, strings, lists, dicts, complex: TypeError; 0 and 5e-324: ZeroDivisionError) and
ordinary wild floats.  The property: a result or a ParameterError, nothing else.

The entry points and their valid small arguments are those of the fixed fuzz corpus
(benchmarks/api_fuzz.py, which counts the escapes over all of them: 413 of 2709 calls on the code
before this test, 0 now); the few whose valid call is a whole computation (atlas runs, sweeps,
families, spectra) are left to that corpus so the test stays fast.
"""

from __future__ import annotations

import math
import warnings

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from benchmarks.api_fuzz import BAD, entry_points
from fpucore import ParameterError

SLOW = {"atlas.run", "atlas.sweep", "wave.superkink_family", "wave.solitary_family",
        "floquet.energy_criterion", "floquet.spectrum", "floquet.monodromy", "simulate.seeded",
        "simulate.riemann", "simulate.gaussian", "wave.solve_superkink", "wave.solve_solitary",
        "diagram.existence_diagram", "diagram.solitary_family", "phase.phase_plane"}  # fmt: skip


@pytest.fixture(scope="module")
def calls():
    return {(name, p): (fn, kw) for name, fn, kw, params in entry_points() for p in params}


BAD_VALUES = st.one_of(
    st.sampled_from(BAD),
    st.integers(min_value=2**1024, max_value=10**600),  # beyond double precision
    st.integers(max_value=-(2**1024), min_value=-(10**600)),
    st.floats(allow_nan=True, allow_infinity=True),
    st.none(),
    st.text(max_size=3),
    st.lists(st.floats(allow_nan=True), max_size=2),
    st.complex_numbers(max_magnitude=10),
)
FAST = settings(derandomize=True, max_examples=200, deadline=None, database=None,
                suppress_health_check=list(HealthCheck))  # fmt: skip


@FAST
@given(data=st.data())
def test_a_bad_number_is_a_result_or_a_parameter_error(calls, data):
    key = data.draw(st.sampled_from(sorted(k for k in calls if k[0] not in SLOW)), label="call")
    bad = data.draw(BAD_VALUES, label="value")
    fn, kw = calls[key]
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fn(**{**kw, key[1]: bad})
    except ParameterError as exc:
        text = str(exc)
        assert "\n" not in text and len(text) < 2000, text
        assert exc.name, text


@pytest.mark.parametrize("bad", [10**400, -(10**400), math.nan, None, "x", [1.0]])
def test_wave_solvers_refuse_bad_numbers_before_the_work(calls, bad):
    for name in ("wave.solve_superkink", "wave.solve_solitary"):
        fn, kw = calls[(name, "V")]
        with pytest.raises(ParameterError) as ei:
            fn(**{**kw, "V": bad})
        assert ei.value.name == "V"
