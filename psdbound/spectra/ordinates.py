"""The lowest Fourier frequencies: narrow estimates, their degrees of freedom, a window's excess.

Each window's narrow estimate at its lowest Fourier frequencies, the degrees of freedom of
their sums, and a window's excess there over the other windows of its shape group.

The statement's multitaper (``NW = 4``) smooths over ``+- 4 / T``: a slow reflector's power,
largest at the lowest Fourier frequencies ``j / T``, shows in no band of its own. A narrow
multitaper (``NW =`` :data:`LOWEST_NW`, :data:`LOWEST_TAPERS` tapers, resolution
``+- 1.5 / T``) of each window (mean removed) at ``j = 1 ..`` :data:`MAX_ORDINATES` below
``f_min`` resolves it. Two uses:

* :mod:`psdbound.spectra.lowest` holds the bound's expected estimate above each shape
  group's upper limit there;
* :mod:`psdbound.spectra.groups` tests whether a window's estimate there exceeds the other
  windows' of its group more than its own level says (:func:`low_excess_p`): a minority of
  slow strong reflectors, whose excess lies below the statement's lowest band and which the
  tests on the bands miss, gets its own group.

**Degrees of freedom.** Adjacent ordinates ``j / T`` and ``(j + 1) / T`` lie within each
other's resolution ``+- 1.5 / T``, and the mean removal empties part of ``j = 1``: the
estimates are not independent. Counted as ``2 K`` each, four ordinates of one window would
carry 16 degrees of freedom; they carry 7.4 (3.35 for ``j = 1`` alone). The count here is
Satterthwaite's ``tr(Q)^2 / tr(Q^2)`` of the estimate's quadratic form ``Q`` for white noise
([Satterthwaite1946]_; Percival and Walden 1993, section 7.3), exact for a locally flat
spectrum, computed from the Gram matrix of the tapered, mean-removed Fourier vectors
(:func:`ordinate_dof`).

References
----------
.. [Satterthwaite1946] Satterthwaite, F. E. (1946). An approximate distribution of estimates
   of variance components. *Biometrics Bulletin*, 2(6), 110-114.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy import special, stats

from psdbound.spectra._multitaper import dpss_tapers
from psdbound.spectra.limits import log_chi2_bias

__all__ = [
    "LENGTH_MATCH",
    "LOWEST_NW",
    "LOWEST_TAPERS",
    "MAX_ORDINATES",
    "LowestOrdinates",
    "low_excess_p",
    "lowest_ordinates",
    "ordinate_dof",
]

#: Time-half-bandwidth product of the lowest-frequency estimate.
LOWEST_NW = 1.5
#: Its DPSS tapers, ``floor(2 NW) - 1`` (as :func:`psdbound.spectra.expectation.lag_kernels`
#: takes for ``nw``): two.
LOWEST_TAPERS = max(1, int(2.0 * LOWEST_NW) - 1)
#: Most Fourier frequencies checked per window.
MAX_ORDINATES = 4
#: Windows compared by :func:`low_excess_p` differ in length by at most this factor (their
#: ordinates ``j / T`` then lie within one resolution half-width of each other).
LENGTH_MATCH = 1.25


@dataclass(frozen=True)
class LowestOrdinates:
    """Narrow multitaper estimates of each window at its lowest Fourier frequencies.

    Attributes
    ----------
    n : ndarray of int, shape (M,)
        Window lengths, samples.
    j : ndarray of int, shape (J,)
        Fourier indices ``j`` (frequency ``j / (n dt)`` of each window).
    estimate_m2_hz : ndarray, shape (M, J)
        One-sided estimates, m^2/Hz.
    dt_s : float
        Sampling interval, seconds.
    """

    n: NDArray[np.int64]
    j: NDArray[np.int64]
    estimate_m2_hz: NDArray[np.float64]
    dt_s: float

    def dof(self, rows: NDArray[np.int64], run: NDArray[np.int64]) -> float:
        """Degrees of freedom of the sum over windows ``rows`` of their mean over ``run``.

        ``run`` indexes :attr:`j`; the windows are independent (their sum adds them).
        """
        js = tuple(int(v) for v in self.j[run])
        return float(sum(ordinate_dof(int(n), js) for n in self.n[rows]))


def lowest_ordinates(
    stretches: Sequence[NDArray[np.float64]], dt_s: float, f_min_hz: float
) -> LowestOrdinates | None:
    """Estimate every window at the Fourier frequencies ``j / T`` below ``f_min``.

    Parameters
    ----------
    stretches : sequence of ndarray
        The windows (evenly sampled, finite).
    dt_s : float
        Sampling interval, seconds.
    f_min_hz : float
        Lowest frequency of the statement, Hz.

    Returns
    -------
    LowestOrdinates or None
        ``j = 1 ..`` up to :data:`MAX_ORDINATES`, as far as ``j / T`` lies
        below ``f_min`` for every window; None when not even ``j = 1`` does.
    """
    n = np.array([x.size for x in stretches], dtype=np.int64)
    n_j = min(MAX_ORDINATES, int(np.ceil(f_min_hz * float(n.min()) * dt_s)) - 1)
    if n_j < 1:
        return None
    j = np.arange(1, n_j + 1)
    est = np.zeros((n.size, n_j))
    for i, x in enumerate(stretches):
        y = np.asarray(x, dtype=float) - float(np.mean(x))
        eig = np.abs(_tapered_fourier(y.size, tuple(j.tolist())) @ y) ** 2
        est[i] = 2.0 * dt_s * eig.mean(axis=0)
    return LowestOrdinates(n, j, est, float(dt_s))


@lru_cache(maxsize=32)
def _tapered_fourier(n: int, js: tuple[int, ...]) -> NDArray[np.complex128]:
    """Return the estimate's vectors, each taper times ``exp(-2 pi i j t / n)``, (K, J, n).

    Windows of one length share them (read-only).
    """
    tapers = dpss_tapers(n, LOWEST_NW, LOWEST_TAPERS)[0]
    phase = np.exp(-2j * np.pi * np.outer(np.asarray(js), np.arange(n)) / n)
    out = tapers[:, None, :] * phase[None]
    out.setflags(write=False)
    return out


@lru_cache(maxsize=256)
def ordinate_dof(n: int, js: tuple[int, ...]) -> float:
    """Degrees of freedom of one window's mean narrow estimate over Fourier indices ``js``.

    Satterthwaite's ``tr(Q)^2 / tr(Q^2)`` for white noise, ``Q`` the quadratic
    form of the estimate (its tapered, mean-removed Fourier vectors, real and
    imaginary parts): ``2 K len(js)`` for independent ordinates, less for the
    overlapping ones of :func:`lowest_ordinates`.

    Parameters
    ----------
    n : int
        Window length, samples.
    js : tuple of int
        Fourier indices.

    Returns
    -------
    float
    """
    v = _tapered_fourier(n, js).reshape(-1, n)
    v = v - v.mean(axis=1, keepdims=True)  # the estimate's window had its mean removed
    vec = np.vstack([v.real, v.imag])
    gram = vec @ vec.T
    return float(np.trace(gram) ** 2 / np.sum(gram * gram))


def low_excess_p(
    lowest: LowestOrdinates,
    members: NDArray[np.int64],
    level: NDArray[np.float64],
    level_se: NDArray[np.float64],
) -> NDArray[np.float64]:
    """p-value of each member's excess at its lowest ordinates over the others, level-adjusted.

    For member ``w`` the others of about its length (within :data:`LENGTH_MATCH`)
    are scaled to its level, ``exp(d_w - d_o)``; their reference is the median
    of their logs, each less the median of ``ln(chi^2_nu / nu)`` (a median, so
    that a second slow reflector among the others does not hide the first).
    Under a common shape ``ln mean_w - E ln(chi^2_nu_w / nu_w) - ref`` is about
    normal with variance ``psi'(nu_w / 2) + (pi / 2) psi'(nu / 2) / n_o +
    se_w^2`` (the sample median's variance; the upper tail of a log chi-square
    is lighter than the normal's, so the p-value errs large). One-sided: only a
    window above its group can be left uncovered by it.

    Parameters
    ----------
    lowest : LowestOrdinates
        Every window's narrow estimates.
    members : ndarray of int
        Rows of ``lowest`` in the group being tested.
    level, level_se : ndarray, shape (len(members),)
        Each member's log level deviation and its standard error, from the bands.

    Returns
    -------
    ndarray, shape (len(members),)
        1 for a member with no other of about its length.
    """
    n = lowest.n[members].astype(float)
    js = tuple(lowest.j.tolist())
    mean = lowest.estimate_m2_hz[members].mean(axis=1)
    nu = np.array([ordinate_dof(int(k), js) for k in lowest.n[members]])
    positive = mean > 0.0
    log_mean = np.log(np.where(positive, mean, 1.0))
    median_log = np.log(stats.chi2.median(nu) / nu)
    spread = special.polygamma(1, nu / 2.0)
    out = np.ones(members.size)
    for i in range(members.size):
        peers = positive & (np.abs(np.log(n / n[i])) <= np.log(LENGTH_MATCH))
        peers[i] = False
        if not peers.any() or not positive[i]:
            continue
        ref = np.median(log_mean[peers] - level[peers] - median_log[peers]) + level[i]
        excess = log_mean[i] - log_chi2_bias(nu[i]) - ref
        var = spread[i] + 0.5 * np.pi * float(np.mean(spread[peers])) / peers.sum()
        out[i] = float(stats.norm.sf(excess / np.sqrt(var + level_se[i] ** 2)))
    return out
