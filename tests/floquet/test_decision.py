"""The stability decision on synthetic windows e(N) with a known answer, and the record's texts.

The window is the one the spectrum computes at N = 500 (6 rings in [250, 500]).  References are
the laws the sequences are built from: a ring resonance is a sawtooth under a C/N envelope (the
splitting of colliding phonon multipliers spaced 2π/N), a mode of the wave a constant growth.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from fpucore.floquet import decision
from fpucore.floquet import finite_size as fs

N = np.array(fs.chain_lengths(500) + [500], float)


def _decide(e, err=None, n=N):
    err = np.full(len(e), 2e-12) if err is None else err
    return decision.decide(np.asarray(n, float), np.asarray(e, float), err, growth_rate=0.01)


# a sawtooth whose peaks lie on 0.3/N: which phonon pair collides changes with N
SAW = np.array([1.0, 0.35, 0.9, 0.55, 1.0, 0.95])


@pytest.mark.parametrize(
    "e, cls, reason",
    [
        (0.3 / N * SAW, "finite_size", "dips"),  # sawtooth, 1/N envelope, present everywhere
        (0.3 / N * np.r_[1.0, 0.9, 0.8, 0.9, 1.0, 0.95], "finite_size", "decays"),
        (0.3 / N * np.where(SAW > 0.5, SAW, 0.0), "finite_size", "absent"),  # comes and goes
        (0.3 / N, "finite_size", "decays"),  # the clean 1/N law (superkink V = 4.8)
        (1.93 / N - 8.0 / N**2, "finite_size", "decays"),  # 1/N with curvature (e·N rising)
        (np.full(N.size, 1e-3), "unstable", "persists"),  # constant positive: a mode
        (0.01 + 0.3 / N, "unstable", "persists"),  # converged to a positive limit within 6 %
        (np.linspace(3e-5, 7e-5, N.size), "undetermined", "unresolved"),  # grows with N
        (np.array([2e-3, 9e-4, 5e-4, 3e-4, 2e-4, 1e-13]), "stable", "within_error"),
    ],
)
def test_synthetic_windows(e, cls, reason):
    d, _ = _decide(e)
    assert (d.classification, d.reason) == (cls, reason), d.sentence
    assert (d.next_step != "") == (cls == "undetermined")


def test_two_points_are_undetermined_and_say_what_would_decide():
    d, _ = _decide([2e-3, 1e-3], n=[250, 500])
    assert d.classification == "undetermined" and d.reason == "few_lengths"
    assert "compute at N >= 1000" in d.sentence and d.next_step in d.sentence
    d, _ = decision.decide(np.array([64.0]), np.array([6e-3]), np.array([1e-12]), 0.01, "N = 64 is "
                     "too short", n_min=64)  # fmt: skip
    assert d.classification == "undetermined" and "compute at N >= 128" in d.sentence


def test_a_window_stopped_early_is_decided_by_its_absent_excess_or_dip():
    """The spectrum computes the rings shortest first and stops once an absent excess or a dip
    has decided the window (fs.settled); three points then suffice."""
    n = np.array([250, 292, 500], float)
    e = np.array([3.97e-5, 2.2e-16, 6.197e-5])  # superkink V = 5.6, N = 500 (measured)
    err = np.full(3, 1e-10)
    assert fs.settled(n, e, err) and not fs.settled(n[[0, 2]], e[[0, 2]], err[:2])
    d, _ = decision.decide(n, e, err, 0.01)
    assert (d.classification, d.reason) == ("finite_size", "absent")
    dip = np.array([1.4e-4, 3.1e-5, 1.2e-4])
    assert fs.settled(n, dip, err) and decision.decide(n, dip, err, 0.01)[0].reason == "dips"
    assert not fs.settled(n, np.array([2e-4, 1.5e-4, 1.2e-4]), err)  # a decay needs the window


def test_the_old_three_point_fallback_cases_are_no_longer_unstable():
    """The superkink V = 4.8 at the README's lengths (measured, points of a 1/N law with
    curvature) and V = 5.6 (a sawtooth): the old test said "unstable" for both."""
    n = np.array([250, 292, 334, 376, 416, 458, 500], float)
    e48 = np.array([7.60e-3, 6.53e-3, 5.73e-3, 5.10e-3, 4.63e-3, 4.21e-3, 3.864e-3])
    e56 = np.array([3.97e-5, 2.2e-16, 7.16e-5, 8.54e-5, 1.00e-4, 9.16e-5, 6.197e-5])
    e555 = np.array([1.67e-5, 1.38e-4, 1.55e-4, 1.42e-4, 3.12e-5, 8.27e-5, 1.19e-4])
    assert _decide(e48, n=n)[0].reason == "decays"
    assert _decide(e56, n=n)[0].reason == "absent"
    assert _decide(e555, n=n)[0].reason == "dips"
    # the old e∞ fit: "significantly positive" for this 1/N law with curvature
    old = fs.extrapolate(n, e48, np.full(n.size, 2e-12))
    assert old[0] > 2 * old[1]


_NUM = re.compile(r"[-+]?\d+\.\d+e[-+]\d+")


@pytest.mark.parametrize(
    "e", [0.3 / N * SAW, 0.3 / N, 0.3 / N * np.where(SAW > 0.5, SAW, 0.0), np.full(N.size, 1e-3),
          np.linspace(3e-5, 7e-5, N.size), np.r_[np.full(N.size - 1, 1e-3), 1e-13]],
)  # fmt: skip
def test_words_agree_with_the_numbers(e):
    """Headline and sentence come from one record, and what they claim is true of the points
    printed beside them; no fit is printed whose error bar exceeds its value."""
    d, _ = _decide(e)
    s, h = d.sentence, d.headline
    assert s.split(":")[0] in h or h.startswith(s.split(":")[0])
    printed = [float(x) for x in _NUM.findall(s.split("max|mu|-1 at N = ")[-1])]
    if d.classification == "stable":
        assert d.excess <= d.error
    elif d.classification == "finite_size" and d.reason == "absent":
        assert any(x <= 2e-12 for x in printed) and "comes and goes" in h
        for n in d.absent_N:
            assert f"{n}: " in s
    elif d.classification == "finite_size" and d.reason == "dips":
        k = list(d.points_N).index(d.dip_N[0])
        assert printed[k] < 0.5 * min(max(printed[:k]), max(printed[k + 1 :]))
        assert "comes and goes" in h and f"below {min(printed):.2e}" in s
    elif d.classification == "finite_size":
        assert printed[-1] < max(printed) and "decays" in h
    elif d.classification == "unstable":
        assert min(printed) > 0 and (max(printed) - min(printed)) <= 0.1 * printed[-1]
        assert "persists" in h
    else:
        assert h == "not determined at N = 500" and "compute at N >= 1000" in s
    for p, dp in re.findall(r"p = ([-\d.]+) \+/- ([-\d.e+]+)", s):
        assert float(dp) < abs(float(p))
    j = json.loads(json.dumps(d.as_dict()))
    assert j["headline"] == h and j["sentence"] == s and j["classification"] in fs.CLASSES
    assert all(v is None or not isinstance(v, float) or math.isfinite(v) for v in j.values())
