"""Stationarity test of a window: Levene on 4 parts, then two-sample K-S on 2 halves.

Following the thesis (section 3.2): the Levene test (equality of variances)
runs on the window split into four equal consecutive parts; only if it
passes does the two-sample Kolmogorov-Smirnov test (same distribution) run
on the two halves. The window is stationary when both p-values exceed the
significance level ``alpha``.

Both tests assume independent samples; time-correlated multipath makes them
reject more often than ``alpha`` at a given window length (a conservative
direction: windows get shorter, never longer).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy import stats

__all__ = ["StationarityTest", "test_stationarity"]


@dataclass(frozen=True)
class StationarityTest:
    """Outcome of :func:`test_stationarity`.

    Attributes
    ----------
    stationary : bool
        Both tests passed.
    levene_p : float
        p-value of the Levene test on four parts.
    ks_p : float or None
        p-value of the two-sample K-S test on two halves (None when the
        Levene test already failed).
    alpha : float
        Significance level used.
    """

    stationary: bool
    levene_p: float
    ks_p: float | None
    alpha: float


def test_stationarity(
    x: ArrayLike, *, alpha: float = 0.05, center: str = "mean"
) -> StationarityTest:
    """Test one window for stationarity (Levene on 4 parts, then K-S on 2).

    Parameters
    ----------
    x : array_like
        The window's samples (mapped multipath, metres).
    alpha : float, default 0.05
        Significance level of both tests.
    center : {"mean", "median", "trimmed"}, default "mean"
        Centre of the Levene statistic; "mean" is Levene's original test,
        "median" the Brown-Forsythe variant.

    Returns
    -------
    StationarityTest
        The decision and p-values.
    """
    v = np.asarray(x, dtype=float)
    if v.size < 8:
        return StationarityTest(False, 0.0, None, alpha)
    parts = np.array_split(v, 4)
    lev_p = float(stats.levene(*parts, center=center).pvalue)
    if not lev_p > alpha:
        return StationarityTest(False, lev_p, None, alpha)
    half = v.size // 2
    ks_p = float(stats.ks_2samp(v[:half], v[half:]).pvalue)
    return StationarityTest(ks_p > alpha, lev_p, ks_p, alpha)


test_stationarity.__test__ = False  # not a pytest test despite its name
