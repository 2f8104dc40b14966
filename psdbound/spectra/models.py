"""Closed-form PSDs of the bounding model: first-order Gauss-Markov + white noise.

Conventions (used everywhere in psdbound):

* PSDs are **one-sided, per hertz**, on ``0 <= f <= f_N = 1/(2 dt)`` for
  sampled data: the variance is the integral of the PSD from 0 to ``f_N``
  (from 0 to infinity for a continuous process). Units: m^2/Hz.
* Gauss-Markov (GMRP) autocorrelation ``R(t) = sigma^2 exp(-|t|/tau)``.
  Its two-sided continuous PSD is ``2 sigma^2 tau / (1 + (2 pi f tau)^2)``
  -- the thesis's expression ``(2 sigma^2/tau) / (1/tau^2 + 4 pi^2 f^2)``
  (eq. 3.6) -- and the one-sided PSD is twice that for ``f > 0``.
* Sampled at interval ``dt``, the GMRP is an AR(1) sequence with
  ``phi = exp(-dt/tau)`` whose one-sided PSD (the continuous PSD with every
  alias folded in) is
  ``2 sigma^2 dt (1 - phi^2) / (1 - 2 phi cos(2 pi f dt) + phi^2)``.
* White noise of per-sample standard deviation ``sigma_wn`` has the flat
  one-sided PSD ``2 sigma_wn^2 dt`` on ``[0, f_N]``. (The thesis's
  ``N_WN`` is the two-sided level ``sigma_wn^2 dt``.)
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "gm_psd_continuous",
    "gm_psd_sampled",
    "white_psd",
    "gm_acf",
]


def gm_psd_continuous(f_hz: ArrayLike, sigma_m: float, tau_s: float) -> NDArray[np.float64]:
    """One-sided PSD of a continuous first-order Gauss-Markov process, m^2/Hz.

    Parameters
    ----------
    f_hz : array_like
        Frequencies, Hz (>= 0).
    sigma_m : float
        Standard deviation, metres.
    tau_s : float
        Time constant, seconds.

    Returns
    -------
    ndarray
        ``4 sigma^2 tau / (1 + (2 pi f tau)^2)``.
    """
    f = np.asarray(f_hz, dtype=float)
    return 4.0 * sigma_m**2 * tau_s / (1.0 + (2.0 * np.pi * f * tau_s) ** 2)


def gm_psd_sampled(
    f_hz: ArrayLike, sigma_m: float, tau_s: float, dt_s: float
) -> NDArray[np.float64]:
    """One-sided PSD of a Gauss-Markov process sampled every ``dt_s`` (aliased), m^2/Hz.

    Parameters
    ----------
    f_hz : array_like
        Frequencies, Hz, in ``[0, 1/(2 dt)]``.
    sigma_m : float
        Standard deviation, metres.
    tau_s : float
        Time constant, seconds.
    dt_s : float
        Sampling interval, seconds.

    Returns
    -------
    ndarray
        ``2 sigma^2 dt (1 - phi^2) / (1 - 2 phi cos(2 pi f dt) + phi^2)``,
        ``phi = exp(-dt/tau)``; integrates to ``sigma^2`` over ``[0, f_N]``.
    """
    f = np.asarray(f_hz, dtype=float)
    phi = np.exp(-dt_s / tau_s)
    return (
        2.0
        * sigma_m**2
        * dt_s
        * (1.0 - phi**2)
        / (1.0 - 2.0 * phi * np.cos(2.0 * np.pi * f * dt_s) + phi**2)
    )


def white_psd(f_hz: ArrayLike, sigma_wn_m: float, dt_s: float) -> NDArray[np.float64]:
    """One-sided PSD of sampled white noise with per-sample std ``sigma_wn_m``, m^2/Hz."""
    f = np.asarray(f_hz, dtype=float)
    return np.full(f.shape, 2.0 * sigma_wn_m**2 * dt_s)


def gm_acf(lag_s: ArrayLike, sigma_m: float, tau_s: float) -> NDArray[np.float64]:
    """Autocorrelation ``sigma^2 exp(-|lag|/tau)`` of a Gauss-Markov process, m^2."""
    lag = np.asarray(lag_s, dtype=float)
    return sigma_m**2 * np.exp(-np.abs(lag) / tau_s)
