"""What ROTI multipath alone produces: an empirical null with a stated false-alarm rate.

ROTI of the geometry-free phase holds the multipath too (``L_a - L_b`` moves
with the two carriers' multipath), so a fixed threshold either cuts strong
multipath as "ionosphere" or, scaled up with an elevation mapping, lets
disturbances of low satellites through. Here the distribution of ROTI under
multipath alone is estimated from the data themselves, per elevation band,
and a block is ionosphere when its ROTI is improbable under it.

**Model.** Within a 5-min block ROT is a stationary series (differences of
the multipath over 30 s), so ``ROTI^2`` is a scaled chi-square,
``s^2 chi2_nu / nu``: ``s^2`` the band's multipath ROT variance and ``nu`` the
effective degrees of freedom (fewer than the block's samples when ROT is
correlated; smaller still where satellites differ). The scale is local in
elevation: the 30th percentile of ``ROTI^2`` over the blocks nearest in
elevation. The shape is common: ``nu`` from the ratio of the 30th to the 10th
percentile of all blocks' ``ROTI^2`` over their local scale, taken at a
lower bootstrap confidence limit (a heavier tail). Only the lower part of
the distribution enters: an *empirical null* in the sense of Efron (2004),
which disturbed blocks, in the upper tail, barely move (30 % of the blocks
disturbed move the scale by at most 40 %, ``tests/screening/test_null.py``).
Each local quantile is placed at the median elevation of its blocks (at the
ends of the range the window is one-sided; placed at the end block, the
scale came out 10-13 % low one degree above the mask where multipath grows
towards the horizon).

**Test.** A block is ionosphere when its ROTI exceeds the null's ``1 - p``
quantile, ``p`` the stated false-alarm probability per block (default
1e-3), and the ionospheric significance level (0.15 TECU/min by default,
:mod:`psdbound.screening.screen`). Three tests share ``p`` (a third each,
Bonferroni): the block alone, the persistence below, and the coherence
across satellites (:mod:`psdbound.screening.coherence`). The same ``p`` holds at every
elevation: the local multipath sets the threshold, no mapping is assumed.
On synthetic nulls the realised rate is 0.3-2.4 times the stated one (the
far tail rests on the fitted shape). Where the significance level lies above
the null's quantile it sets the threshold, and the probability that
multipath alone exceeds it is smaller (:meth:`MultipathNull.exceedance`).
On real quiet days the far tail is heavier than the fitted chi-square (ESBC:
2.3 % of the blocks above the 1 - 1e-3 quantile), most at low elevation; the
significance level keeps that from cutting data where multipath is weak
(:mod:`psdbound.screening.screen`).

**Persistence.** A disturbance lasts longer than a block: the sum of
``ROTI^2 / s^2`` over 3 consecutive blocks of an arc (chi-square with ``3 nu``
degrees of freedom under the null) is tested at the same ``p``
(:meth:`MultipathNull.persistent`). A 0.3 TECU/min disturbance at 21 deg,
where multipath alone gives about 0.15 TECU/min, escapes the single-block
test in a quarter of its blocks; over three blocks its excess is about twice
the threshold.

**When the null is disturbed.** If much of the series is disturbed (a
polar or equatorial day), the lower quantiles are no longer multipath: the
fitted shape is then heavy-tailed (``nu`` below :data:`NU_DISTURBED`) and
the null is not trusted; the screen then also applies the elevation-scaled
fixed threshold and says so.

References
----------
Efron, B. (2004). Large-scale simultaneous hypothesis testing: the choice of
a null hypothesis. Journal of the American Statistical Association 99(465),
96-104.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import optimize, special, stats

from psdbound.screening.options import FALSE_ALARM

__all__ = [
    "FALSE_ALARM",
    "MEMBER_TAIL",
    "MIN_BLOCKS",
    "MultipathNull",
    "fit_null",
    "local_exceedance",
    "local_scale",
    "lower_dof",
]

#: Fewest blocks to fit a null; also the neighbours of each local scale.
MIN_BLOCKS = 40
#: Quantiles of ROTI^2 the null is fitted to (the lower part: disturbed blocks sit above).
Q_LO, Q_HI = 0.1, 0.3
#: Elevations at which the local scale is tabulated.
_N_GRID = 24
#: Degrees of freedom searched.
_NU = (0.5, 400.0)
#: Bootstrap resamples of the shape.
N_BOOT = 40
#: Consecutive blocks of the persistence test (15 min, the shortest disturbance screened).
PERSIST_BLOCKS = 3
#: Tail of the null a block of a significant run must itself be in to be flagged.
MEMBER_TAIL = 0.25
#: Below this shape the null is itself disturbed (multipath days: 5.5 on ESBC, 7.8 on a
#: simulated 6 mm day; the polar NYA1 day, 30 % of it disturbed: 1.9).
NU_DISTURBED = 3.0


def _ratio(nu: float) -> float:
    """``Q_HI`` over ``Q_LO`` quantile of a chi-square with ``nu`` degrees of freedom.

    ``2 gammaincinv(nu / 2, q)`` is what ``scipy.stats.chi2.ppf(q, nu)``
    computes (the same values, bit for bit), without the distribution
    framework's argument handling, which cost 40 times the special function
    in the root searches of :func:`lower_dof` (about 1,400 calls a station day).
    """
    hi, lo = (2.0 * special.gammaincinv(nu / 2.0, q) for q in (Q_HI, Q_LO))
    return float(hi / lo)


def _dof_of(u: NDArray[np.float64], ratio: Callable[[float], float] = _ratio) -> float:
    """Return ``nu`` of the family whose ``Q_HI / Q_LO`` quantile ratio matches the sample's."""
    q_lo, q_hi = np.quantile(u, [Q_LO, Q_HI])
    r = q_hi / max(q_lo, 1e-300)
    lo, hi = _NU
    if r >= ratio(lo):
        return lo
    if r <= ratio(hi):
        return hi
    return float(optimize.brentq(lambda v: ratio(v) - r, lo, hi))


