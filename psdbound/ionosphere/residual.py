"""Time-domain cutoff criterion: the ionosphere the fit's high-pass leaves, against multipath.

The question a cutoff answers is how much ionospheric delay is left in the
isolated multipath series after the high-pass, compared with the multipath
the bound describes (thesis section 2.6.2: the residual "must be negligible
with regard to multipath"). The ``"residual"`` criterion answers it
directly, in the time domain, with exactly the filter the fit applies:

1. the simulated one-day series of a satellite is split into its arcs
   (:func:`split_arcs`); each arc's mean is removed (the fit removes the
   ambiguity with the arc mean), and the arc is filtered with
   :class:`psdbound.isolation.HighPass` (default 4th-order Butterworth,
   zero-phase ``sosfiltfilt``, odd padding, ``1/f_c`` trimmed at each end);
   arcs shorter than :data:`MIN_KEPT_S` after trimming are dropped, as
   :func:`psdbound.isolation.isolate_dual_frequency` drops them;
2. the residual is the RMS over every kept sample of the day, times
   ``scale`` (:data:`psdbound.isolation.DF_SCALING` = 1/sqrt(2) for a
   dual-frequency difference, the fit's per-carrier scaling; 1 for a single
   carrier, which is then conservative by 6.8 dB for the L1-L2 fit);
3. ``f_c`` is the lowest frequency above which the residual stays at or
   below the threshold ``sigma_MP 10^(-margin_dB / 20)``; default
   ``sigma_MP`` = :data:`DEFAULT_MP_SIGMA_M` (1 mm) and ``margin_dB`` =
   :data:`DEFAULT_MARGIN_DB` (40 dB, the thesis's factor 100 in amplitude):
   0.01 mm, 0.01 % of the multipath variance.

The search (:func:`residual_cutoff`) scans a log-spaced grid of cutoffs
from just below Nyquist downwards, so "stays below" is checked at every grid
point above the answer, then refines the crossing by bisection in
``log f``. A cutoff at which every arc is trimmed away leaves nothing of the
ionosphere (residual 0), as it leaves nothing of the fit's data.

Why not a periodogram criterion: satellite passes are windows a few hours
long, and the spectrum of a windowed smooth signal leaks at ``f^-2`` from
the arc edges (Harris 1978; Percival & Walden 1993, section 6.4), so the
40 dB point of an untapered Lomb-Scargle measures the passes, not the
ionosphere (docs/method/cutoff.rst gives the numbers). A time-domain residual has no
such floor: what the fit's filter leaves is what the criterion measures,
edge transients included.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.ionosphere.names import (
    F_MIN_HZ,
    MIN_KEPT_S,
)
from psdbound.isolation import HighPass

__all__ = [
    "MIN_KEPT_S",
    "F_MIN_HZ",
    "ResidualCutoff",
    "residual_cutoff",
    "residual_cutoffs",
    "residual_rms",
    "residual_threshold_m",
    "highpass_arcs",
    "split_arcs",
]


def residual_threshold_m(mp_sigma_m: float, margin_db: float) -> float:
    """Return the allowed residual ionosphere RMS ``mp_sigma_m * 10^(-margin_db / 20)``, m.

    Parameters
    ----------
    mp_sigma_m : float
        Reference multipath sigma, m (> 0).
    margin_db : float
        How far below it the residual must be, dB (>= 0).

    Returns
    -------
    float
        Threshold, m.
    """
    if not mp_sigma_m > 0 or not margin_db >= 0:
        raise InputError(
            f"need mp_sigma_m > 0 and margin_db >= 0, got {mp_sigma_m} m and {margin_db} dB"
        )
    return float(mp_sigma_m * 10.0 ** (-margin_db / 20.0))


def split_arcs(t_s: ArrayLike, y_m: ArrayLike, dt_s: float) -> list[NDArray[np.float64]]:
    """Split a gappy regularly sampled series into its arcs (contiguous runs).

    Parameters
    ----------
    t_s : array_like of float
        Sample times, s, increasing, on a ``dt_s`` grid.
    y_m : array_like of float
        Values, m.
    dt_s : float
        Sampling interval, s; a step above 1.5 ``dt_s`` starts a new arc.

    Returns
    -------
    list of ndarray of float64
        The values of each arc, in time order.
    """
    t = np.asarray(t_s, dtype=np.float64)
    y = np.asarray(y_m, dtype=np.float64)
    if t.shape != y.shape or t.ndim != 1:
        raise InputError(f"t_s and y_m must be 1-D of equal length, got {t.shape}, {y.shape}")
    if t.size == 0:
        return []
    breaks = np.flatnonzero(np.diff(t) > 1.5 * dt_s) + 1
    return np.split(y, breaks)


def highpass_arcs(
    arcs: list[NDArray[np.float64]],
    dt_s: float,
    f_c_hz: float,
    *,
    highpass: HighPass | None = None,
) -> list[tuple[NDArray[np.float64], NDArray[np.bool_]]]:
    """Apply the fit's high-pass to each arc with :meth:`~psdbound.isolation.HighPass.apply`.

    Each arc is filtered as the isolation filters it (odd reflection over
    ``min(n - 1, ceil(3 / (f_c dt)))`` samples, forward-backward,
    ``ceil(1 / (f_c dt))`` samples trimmed at each end for ``edge="trim"``);
    the design and its initial state are computed once per options,
    sampling and cutoff.

    Parameters
    ----------
    arcs : list of ndarray of float64
        Evenly sampled arcs.
    dt_s : float
        Sampling interval, s.
    f_c_hz : float
        Cutoff, Hz.
    highpass : HighPass, optional
        The filter (default design).

    Returns
    -------
    list of (ndarray of float64, ndarray of bool)
        Filtered arc and the samples kept, per arc.
    """
    hp = HighPass() if highpass is None else highpass
    return [hp.apply(np.asarray(x, dtype=np.float64), dt_s, f_c_hz) for x in arcs]


def _zero_phase_sumsq(
    arcs: list[NDArray[np.float64]],
    dt_s: float,
    f_c_hz: float,
    hp: HighPass,
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """Sum of squares and count of the kept samples of each filtered arc, all arcs at once.

    The arcs are odd-extended as :meth:`HighPass.apply` extends them,
    stacked left-aligned in one zero-filled matrix and run through
    ``sosfilt`` forwards, then (each row reversed over its own length)
    backwards: row by row the same arithmetic as ``sosfiltfilt``, in two
    calls instead of two per arc. The kept samples (``ceil(1 / (f_c dt))``
    trimmed at each end) occupy the same index range in the reversed row.
    """
    n = np.array([x.size for x in arcs], dtype=np.int64)
    k_trim = int(np.ceil(1.0 / (f_c_hz * dt_s))) if hp.edge == "trim" else 0
    if hp.kind == "fir":
        ss = np.zeros(n.size)
        for i, (y, keep) in enumerate(highpass_arcs(arcs, dt_s, f_c_hz, highpass=hp)):
            ss[i] = float(np.sum(y[keep] ** 2))
        return ss, np.maximum(n - 2 * k_trim, 0)
    from scipy.signal import sosfilt

    sos = hp.sos(dt_s, f_c_hz)
    zi = hp.initial_state(dt_s, f_c_hz)[:, None, :]
    pad = np.minimum(n - 1, int(np.ceil(3.0 / (f_c_hz * dt_s))))
    length = n + 2 * pad
    width = int(length.max())
    x = np.zeros((n.size, width))
    for i, (a, p) in enumerate(zip(arcs, pad, strict=True)):
        if p > 0:
            a = np.concatenate([2 * a[0] - a[p:0:-1], a, 2 * a[-1] - a[-2 : -p - 2 : -1]])
        x[i, : a.size] = a
    rows = np.arange(n.size)[:, None]
    cols = np.arange(width)[None, :]
    y, _ = sosfilt(sos, x, axis=1, zi=zi * x[:, 0][None, :, None])
    back = length[:, None] - 1 - cols
    r = np.where(back >= 0, y[rows, np.maximum(back, 0)], 0.0)
    r, _ = sosfilt(sos, r, axis=1, zi=zi * r[:, 0][None, :, None])
    lo = (pad + k_trim)[:, None]
    hi = (pad + n - k_trim)[:, None]
    kept = (cols >= lo) & (cols < hi)
    return np.sum(np.where(kept, r * r, 0.0), axis=1), np.maximum(n - 2 * k_trim, 0)


def _usable(
    arcs: list[NDArray[np.float64]], dt_s: float, f_c_hz: float, hp: HighPass, min_kept_s: float
) -> list[bool]:
    """Which arcs keep at least ``min_kept_s`` after trimming (the fit drops the others)."""
    k = int(np.ceil(1.0 / (f_c_hz * dt_s))) if hp.edge == "trim" else 0
    return [a.size - 2 * k >= 2 and (a.size - 2 * k - 1) * dt_s >= min_kept_s for a in arcs]


def residual_rms(
    arcs: list[NDArray[np.float64]],
    dt_s: float,
    f_c_hz: float,
    *,
    highpass: HighPass | None = None,
    min_kept_s: float = MIN_KEPT_S,
) -> tuple[float, int]:
    """RMS of what the fit's high-pass leaves of the arcs (mean removed per arc).

    Parameters
    ----------
    arcs : list of ndarray of float64
        Evenly sampled arcs, m (e.g. from :func:`split_arcs`).
    dt_s : float
        Sampling interval, s.
    f_c_hz : float
        Cutoff, Hz (below Nyquist).
    highpass : HighPass, optional
        The filter; default the fit's default :class:`~psdbound.isolation.HighPass`.
    min_kept_s : float, default 600
        Arcs whose kept span is shorter are dropped, as the fit drops them.

    Returns
    -------
    rms_m : float
        RMS over the kept samples of all arcs, m (0 when nothing is kept).
    n_kept : int
        Samples kept.
    """
    hp = HighPass() if highpass is None else highpass
    hp.check_cutoff(f_c_hz, dt_s)
    use = [
        a - a.mean()
        for a, ok in zip(arcs, _usable(arcs, dt_s, f_c_hz, hp, min_kept_s), strict=True)
        if ok
    ]
    if not use:
        return 0.0, 0
    ss, cnt = _zero_phase_sumsq(use, dt_s, f_c_hz, hp)
    n = int(cnt.sum())
    return (float(np.sqrt(ss.sum() / n)) if n else 0.0), n


@dataclass(frozen=True, eq=False)
class ResidualCutoff:
    """Cutoff of one series by the residual criterion, and how it was found.

    Attributes
    ----------
    f_c_hz : float
        Cutoff, Hz (at the first threshold when several were given).
    reached : bool
        False if the residual exceeds the threshold even at the top of the
        search (just below Nyquist; ``f_c_hz`` is then the top).
    floor : bool
        True if the residual never exceeds the threshold down to the bottom
        of the search (``f_c_hz`` is then the bottom, :data:`F_MIN_HZ`).
    threshold_m : float
        Allowed residual RMS in the fit's series, m.
    scale : float
        Factor from the simulated delay to the fit's series.
    n_samples, n_arcs : int
        Samples and arcs of the series.
    variance_m2 : float
        Variance of the (unscaled) series, m^2.
    curve_f_hz, curve_rms_m : ndarray of float64
        The scanned cutoffs (decreasing) and their scaled residuals, m.
    f_c_by_threshold : dict
        Cutoff for every threshold given (m -> Hz).
    """

    f_c_hz: float
    reached: bool
    floor: bool
    threshold_m: float
    scale: float
    n_samples: int
    n_arcs: int
    variance_m2: float
    curve_f_hz: NDArray[np.float64]
    curve_rms_m: NDArray[np.float64]
    f_c_by_threshold: dict[float, float] = field(default_factory=dict)

    @property
    def tau_c_min(self) -> float:
        """Time constant ``1 / f_c``, minutes."""
        return 1.0 / self.f_c_hz / 60.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready scalar summary (no arrays)."""
        return {
            "f_c_hz": self.f_c_hz,
            "tau_c_min": self.tau_c_min,
            "reached": self.reached,
            "floor": self.floor,
            "threshold_m": self.threshold_m,
            "scale": self.scale,
            "n_samples": self.n_samples,
            "n_arcs": self.n_arcs,
            "variance_m2": self.variance_m2,
            "f_c_by_threshold": [[k, v] for k, v in self.f_c_by_threshold.items()],
        }


