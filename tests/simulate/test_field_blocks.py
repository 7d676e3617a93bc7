"""extreme_blocks: a field reduced for drawing keeps its extremes (every k-th site does not)."""

from __future__ import annotations

import numpy as np
import pytest

from fpucore.errors import ParameterError
from fpucore.simulate import extreme_blocks


def test_a_one_site_peak_and_a_one_site_dip_survive_the_reduction():
    L = 2400
    n = np.arange(1, L + 1)
    z = np.ones((3, L))
    z[0, 1200] = 7.0  # a peak one site wide (eq. GaussIC's width is ~1 site)
    z[2, 1799] = -3.0  # a dip at another time
    z[0, 1201] = -0.5  # a dip beside the peak, farther from the background than ...
    z[0, 1202] = 0.9
    b = extreme_blocks(z, n, 1000)
    assert b.block == 5 and b.image.shape == (3, 960) and b.width == 2.5 and b.x0 == 0.5
    assert b.image.max() == 7.0 and b.image.min() == -3.0
    assert b.image[0, 2 * (1200 // 5) + 1] == 7.0 and b.image[0, 2 * (1200 // 5)] == -0.5
    assert b.image[2, 2 * (1799 // 5)] == -3.0
    # every k-th site (what max_sites_out keeps) misses both
    picked = z[:, np.unique(np.linspace(0, L - 1, 1000).round().astype(int))]
    assert picked.max() < 7.0 or picked.min() > -3.0
    assert "block of 5 sites" in b.note


def test_a_ragged_last_block_and_no_reduction():
    z = np.arange(10.0)[None, :]
    b = extreme_blocks(z, np.arange(1, 11), 6)  # blocks of 4: the last holds two sites
    assert b.block == 4 and b.image.shape == (1, 6)
    assert list(b.image[0]) == [0.0, 3.0, 4.0, 7.0, 8.0, 9.0]
    b = extreme_blocks(z, np.arange(1, 11), 10)
    assert b.block == 1 and b.note == "" and np.array_equal(b.image, z)


def test_bad_input_is_named():
    with pytest.raises(ParameterError, match="max_columns"):
        extreme_blocks(np.zeros((2, 3)), np.arange(3), 1)
    with pytest.raises(ParameterError, match="snapshots"):
        extreme_blocks(np.zeros(3), np.arange(3))
