"""Wave tracking in a simulated space-time strain field (paper §6, Figs. Riemann1, SWdyn).

Three stages:

1. **Detection** (:func:`scan_profile`) on full-resolution strain profiles w_n(t_k) in a late time
   window.  Each half of the chain is scanned from its end towards the origin of the initial
   disturbance.  Starting from the undisturbed plateau (the state *ahead*), the first site where
   |w − ahead| exceeds ``threshold`` starts a structure; following the profile monotonically away
   from the plateau either reaches a new flat plateau — a **front** (a ``"superkink"`` if the two
   states lie on opposite sides of w*, else ``"front"``) — or an extremum that falls back — a
   **pulse**.  A pulse followed within a few widths by another extremum of the same sign and at
   least half its amplitude is the leading edge of a dispersive shock wave (``"dsw_edge"``; the
   scan of that half stops there); otherwise it is a ``"solitary"`` wave, and the scan continues
   only if a plateau follows it.
2. **Velocity** of each structure.  A coarse velocity comes from a linear fit of its positions
   (parabolic peak / interpolated mid-level crossing) over the snapshots of the window.  It is
   refined with the passage times recorded by the integrator at every site (time extrema of
   w_n(t) for pulses, crossings of w* for superkinks, located with degree-7 Hermite interpolation
   inside the step): for a wave moving with constant velocity V these times are exactly
   t_n = t_0 + n / V, so a least-squares line through (n, t_n) over the sites passed in the late
   window gives V with no lattice-phase error.
3. **Error** of each velocity, measured, not assumed: ``velocity_error`` = the fit's standard
   error + the spread of V over other fit windows (:data:`WINDOWS`: a longer one starting half a
   window earlier, the window's later half, its earlier half) + the spread over the detection
   threshold (×½ and ×2, :data:`THRESHOLDS`; the wave matched by kind and position).  A steady
   wave (superkink, solitary wave) gives the same V in every window (spread ~1e-9); the leading
   edge of a dispersive shock is not steady: on the paper's Riemann run its V drifts by ~6e-4
   between windows, which the standard error of one fit (1e-5) does not show.  The state ahead
   (``background``) gets the same treatment: ``background_error`` is its spread over the window's
   snapshots and the thresholds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fpucore.simulate.result import TrackedWave

#: fit windows besides the tracking window [t_a, t_b] (D = t_b − t_a), as (start, end) in units of
#: D from t_a: one starting half a window earlier, the later half, the earlier half
WINDOWS = ((-0.5, 1.0), (0.5, 1.0), (0.0, 0.5))
#: detection thresholds besides the run's, as factors
THRESHOLDS = (0.5, 2.0)
#: a wave found at another threshold is the same wave if its final position is this close (sites)
SAME_WAVE_SITES = 3.0


@dataclass
class _Feature:
    kind: str
    sign: int  # pulses: +1 tensile / −1 compressive; fronts: sign(behind − ahead)
    pos: float  # chain index (0-based, fractional)
    ahead: float
    behind: float
    peak: float


def _parabolic_vertex(x: np.ndarray, k: int) -> float:
    if 0 < k < x.size - 1:
        a, b, c = x[k - 1], x[k], x[k + 1]
        den = a - 2 * b + c
        if den != 0:
            return k + 0.5 * (a - c) / den
    return float(k)


def scan_profile(
    w: np.ndarray,
    origin: float,
    side: int,
    threshold: float,
    w_star: float,
    plateau: int = 12,
    max_waves: int = 4,
) -> list[_Feature]:
    """Structures in one half of the profile ``w`` (L,), scanning from the end ``side`` (+1: the
    high-n end, −1: the low-n end) towards ``origin`` (chain index).  Returns features in scan order
    (outermost first), positions as chain indices."""
    L = w.size
    if side > 0:
        x = w[::-1]
        limit = int(L - 1 - np.ceil(origin))
    else:
        x = w
        limit = int(np.floor(origin))
    limit = max(0, min(limit, L - 1))

    def to_chain(i: float) -> float:
        return L - 1 - i if side > 0 else i

    feats: list[_Feature] = []
    if limit <= plateau:
        return feats
    ahead = float(np.median(x[:plateau]))
    i = 0
    nx = x.size
    while len(feats) < max_waves:
        dev = np.nonzero(np.abs(x[i:limit] - ahead) > threshold)[0]
        if dev.size == 0:
            break
        j = i + int(dev[0])
        sgn = 1 if x[j] > ahead else -1
        k = j
        while k + 1 < nx and sgn * (x[k + 1] - x[k]) > 0:
            k += 1
        seg = x[k : k + plateau]
        flat = seg.size == plateau and np.ptp(seg) < threshold
        if not flat and abs(x[k] - ahead) > threshold:
            # a front closely followed by the next structure (e.g. a superkink with its DSW a few
            # sites behind): the profile does not come back even half-way, and it rests at the
            # extreme level for a few sites
            m = k
            while m + 1 < nx and sgn * (x[m + 1] - x[m]) <= 0:
                m += 1
            q = m
            while q + 1 < nx and sgn * (x[q + 1] - x[q]) >= 0:
                q += 1
            shelf = np.abs(x[k : q + 1] - x[k]) < 0.5 * threshold
            ret = abs(x[m] - x[k])
            flat = ret < 0.5 * abs(x[k] - ahead) and shelf.sum() >= 3
            if flat:
                seg = x[k : q + 1][shelf]
        if flat and abs(x[k] - ahead) > threshold:
            behind = float(np.median(seg))
            mid = 0.5 * (ahead + behind)
            pos = float(k)
            for q in range(max(j - 1, 0), k):
                if (x[q] - mid) * (x[q + 1] - mid) <= 0 and x[q + 1] != x[q]:
                    pos = q + (mid - x[q]) / (x[q + 1] - x[q])
                    break
            kind = "superkink" if (ahead - w_star) * (behind - w_star) < 0 else "front"
            feats.append(_Feature(kind, sgn, to_chain(pos), ahead, behind, np.nan))
            ahead = behind
            i = k
            continue
        # pulse with crest at k
        peak = float(x[k])
        amp = peak - ahead
        pos = _parabolic_vertex(x, k)
        m = k
        while m + 1 < nx and sgn * (x[m + 1] - x[m]) < 0:
            m += 1
        q = m
        while q + 1 < nx and sgn * (x[q + 1] - x[q]) > 0:
            q += 1
        next_amp = sgn * (x[q] - ahead)
        width = max(k - j + 1, 2)
        behind_seg = x[m : m + plateau]
        behind = float(np.mean(behind_seg)) if behind_seg.size else np.nan
        if next_amp > 0.5 * abs(amp) and (q - k) <= max(6 * width, plateau):
            feats.append(_Feature("dsw_edge", sgn, to_chain(pos), ahead, behind, peak))
            break
        feats.append(_Feature("solitary", sgn, to_chain(pos), ahead, behind, peak))
        if behind_seg.size == plateau and np.max(np.abs(behind_seg - ahead)) < threshold:
            i = m
            continue
        break
    return feats


def _family(f: _Feature) -> tuple[str, int]:
    return ("front" if f.kind in ("superkink", "front") else "pulse", f.sign)


def fit_passage(n_sites, times):
    """Least-squares t = t0 + n·s with one outlier-rejection pass; returns (V, σ_V, count)."""
    n = np.asarray(n_sites, float)
    t = np.asarray(times, float)
    if n.size < 4:
        return np.nan, np.nan, int(n.size)
    for _ in range(2):
        A = np.vstack([n, np.ones_like(n)]).T
        coef, *_ = np.linalg.lstsq(A, t, rcond=None)
        res = t - A @ coef
        mad = np.median(np.abs(res - np.median(res))) + 1e-15
        keep = np.abs(res) <= 8 * 1.4826 * mad + 1e-12
        if keep.all() or keep.sum() < 4:
            break
        n, t = n[keep], t[keep]
    A = np.vstack([n, np.ones_like(n)]).T
    coef, *_ = np.linalg.lstsq(A, t, rcond=None)
    res = t - A @ coef
    dof = max(n.size - 2, 1)
    s2 = float(res @ res) / dof
    var_slope = s2 / max(float(((n - n.mean()) ** 2).sum()), 1e-300)
    slope = coef[0]
    V = 1.0 / slope
    return float(V), float(np.sqrt(var_slope) * V * V), int(n.size)


def track(
    law,
    t_trk: np.ndarray,
    w_trk: np.ndarray,
    origin: float,
    threshold: float,
    events,
    crossings,
    level: float,
    max_waves: int = 4,
) -> list[TrackedWave]:
    """Detect and measure the waves of a run.

    t_trk : (K,) times of the late-window snapshots; w_trk : (K, L) full-resolution strains;
    origin : chain index of the initial disturbance; events : (ev_t, ev_w, ev_s) per-site time
    extrema (L, nE) from the integrator; crossings : (cr_t, cr_s) per-site crossings of ``level``
    (= w*).  Returns the waves of both halves, outermost first (left half, then right half).
    """
    ev_t, ev_w, ev_s = events
    cr_t, cr_s = crossings
    good = np.all(np.isfinite(w_trk), axis=1)
    t_trk, w_trk = t_trk[good], w_trk[good]
    if t_trk.size < 3:
        return []
    w_star = float(law.w_star)
    L = w_trk.shape[1]
    passes = (ev_t, ev_w, ev_s, cr_t, cr_s, L)
    waves: list[TrackedWave] = []
    for side in (-1, 1):

        def scans_at(thr, side=side):
            return [scan_profile(w, origin, side, thr, w_star, max_waves=max_waves) for w in w_trk]

        scans = scans_at(threshold)
        other = [scans_at(k * threshold) for k in THRESHOLDS]
        for r, f in enumerate(scans[-1]):
            m = _measure(f, r, scans, t_trk, side, t_trk[0], t_trk[-1], passes)
            if m is None:
                continue  # not an outgoing wave
            V, dV, nfit, method, crest, aheads = m
            D = t_trk[-1] - t_trk[0]
            v_win = [_measure(f, r, scans, t_trk, side, t_trk[0] + a * D, t_trk[0] + b * D,
                              passes) for a, b in WINDOWS]  # fmt: skip
            win = max((abs(x[0] - V) for x in v_win if x is not None and np.isfinite(x[0])),
                      default=0.0)  # fmt: skip
            v_thr, b_thr = [], []
            for sc in other:
                k = _same_wave(f, sc[-1])
                x = None if k is None else _measure(sc[-1][k], k, sc, t_trk, side, t_trk[0],
                                                    t_trk[-1], passes)  # fmt: skip
                if x is not None and np.isfinite(x[0]):
                    v_thr.append(abs(x[0] - V))
                    b_thr.append(abs(sc[-1][k].ahead - f.ahead))
            thr_spread = max(v_thr) if v_thr else float("nan")
            dV_all = dV + win + (thr_spread if v_thr else 0.0)
            b_err = max([float(np.max(np.abs(aheads - f.ahead))), *b_thr])
            peak = f.peak
            if f.kind in ("superkink", "front"):
                amp = f.behind - f.ahead
            else:
                if np.isfinite(crest):  # time extrema at the sites: the crest, not a site sample
                    peak = crest
                amp = peak - f.ahead
            # ahead is on the outer side: left half → ahead is left state
            left, right = (f.ahead, f.behind) if side < 0 else (f.behind, f.ahead)
            waves.append(
                TrackedWave(
                    kind=f.kind,
                    velocity=float(V),
                    velocity_error=float(dV_all),
                    amplitude=float(amp),
                    left_state=float(left),
                    right_state=float(right),
                    background=float(f.ahead),
                    peak=float(peak),
                    position=float(f.pos) + 1.0,
                    n_fit=int(nfit),
                    method=method,
                    velocity_fit_error=float(dV),
                    velocity_window_spread=float(win),
                    velocity_threshold_spread=float(thr_spread),
                    background_error=float(b_err),
                )
            )
    return waves


def _same_wave(f: _Feature, final: list[_Feature]) -> int | None:
    """Index of the feature in ``final`` (a scan at another threshold) that is f: same family,
    final position within SAME_WAVE_SITES."""
    best = None
    for k, g in enumerate(final):
        d = abs(g.pos - f.pos)
        if _family(g) == _family(f) and d <= SAME_WAVE_SITES and (best is None or d < best[1]):
            best = (k, d)
    return None if best is None else best[0]


def _measure(f: _Feature, r: int, scans, t_trk, side: int, t_a: float, t_b: float, passes):
    """Velocity of the r-th feature f of the final scan, fitted over [t_a, t_b]: the coarse ray
    from its positions in the snapshots, refined by passage times (:func:`_refine`).  Returns
    (V, σ_V, count, method, crest, states ahead over the snapshots), or None if the wave is not
    outgoing."""
    ts, xs, aheads = [], [], []
    for tk, sc in zip(t_trk, scans):
        if len(sc) > r and _family(sc[r]) == _family(f):
            ts.append(tk)
            xs.append(sc[r].pos)
            aheads.append(sc[r].ahead)
    if len(ts) < 3:
        return None
    ts_a, xs_a = np.asarray(ts), np.asarray(xs)
    V0, x0 = np.polyfit(ts_a, xs_a, 1)
    if abs(V0) < 0.05 or np.sign(V0) != side:
        return None
    # the tracking window itself starts where the wave was first seen in it; other fit windows
    # start at their own t_a
    t0 = ts_a[0] if abs(t_a - t_trk[0]) <= 1e-12 * max(1.0, t_b) else max(t_a, 0.0)
    V, dV, nfit, method, crest = _refine(f, V0, x0, t0, t_b, *passes)
    if not np.isfinite(V):
        sel = (ts_a >= t_a - 1e-12) & (ts_a <= t_b + 1e-12)
        if sel.sum() < 3:
            return None
        tw, xw = ts_a[sel], xs_a[sel]
        V1, x1 = np.polyfit(tw, xw, 1)
        res = xw - (V1 * tw + x1)
        dof = max(tw.size - 2, 1)
        dV = float(np.sqrt((res @ res) / dof / (((tw - tw.mean()) ** 2).sum())))
        V, nfit, method = float(V1), int(tw.size), "snapshots"
    return V, dV, nfit, method, crest, np.asarray(aheads)


def _refine(f, V0, x0, t_a, t_b, ev_t, ev_w, ev_s, cr_t, cr_s, L):
    """Velocity from per-site passage times near the coarse ray x = x0 + V0 t, t ∈ [t_a, t_b].
    Returns (V, σ_V, count, method, crest) — crest: median strain at the matched time extrema
    (pulses; NaN otherwise)."""
    xa, xb = x0 + V0 * t_a, x0 + V0 * t_b
    lo, hi = sorted((xa, xb))
    # skip the last few sites (events there may still be unconfirmed)
    back = 4 * np.sign(V0)
    n_sites = np.arange(int(np.ceil(lo)), int(np.floor(hi)) + 1)
    n_sites = n_sites[(n_sites >= 0) & (n_sites < L)]
    if V0 > 0:
        n_sites = n_sites[n_sites <= hi - back]
    else:
        n_sites = n_sites[n_sites >= lo - back]
    if f.kind == "superkink":
        tt, ss, want = cr_t, cr_s, f.sign
    elif f.kind == "front":
        return np.nan, np.nan, 0, "", np.nan
    else:
        tt, ss, want = ev_t, ev_s, f.sign
    tol = 0.3 / abs(V0)
    # per site, the recorded time of the wanted sign nearest the coarse ray (all sites at once)
    rows = tt[n_sites]
    tp = (n_sites - x0) / V0
    with np.errstate(invalid="ignore"):
        d = np.where((ss[n_sites] == want) & np.isfinite(rows), np.abs(rows - tp[:, None]), np.inf)
    j = np.argmin(d, axis=1) if n_sites.size else np.zeros(0, dtype=np.int64)
    k = np.arange(n_sites.size)
    hit = d[k, j] < tol if n_sites.size else np.zeros(0, dtype=bool)
    ns, ts = n_sites[hit], rows[k[hit], j[hit]]
    vals = ev_w[n_sites[hit], j[hit]] if f.kind != "superkink" else np.zeros(0)
    if len(ns) < 8:
        return np.nan, np.nan, len(ns), "", np.nan
    V, dV, cnt = fit_passage(ns, ts)
    crest = float(np.median(vals)) if vals.size else np.nan
    return V, dV, cnt, "passage_times", crest
