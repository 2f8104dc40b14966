"""Lomb-Scargle by astropy on the explicitly replicated series."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["lombscargle_astropy", "replicate_series"]


def replicate_series(
    t_s: NDArray[np.float64], y: NDArray[np.float64], copies: int, period_s: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The series and its ``copies - 1`` replicas shifted by multiples of ``period_s``.

    Parameters
    ----------
    t_s : ndarray of float64
        Sample times, s.
    y : ndarray of float64
        Values.
    copies : int
        Number of copies (1: the series itself).
    period_s : float
        Shift between consecutive copies, s.

    Returns
    -------
    t_all_s, y_all : ndarray of float64
        Concatenated times and values of the copies.
    """
    shifts = period_s * np.arange(copies)
    t_all = (t_s[None, :] + shifts[:, None]).ravel()
    return t_all, np.tile(y, copies)


def lombscargle_astropy(
    t_s: NDArray[np.float64],
    y: NDArray[np.float64],
    frequency_hz: NDArray[np.float64],
    *,
    copies: int = 1,
    period_s: float = 0.0,
    normalization: str = "psd",
    astropy_method: str = "auto",
    method_kwds: dict | None = None,
    fit_mean: bool = True,
    center_data: bool = True,
) -> NDArray[np.float64]:
    from astropy.timeseries import LombScargle

    t_all, y_all = replicate_series(t_s - t_s[0], y, copies, period_s)
    ls = LombScargle(
        t_all, y_all, fit_mean=fit_mean, center_data=center_data, normalization=normalization
    )
    return np.asarray(
        ls.power(frequency_hz, method=astropy_method, method_kwds=method_kwds), dtype=np.float64
    )
