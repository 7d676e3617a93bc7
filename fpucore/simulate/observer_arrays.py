"""The observer's arrays of a chain simulation (:class:`fpucore.simulate.layout.Observer`), in
Python around the Numba observer (:mod:`fpucore.simulate.observer`): allocated before a run
(one that records events, crossings and probes, or one that records nothing, for the
step-doubling companion run), and the pending extrema confirmed at its end."""

from __future__ import annotations

import numpy as np

from fpucore.simulate.layout import Observer


def finalize_events(y, L, thr, obs: Observer) -> None:
    """Confirm the pending extremum candidate of every site if the strain has since moved away
    from it by more than the prominence threshold (otherwise a wave that passed a site shortly
    before the end, with no later opposite extremum, would be missed)."""
    K = obs.ev_t.shape[1]
    zz, ev_n = obs.zz, obs.ev_n
    for n in np.nonzero(obs.zdir)[0]:
        if ev_n[n] < K and abs(zz[0, n] - y[n]) > thr:
            k = ev_n[n]
            obs.ev_t[n, k], obs.ev_w[n, k], obs.ev_s[n, k] = obs.zt[n], zz[0, n], obs.zdir[n]
            ev_n[n] += 1


def make_observer(
    L: int, w0: np.ndarray, thr: float, level: float, n_events: int, probe_idx, probe_t
) -> Observer:
    """An observer of L sites recording extrema of prominence ``thr``, crossings of ``level``
    (at most ``n_events`` per site) and the strain at the sites ``probe_idx`` on the grid
    ``probe_t`` (its first column, t = 0, from w0)."""
    zz = np.empty((3, L))  # per site: extremum candidate, running min, running max
    zz[:] = w0
    probe_out = np.full((probe_idx.size, probe_t.size), np.nan)
    probe_out[:, 0] = w0[probe_idx]
    return Observer(
        thr,
        level,
        zz,
        np.zeros(L),
        np.zeros(L, np.int8),
        np.full((L, n_events), np.nan),
        np.full((L, n_events), np.nan),
        np.zeros((L, n_events), np.int8),
        np.zeros(L, np.int64),
        np.full((L, 4), np.nan),
        np.zeros((L, 4), np.int8),
        np.zeros(L, np.int64),
        probe_idx,
        probe_t,
        probe_out,
        np.ones(1, np.int64),
        np.zeros(8),
    )


def null_observer(L: int) -> Observer:
    """An observer that records nothing (infinite prominence, NaN level, no probes)."""
    e = np.zeros((L, 1))
    ei = np.zeros((L, 1), np.int8)
    en = np.zeros(L, np.int64)
    zz = np.zeros((3, L))
    zz[1] = -np.inf
    zz[2] = np.inf
    return Observer(
        np.inf,
        np.nan,
        zz,
        np.zeros(L),
        np.zeros(L, np.int8),
        e,
        e,
        ei,
        en,
        e,
        ei,
        en,
        np.zeros(0, np.int64),
        np.zeros(0),
        np.zeros((0, 0)),
        np.zeros(1, np.int64),
        np.zeros(8),
    )
