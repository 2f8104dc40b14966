"""The Q-Q criterion of seed 001: sample against standard-normal quantiles.

:func:`qq_ratio` pairs sorted samples with normal quantiles;
:func:`gaussian_overbound_sigma` is the seed's zero-mean bound (largest
quantile ratio outside a core). The overbounds an integrity argument rests on
(paired, two-step, CDF) are in :mod:`psdbound.aviation.overbound`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.stats import norm

from psdbound.errors import InputError

__all__ = ["gaussian_overbound_sigma", "qq_ratio"]


def qq_ratio(
    samples: ArrayLike, *, sigma: float = 1.0
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Sample vs standard-normal quantiles and their ratio (a Q-Q plot), seed 001.

    The ``i``-th smallest of ``n`` samples (divided by ``sigma``) is paired
    with the normal quantile ``z_i = Phi^-1((i - 0.5) / n)`` (Hazen plotting
    positions); the ratio is ``x_(i) / z_i``.

    Parameters
    ----------
    samples : array_like
        Sample errors (any unit), e.g. errors normalised by a model sigma.
    sigma : float, default 1
        Divide the samples by this first.

    Returns
    -------
    z : ndarray
        Standard-normal quantiles.
    x : ndarray
        Sorted samples / ``sigma``.
    ratio : ndarray
        ``x / z`` (``nan`` where ``z = 0``).
    """
    x = np.sort(np.asarray(samples, dtype=float).reshape(-1)) / float(sigma)
    if x.size < 2 or not np.isfinite(x).all():
        raise InputError("need at least 2 finite samples")
    p = (np.arange(1, x.size + 1) - 0.5) / x.size
    z = norm.ppf(p)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(z != 0, x / z, np.nan)
    return z, x, ratio


def gaussian_overbound_sigma(
    samples: ArrayLike, *, sigma: float = 1.0, min_abs_z: float = 1.0
) -> float:
    """Sigma of the smallest zero-mean Gaussian whose quantiles enclose the sample's.

    The largest ratio of sample to standard-normal quantile (seed 001: "the
    maximum ratio between the sample quantiles and the gaussian quantiles
    will provide the standard deviation of the minimum gaussian that bounds
    the sample distribution"): ``max x_(i) / z_i`` over the points with
    ``|z_i| >= min_abs_z``, which makes ``sigma z_i >= x_(i)`` in the upper
    tail and ``sigma z_i <= x_(i)`` in the lower tail. The core
    (``|z| < min_abs_z``) is left out because ``x / z`` is unstable there
    (any non-zero median divided by ``z -> 0``); integrity cares about tails.
    This is the Q-Q criterion of the seed, not the two-step (paired)
    overbounding of its reference [4].

    Parameters
    ----------
    samples : array_like
        Sample errors (e.g. normalised by a model sigma, then the result is
        the model's inflation factor).
    sigma : float, default 1
        Divide the samples by this first.
    min_abs_z : float, default 1
        Only quantiles with ``|z| >= min_abs_z`` count (0 keeps all).

    Returns
    -------
    float
        The overbounding sigma (in units of ``sigma``).
    """
    z, _, ratio = qq_ratio(samples, sigma=sigma)
    keep = (np.abs(z) >= float(min_abs_z)) & (z != 0)
    if not keep.any():
        raise InputError(f"no sample quantile with |z| >= {min_abs_z}; use more samples")
    return float(np.max(ratio[keep]))