def _crossing(f_hi: float, r_hi: float, f_lo: float, r_lo: float, thr: float) -> float:
    """Log-log interpolated cutoff where the residual passes ``thr`` (r_lo > thr >= r_hi)."""
    if r_hi <= 0.0:
        return f_hi
    frac = (np.log(r_lo) - np.log(thr)) / (np.log(r_lo) - np.log(r_hi))
    return float(np.exp(np.log(f_lo) + frac * (np.log(f_hi) - np.log(f_lo))))


def _search_grid(
    thr: list[float],
    scale: float,
    dt_s: float,
    nyquist_fraction: float,
    f_min_hz: float,
    points_per_decade: int,
) -> NDArray[np.float64]:
    """Check the thresholds and search settings; return the cutoff grid, Hz, descending."""
    if not thr or min(thr) <= 0 or not scale > 0:
        raise InputError(f"need thresholds > 0 and scale > 0, got {thr}, {scale}")
    if points_per_decade < 1:
        raise InputError(f"points_per_decade = {points_per_decade} must be >= 1")
    f_top = nyquist_fraction * 0.5 / dt_s
    if not 0 < f_min_hz < f_top:
        raise InputError(f"need 0 < f_min_hz < {f_top:g} Hz, got {f_min_hz}")
    return np.geomspace(
        f_top, f_min_hz, int(np.ceil(np.log10(f_top / f_min_hz) * points_per_decade)) + 1
    )


