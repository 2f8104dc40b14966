"""Time in stationary windows: one measure, light to import (no NumPy)."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = ["covered_time_s"]


def covered_time_s(spans: Iterable[tuple[Any, float, float]], interval_s: float) -> float:
    """Return the time the union of windows covers, s: every sample counted once.

    The one measure of "time in windows" (the verdict's data for tau, the
    result's ``windows.covered_s``, a campaign day's ``covered_s``): each
    window ``(arc, t_start, t_stop)`` covers its epochs, ``t_stop - t_start +
    interval_s``; overlapping windows of one arc are merged.

    Parameters
    ----------
    spans : iterable of (arc, float, float)
        Arc and first and last epoch of each window, GPS s.
    interval_s : float
        Sampling interval, s.

    Returns
    -------
    float
    """
    total, cur = 0.0, None
    for arc, t0, t1 in sorted(spans):
        t1 = t1 + interval_s
        if cur is None or arc != cur[0] or t0 > cur[2]:
            if cur is not None:
                total += cur[2] - cur[1]
            cur = [arc, t0, t1]
        else:
            cur[2] = max(cur[2], t1)
    if cur is not None:
        total += cur[2] - cur[1]
    return total
