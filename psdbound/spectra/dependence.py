"""Windows that are not independent: clusters and their correlation.

The pooled limits add the windows' degrees of freedom; that needs windows
whose errors are independent. Two cases in GNSS data are not:

* **dual-antenna double differences** share the reference satellite: windows
  of several satellites at the same time, differenced against one reference,
  all carry its multipath (:func:`reference_clusters`);
* **consecutive days of one station** repeat the multipath of a satellite
  one orbit repeat later (a sidereal day for the ground track, to within a
  few minutes), so a window on day 2 is largely a copy of one on day 1
  (:func:`repeat_clusters`).

Each cluster's windows then count as ``m / (1 + (m - 1) rho)`` windows
(Kish's design effect, :func:`psdbound.spectra.limits.design_effect_dof`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from psdbound.constants import SIDEREAL_DAY_S

__all__ = ["cluster_labels", "overlap_correlation", "reference_clusters", "repeat_clusters"]


def cluster_labels(n: int, pairs: Sequence[tuple[int, int]]) -> NDArray[np.int64]:
    """Label the connected components of ``n`` items linked by ``pairs`` (0, 1, ...)."""
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in pairs:
        parent[root(a)] = root(b)
    roots = [root(i) for i in range(n)]
    _, labels = np.unique(roots, return_inverse=True)
    return labels.astype(np.int64)


def _reference(sats: str) -> str | None:
    parts = str(sats).split("-")
    return parts[-1] if len(parts) == 2 else None


def reference_clusters(
    sats: Sequence[str], t_start_s: NDArray[np.float64], t_stop_s: NDArray[np.float64]
) -> NDArray[np.int64] | None:
    """Cluster double-difference windows that share a reference satellite in time.

    Parameters
    ----------
    sats : sequence of str
        Each window's pair, ``"G03-G06"`` (satellite, reference).
    t_start_s, t_stop_s : ndarray
        Each window's first and last epoch, seconds.

    Returns
    -------
    ndarray of int or None
        Cluster labels (windows linked when they share the reference and
        overlap in time); None when no window is a difference.
    """
    refs = [_reference(s) for s in sats]
    if all(r is None for r in refs):
        return None
    t0, t1 = np.asarray(t_start_s, dtype=float), np.asarray(t_stop_s, dtype=float)
    pairs = [
        (i, j)
        for i in range(len(refs))
        for j in range(i + 1, len(refs))
        if refs[i] is not None and refs[i] == refs[j] and t0[i] <= t1[j] and t0[j] <= t1[i]
    ]
    return cluster_labels(len(refs), pairs)


def repeat_clusters(
    sats: Sequence[str],
    t_start_s: NDArray[np.float64],
    duration_s: NDArray[np.float64],
    *,
    period_s: float = SIDEREAL_DAY_S,
) -> NDArray[np.int64]:
    """Cluster windows of one satellite that repeat a whole number of periods apart.

    Parameters
    ----------
    sats : sequence of str
        Each window's satellite (or pair).
    t_start_s : ndarray
        Each window's first epoch, seconds (a common time scale).
    duration_s : ndarray
        Each window's length, seconds.
    period_s : float, default the sidereal day
        Repeat period of the geometry, seconds.

    Returns
    -------
    ndarray of int
        Labels: windows of the same satellite whose start times, reduced by
        the nearest whole number (>= 1) of periods, lie within the shorter
        window's length of each other share a label.
    """
    t0, dur = np.asarray(t_start_s, dtype=float), np.asarray(duration_s, dtype=float)
    pairs = []
    for i in range(len(sats)):
        for j in range(i + 1, len(sats)):
            if sats[i] != sats[j]:
                continue
            lag = abs(t0[j] - t0[i])
            k = round(lag / period_s)
            if k >= 1 and abs(lag - k * period_s) < min(dur[i], dur[j]):
                pairs.append((i, j))
    return cluster_labels(len(sats), pairs)


def overlap_correlation(
    series: Sequence[NDArray[np.float64]],
    t_start_s: NDArray[np.float64],
    dt_s: float,
    labels: NDArray[np.int64],
) -> tuple[float, int]:
    """Median correlation of the overlapping parts of windows in one cluster.

    The correlation of two series is an upper bound on that of their PSD
    estimates (for Gaussian series the latter is the squared coherence), so
    using it as the intra-cluster correlation is conservative.

    Parameters
    ----------
    series : sequence of ndarray
        Each window's samples (even sampling, no gaps).
    t_start_s : ndarray
        Each window's first epoch, seconds.
    dt_s : float
        Sampling interval, seconds.
    labels : ndarray of int
        Cluster labels.

    Returns
    -------
    rho : float
        Median over overlapping pairs (at least 32 common samples) of the
        sample correlation, clipped to [0, 1]; 0 without such pairs.
    n_pairs : int
        Pairs used.
    """
    t0 = np.asarray(t_start_s, dtype=float)
    values = []
    for c in np.unique(labels):
        idx = np.flatnonzero(labels == c)
        for a_i, i in enumerate(idx):
            for j in idx[a_i + 1 :]:
                off = int(round((t0[j] - t0[i]) / dt_s))
                a, b = (series[i], series[j]) if off >= 0 else (series[j], series[i])
                off = abs(off)
                n = min(a.size - off, b.size)
                if n >= 32:
                    values.append(float(np.corrcoef(a[off : off + n], b[:n])[0, 1]))
    if not values:
        return 0.0, 0
    return float(np.clip(np.median(values), 0.0, 1.0)), len(values)