def lower_dof(u: NDArray[np.float64], ratio: Callable[[float], float] = _ratio) -> float:
    """Return a lower confidence limit of ``nu`` (a heavier tail: the stated rate holds).

    The far tail is sensitive to ``nu``: its point estimate from a few thousand
    blocks put the realised false-alarm rate at 0.7-3.5 times the stated one.
    The 10th percentile of :data:`N_BOOT` bootstrap estimates (seeded) is used.

    Parameters
    ----------
    u : ndarray
        The blocks' statistic over its local scale (dimensionless).
    ratio : callable, optional
        ``nu -> Q_HI / Q_LO`` quantile ratio of the family (default: chi-square).

    Returns
    -------
    float
        ``nu``, within :data:`_NU`.
    """
    rng = np.random.default_rng(0)
    boot = [_dof_of(u[rng.integers(0, u.size, u.size)], ratio) for _ in range(N_BOOT)]
    return float(np.quantile(boot, 0.1))


@dataclass(frozen=True)
class MultipathNull:
    """ROTI^2 under multipath alone: a local scale in elevation and one shape.

    ``ROTI^2 / q(el) ~ chi2_nu / chi2_nu(Q_HI)``, ``q(el)`` the local
    ``Q_HI`` quantile of ``ROTI^2`` (interpolated in elevation).

    Attributes
    ----------
    elevation_deg : ndarray
        Elevations of the tabulated local scale, degrees (increasing).
    q_hi : ndarray
        The local ``Q_HI`` quantile of ``ROTI^2`` there, (TECU/min)^2.
    dof : float
        ``nu``, fitted to all blocks scaled by their local quantile.
    n_blocks : int
        Blocks the null was fitted on.
    """

    elevation_deg: NDArray[np.float64]
    q_hi: NDArray[np.float64]
    dof: float
    n_blocks: int

    @property
    def trusted(self) -> bool:
        """Whether the null looks like multipath (``dof >= NU_DISTURBED``).

        A heavy-tailed null (few effective degrees of freedom) means that
        much of the series is disturbed: the lower quantiles are then no
        longer multipath alone.
        """
        return self.dof >= NU_DISTURBED

    def scale2(self, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return ``s^2``, the multipath ROT variance at ``elevation_deg``, (TECU/min)^2."""
        q = np.interp(np.asarray(elevation_deg, dtype=float), self.elevation_deg, self.q_hi)
        return q * self.dof / stats.chi2.ppf(Q_HI, self.dof)

    def threshold(
        self, elevation_deg: ArrayLike, false_alarm: float = FALSE_ALARM
    ) -> NDArray[np.float64]:
        """Return the ROTI a block at ``elevation_deg`` exceeds with probability ``false_alarm``.

        Parameters
        ----------
        elevation_deg : array_like
            Mean elevation of each block, degrees.
        false_alarm : float, default 1e-3
            False-alarm probability per block under multipath alone.

        Returns
        -------
        ndarray
            TECU/min.
        """
        return np.sqrt(
            self.scale2(elevation_deg) * stats.chi2.isf(false_alarm, self.dof) / self.dof
        )

    def exceedance(self, roti_tecu_min: ArrayLike, elevation_deg: ArrayLike) -> NDArray[np.float64]:
        """Return the probability that a block of multipath alone exceeds ``roti_tecu_min``.

        The inverse of :meth:`threshold`: ``exceedance(threshold(el, p), el) == p``.

        Parameters
        ----------
        roti_tecu_min : array_like
            ROTI levels, TECU/min.
        elevation_deg : array_like
            Mean elevation of the blocks, degrees.

        Returns
        -------
        ndarray
            Probability per block under the null (dimensionless, 0-1).
        """
        r = np.asarray(roti_tecu_min, dtype=float)
        return stats.chi2.sf(self.dof * r**2 / self.scale2(elevation_deg), self.dof)

    def persistent(
        self,
        roti_tecu_min: ArrayLike,
        elevation_deg: ArrayLike,
        *,
        blocks: int = PERSIST_BLOCKS,
        false_alarm: float = FALSE_ALARM,
        floor_tecu_min: float = 0.0,
    ) -> NDArray[np.bool_]:
        """Flag runs of consecutive blocks whose ROTI together is improbable under the null.

        A disturbance lasts longer than one 5-min block; over ``blocks``
        consecutive blocks of one arc the scaled sum ``nu sum(ROTI^2 / s^2)`` is
        chi-square with ``blocks nu`` degrees of freedom under multipath alone.
        In a run above its ``1 - false_alarm`` quantile whose RMS ROTI also
        exceeds ``floor_tecu_min``, the blocks in the null's top
        :data:`MEMBER_TAIL` are flagged (a strong block does not carry its
        quiet neighbours with it).

        Parameters
        ----------
        roti_tecu_min, elevation_deg : array_like
            ROTI and mean elevation of the consecutive blocks of one arc.
        blocks : int, default 3
            Run length (15 min).
        false_alarm : float, default 1e-3
            False-alarm probability per run.
        floor_tecu_min : float, default 0
            Smallest RMS ROTI of a flagged run (the ionospheric significance).

        Returns
        -------
        ndarray of bool
        """
        r = np.asarray(roti_tecu_min, dtype=float)
        out = np.zeros(r.size, bool)
        if r.size < blocks:
            return out
        z = np.where(np.isfinite(r), r**2 / self.scale2(elevation_deg), np.nan)
        w = np.lib.stride_tricks.sliding_window_view(z, blocks).sum(axis=1)
        rms = np.sqrt(
            np.lib.stride_tricks.sliding_window_view(
                np.where(np.isfinite(r), r**2, np.nan), blocks
            ).mean(axis=1)
        )
        hit = (w * self.dof > stats.chi2.isf(false_alarm, blocks * self.dof)) & (
            rms > floor_tecu_min
        )
        # a run's blocks are flagged where they are themselves in the null's top quarter: a
        # strong block does not carry its quiet neighbours with it
        member = (z * self.dof > stats.chi2.isf(MEMBER_TAIL, self.dof)) & (r > floor_tecu_min)
        for j in np.flatnonzero(np.nan_to_num(hit, nan=False).astype(bool)):
            out[j : j + blocks] |= member[j : j + blocks]
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "elevation_deg": self.elevation_deg.tolist(),
            "scale_tecu_min": np.sqrt(self.scale2(self.elevation_deg)).tolist(),
            "dof": self.dof,
            "n_blocks": self.n_blocks,
            "trusted": self.trusted,
        }


def fit_null(
    roti_tecu_min: ArrayLike, elevation_deg: ArrayLike, *, min_blocks: int = MIN_BLOCKS
) -> MultipathNull | None:
    """Fit the multipath null of ROTI: a local scale in elevation and one chi-square shape.

    Parameters
    ----------
    roti_tecu_min : array_like
        ROTI of every block of the series, TECU/min (NaN: left out).
    elevation_deg : array_like
        Mean elevation of every block, degrees.
    min_blocks : int, default 40
        Fewest usable blocks; each local ``Q_HI`` quantile is taken over the
        ``max(min_blocks, n / 12)`` blocks nearest in elevation.

    Returns
    -------
    MultipathNull or None
        None with fewer than ``min_blocks`` usable blocks.
    """
    r = np.asarray(roti_tecu_min, dtype=float)
    scale = local_scale(r**2, elevation_deg, min_blocks=min_blocks)
    if scale is None:
        return None
    grid, q, u = scale
    return MultipathNull(grid, q, lower_dof(u), u.size)


def local_scale(
    values: ArrayLike, elevation_deg: ArrayLike, *, min_blocks: int = MIN_BLOCKS
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]] | None:
    """Return the local ``Q_HI`` quantile of ``values`` in elevation, and the scaled values.

    Parameters
    ----------
    values : array_like
        A positive statistic per block (NaN or <= 0: left out), any unit.
    elevation_deg : array_like
        Mean elevation of every block, degrees.
    min_blocks : int, default 40
        Fewest usable blocks; each local quantile is taken over the
        ``max(min_blocks, n / 12)`` blocks nearest in elevation.

    Returns
    -------
    tuple of ndarray or None
        The elevations of the tabulated scale (deg, increasing: the median
        elevation of each window), the local quantile there (the unit of
        ``values``) and every usable block's value over its interpolated
        local quantile (constant beyond the first and last window's median);
        None with fewer than ``min_blocks`` usable blocks.
    """
    x = np.asarray(values, dtype=float)
    el = np.asarray(elevation_deg, dtype=float)
    ok = np.isfinite(x) & np.isfinite(el) & (x > 0)
    n = int(ok.sum())
    if n < min_blocks:
        return None
    e_s, x_s, windows = _local_windows(el[ok], x[ok], min_blocks)
    q = np.array([np.quantile(x_s[w], Q_HI) for w in windows])
    # each quantile belongs to its window's median elevation: at the ends of the elevation range
    # the window is one-sided, and placing its quantile at the end block biased the scale there
    # (low where the multipath grows towards the horizon)
    grid = np.array([np.median(e_s[w]) for w in windows])
    grid, first = np.unique(grid, return_index=True)
    q = q[first]
    return grid, q, x_s / np.interp(e_s, grid, q)


def _local_windows(
    el: NDArray[np.float64], x: NDArray[Any], min_blocks: int
) -> tuple[NDArray[np.float64], NDArray[Any], list[slice]]:
    """Sort by elevation; return the sorted values and the local windows (>= 40, 1/12 of all)."""
    n = el.size
    order = np.argsort(el)
    half = max(min_blocks, n // 12) // 2
    centres = np.unique(np.linspace(0, n - 1, min(_N_GRID, n)).astype(int))
    windows = [slice(max(0, c - half), min(n, c + half + 1)) for c in centres]
    return el[order], x[order], windows


def local_exceedance(
    exceeds: ArrayLike,
    elevation_deg: ArrayLike,
    *,
    min_blocks: int = MIN_BLOCKS,
    confidence_level: float = 0.95,
) -> dict[str, NDArray[np.float64]] | None:
    """Count the blocks above their threshold along elevation; a model-free upper limit.

    The null's tail is extrapolated from its lower quantiles; this measures
    it. Over the same local windows as :func:`local_scale` (the blocks
    nearest in elevation), ``k`` of ``n`` blocks exceed their threshold, and
    the one-sided Clopper-Pearson limit bounds the exceedance probability of
    the day's blocks from above. Ionosphere adds independent variance to the
    rate of TEC, so (to that approximation) the day's blocks exceed a
    threshold at least as often as their multipath alone would: the limit is
    also an upper limit of the false-alarm probability, whatever the null's
    shape.

    Parameters
    ----------
    exceeds : array_like of bool
        Whether each block's statistic exceeded its threshold (NaN
        elevations: left out).
    elevation_deg : array_like
        Mean elevation of every block, degrees.
    min_blocks : int, default 40
        As for :func:`local_scale`.
    confidence_level : float, default 0.95
        Level of the upper limit.

    Returns
    -------
    dict or None
        ``elevation_deg`` (each window's median), ``exceeded`` (k),
        ``blocks`` (n), ``upper`` (the limit, 0-1); None with fewer than
        ``min_blocks`` blocks.
    """
    hit = np.asarray(exceeds, dtype=bool)
    el = np.asarray(elevation_deg, dtype=float)
    ok = np.isfinite(el)
    if int(ok.sum()) < min_blocks:
        return None
    e_s, h_s, windows = _local_windows(el[ok], hit[ok], min_blocks)
    k = np.array([int(h_s[w].sum()) for w in windows], dtype=float)
    n = np.array([w.stop - w.start for w in windows], dtype=float)
    upper = np.where(k < n, stats.beta.ppf(confidence_level, k + 1.0, n - k), 1.0)
    return {
        "elevation_deg": np.array([np.median(e_s[w]) for w in windows]),
        "exceeded": k,
        "blocks": n,
        "upper": upper,
    }
