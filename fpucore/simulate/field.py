"""A space–time strain field reduced for drawing without losing its extremes.

A plot a few hundred pixels wide cannot show every site of a long chain; picking every k-th
site (what ``max_sites_out`` does to the stored field) misses the peaks narrower than k sites
(the paper's Gaussian data, eq. GaussIC, are 1–2 sites wide: Fig. SWdyn (a) drawn at w ≈ 4.6
instead of 7).  :func:`extreme_blocks` instead groups consecutive sites into blocks and draws
each block, at each time, as two half-width columns: its minimum, then its maximum.  Every peak
and every dip of the data is in the image, and the image's extremes are the field's (a block's
value closest to a background would lose a peak beside a dip: the Gaussian's tails dip below
w_B right next to its crest).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fpucore.errors import ParameterError

__all__ = ["Blocks", "extreme_blocks"]


@dataclass(frozen=True)
class Blocks:
    """image : (n_t, n_columns) the drawn field — unreduced, or for each block of sites its
    minimum then its maximum (two columns per block, each half a block wide); x0 : the left
    edge of the first column (site number − ½); width : the columns' width in sites; block :
    sites per block (1: no reduction); note : the reduction in words ("" when there is none)."""

    image: np.ndarray
    x0: float
    width: float
    block: int
    note: str


def extreme_blocks(snapshots: ArrayLike, sites: ArrayLike, max_columns: int = 1000) -> Blocks:
    """Reduce ``snapshots`` (n_t, n_sites) at the 1-based, equally spaced ``sites`` (n_sites,)
    to at most ``max_columns`` columns: if n_sites > max_columns, blocks of
    ⌈n_sites / (max_columns // 2)⌉ consecutive sites, each drawn as its minimum and its maximum
    at each time (fields: :class:`Blocks`).  The image's maximum and minimum are the field's.

    Parameters
    ----------
    snapshots : array_like, shape (n_t, n_sites)
        Strain field w at n_t times.
    sites : array_like, shape (n_sites,)
        1-based, equally spaced site numbers of the columns.
    max_columns : int
        Largest number of columns of the image, >= 2.

    Returns
    -------
    Blocks
        ``image`` of shape (n_t, n_columns), n_columns <= max_columns, with its placement in
        sites (x0, width) and the block size.

    Raises
    ------
    ParameterError
        When ``snapshots`` is not 2-D with ``sites`` of shape (n_sites,), n_sites >= 1, or
        ``max_columns`` is not an integer >= 2.
    """
    z = np.asarray(snapshots, dtype=float)
    n = np.asarray(sites, dtype=float)
    if z.ndim != 2 or n.shape != (z.shape[1],) or n.size == 0:
        raise ParameterError("snapshots", z.shape, "(n_t, n_sites ≥ 1) with sites (n_sites,)")
    if isinstance(max_columns, bool) or int(max_columns) != max_columns or max_columns < 2:
        raise ParameterError("max_columns", max_columns, "an integer >= 2")
    ns = z.shape[1]
    dn = float(n[1] - n[0]) if ns > 1 else 1.0
    x0 = float(n[0]) - 0.5 * dn
    if ns <= max_columns:
        return Blocks(z, x0, dn, 1, "")
    k = math.ceil(ns / (int(max_columns) // 2))
    nb = math.ceil(ns / k)
    pad = nb * k - ns
    # pad the last block with copies of its last column (they change neither extreme)
    zp = np.concatenate([z, np.repeat(z[:, -1:], pad, axis=1)], axis=1) if pad else z
    zb = zp.reshape(z.shape[0], nb, k)
    image = np.empty((z.shape[0], 2 * nb))
    image[:, 0::2] = zb.min(axis=2)
    image[:, 1::2] = zb.max(axis=2)
    note = (
        f"each block of {k} sites is drawn as two half-columns, its minimum and its maximum "
        f"(not every {k}th site)"
    )
    return Blocks(image, x0, 0.5 * k * dn, k, note)