def _sums_at(
    arcs: list[list[NDArray[np.float64]]],
    idx: list[int],
    f: float,
    dt_s: float,
    hp: HighPass,
    min_kept_s: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return the high-passed sum of squares (m^2) and samples of the series ``idx`` at ``f``."""
    owner, batch = [], []
    for i in idx:
        for a, ok in zip(arcs[i], _usable(arcs[i], dt_s, f, hp, min_kept_s), strict=True):
            if ok:
                owner.append(i)
                batch.append(a)
    ss = np.zeros(len(arcs))
    cnt = np.zeros(len(arcs))
    if batch:
        s_arc, c_arc = _zero_phase_sumsq(batch, dt_s, f, hp)
        np.add.at(ss, owner, s_arc)
        np.add.at(cnt, owner, c_arc)
    return ss, cnt


def _scan(
    arcs: list[list[NDArray[np.float64]]],
    grid: NDArray[np.float64],
    dt_s: float,
    hp: HighPass,
    min_kept_s: float,
    scale: float,
    top: float,
) -> list[list[float]]:
    """Return each series' residual RMS (m) down the grid, until it first exceeds ``top``."""
    curves: list[list[float]] = [[] for _ in arcs]
    active = [True] * len(arcs)
    for f in grid:
        idx = [i for i in range(len(arcs)) if active[i]]
        if not idx:
            break
        ss, cnt = _sums_at(arcs, idx, float(f), dt_s, hp, min_kept_s)
        for i in idx:
            r = scale * float(np.sqrt(ss[i] / cnt[i])) if cnt[i] > 0 else 0.0
            curves[i].append(r)
            if r > top:
                active[i] = False
    return curves


def _by_threshold(
    r: NDArray[np.float64], f: NDArray[np.float64], grid: NDArray[np.float64], thr: list[float]
) -> dict[float, float]:
    """Return the cutoff (Hz) per threshold, interpolated where the curve ``r`` first exceeds it."""
    by_thr = {}
    for th in thr:
        above = np.flatnonzero(r > th)
        if above.size == 0:
            by_thr[th] = float(grid[-1])
        elif above[0] == 0:
            by_thr[th] = float(grid[0])
        else:
            j = int(above[0])
            by_thr[th] = _crossing(float(f[j - 1]), float(r[j - 1]), float(f[j]), float(r[j]), th)
    return by_thr


def residual_cutoffs(
    series: list[tuple[ArrayLike, ArrayLike]],
    *,
    dt_s: float,
    thresholds_m: ArrayLike,
    scale: float = 1.0,
    highpass: HighPass | None = None,
    min_kept_s: float = MIN_KEPT_S,
    nyquist_fraction: float = 0.5,
    f_min_hz: float = F_MIN_HZ,
    points_per_decade: int = 16,
) -> list[ResidualCutoff]:
    """Lowest cutoff above which the fit's high-pass leaves at most a threshold, per series.

    Every series is scanned on one log-spaced grid of cutoffs, from
    ``nyquist_fraction`` of Nyquist downwards, in lock-step (one filter
    design and one batched filtering per grid cutoff, :func:`residual_rms`'s
    arithmetic); a series stops when its residual first exceeds the largest
    threshold. For each threshold the cutoff is the log-log interpolation
    of the residual between the last grid cutoff at or below the threshold
    and the first above it, so "stays below" holds at every grid cutoff
    above the answer.

    Parameters
    ----------
    series : list of (array_like, array_like)
        Per satellite, sample times (s, on a ``dt_s`` grid, gaps between
        arcs) and simulated delays (m).
    dt_s : float
        Sampling interval, s.
    thresholds_m : array_like of float
        Allowed residual RMS in the fit's series, m (see
        :func:`residual_threshold_m`); the first is the main one.
    scale : float, default 1
        Factor from the simulated delay to the fit's series
        (:data:`psdbound.isolation.DF_SCALING` for a dual-frequency difference).
    highpass : HighPass, optional
        The fit's filter (default design).
    min_kept_s : float, default 600
        Arcs shorter than this after trimming are dropped.
    nyquist_fraction : float, default 0.5
        Top of the search as a fraction of Nyquist: a cutoff above half of
        Nyquist leaves too little band for a bound anyway (the verdict wants
        a factor 4), and near Nyquist the edge transients of the filter,
        trimmed over only ``1/f_c``, dominate the residual.
    f_min_hz : float, default 1e-4
        Bottom of the search, Hz.
    points_per_decade : int, default 16
        Density of the scan grid.

    Returns
    -------
    list of ResidualCutoff
        One per series, in order.

    Raises
    ------
    InputError
        For a non-positive threshold or scale, or bad search settings.
    """
    thr = [float(v) for v in np.atleast_1d(np.asarray(thresholds_m, dtype=np.float64))]
    grid = _search_grid(thr, scale, dt_s, nyquist_fraction, f_min_hz, points_per_decade)
    hp = HighPass() if highpass is None else highpass
    ys = [np.asarray(y, dtype=np.float64) for _, y in series]
    arcs = [
        [a - a.mean() for a in split_arcs(t, y, dt_s)] for (t, _), y in zip(series, ys, strict=True)
    ]
    curves = _scan(arcs, grid, dt_s, hp, min_kept_s, scale, max(thr))
    out = []
    for i, y in enumerate(ys):
        r = np.asarray(curves[i])
        f = grid[: r.size]
        by_thr = _by_threshold(r, f, grid, thr)
        first = np.flatnonzero(r > thr[0])
        out.append(
            ResidualCutoff(
                f_c_hz=by_thr[thr[0]],
                reached=not (first.size and first[0] == 0),
                floor=first.size == 0,
                threshold_m=thr[0],
                scale=float(scale),
                n_samples=int(y.size),
                n_arcs=len(arcs[i]),
                variance_m2=float(np.var(y)) if y.size else 0.0,
                curve_f_hz=f,
                curve_rms_m=r,
                f_c_by_threshold=by_thr,
            )
        )
    return out


def residual_cutoff(
    t_s: ArrayLike,
    y_m: ArrayLike,
    *,
    dt_s: float,
    threshold_m: float,
    **options: Any,
) -> ResidualCutoff:
    """Residual-criterion cutoff of one series (see :func:`residual_cutoffs`).

    Parameters
    ----------
    t_s : array_like of float
        Sample times, s.
    y_m : array_like of float
        Simulated delay, m.
    dt_s : float
        Sampling interval, s.
    threshold_m : float
        Allowed residual RMS in the fit's series, m.
    **options
        ``scale``, ``highpass``, ``min_kept_s``, ``nyquist_fraction``,
        ``f_min_hz``, ``points_per_decade`` of :func:`residual_cutoffs`.

    Returns
    -------
    ResidualCutoff
    """
    return residual_cutoffs([(t_s, y_m)], dt_s=dt_s, thresholds_m=[threshold_m], **options)[0]
