"""Blackman-Tukey PSD estimate: lag-windowed biased sample autocorrelation.

This is the thesis's estimator (docs/method/spectra.rst): the Fourier transform
of the sample autocorrelation of the data multiplied by a "smoothed
rectangular" lag window that is flat over 80 % of the lags and rolls off
with a cosine over the remaining 20 % -- a Tukey window with ``alpha = 0.2``
spanning lags ``-M .. M``.

With the biased ACF ``r_k = (1/N) sum_n x_n x_{n+k}`` (mean removed) and lag
window ``w_k``, the one-sided PSD is::

    S(f) = 2 dt [ w_0 r_0 + 2 sum_{k=1}^{M} w_k r_k cos(2 pi f k dt) ]

so a white sequence of variance ``s^2`` gives ``2 s^2 dt`` and the integral
of ``S`` over ``[0, f_N]`` is exactly ``w_0 r_0``, the (biased) sample
variance.

Equivalent degrees of freedom (Priestley 1981; Percival & Walden 1993,
eq. 255a, no data taper): ``nu = 2 N / sum_{k=-M}^{M} w_k^2``. The formula is
asymptotic for ``M << N``; for the thesis's full-length lags (``M = N - 1``)
it gives ``nu ~ 1.14`` and very wide confidence intervals.

The Tukey lag window's transform has negative side lobes, so the estimate can
be negative at some frequencies. Negative values are kept as they are and
their number is recorded as ``params["n_negative"]``.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import fft as sp_fft
from scipy.signal import windows

from psdbound.errors import InputError

__all__ = ["blackman_tukey"]


def _biased_acf(x: NDArray[np.float64], max_lag: int) -> NDArray[np.float64]:
    """Biased autocovariance ``(1/N) sum x_n x_{n+k}`` for ``k = 0 .. max_lag``."""
    n = x.size
    nfft = sp_fft.next_fast_len(n + max_lag, real=True)
    spec = sp_fft.rfft(x, nfft)
    acov = sp_fft.irfft(spec.real**2 + spec.imag**2, nfft)[: max_lag + 1]
    return acov / n


def blackman_tukey(
    x: NDArray[np.float64],
    dt_s: float,
    *,
    max_lag_fraction: float = 1.0,
    alpha: float = 0.2,
    nfft: int | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], float, dict[str, Any]]:
    """One-sided Blackman-Tukey PSD with a Tukey lag window.

    Parameters
    ----------
    x : ndarray
        Finite samples, metres (1-D, at least 2).
    dt_s : float
        Sampling interval, seconds.
    max_lag_fraction : float, default 1.0
        Maximum lag ``M = round(max_lag_fraction * (N - 1))`` (at least 1);
        1.0 uses every lag, as the thesis does.
    alpha : float, default 0.2
        Tukey shape parameter: the fraction of the ``2M + 1`` lags in the
        cosine roll-off (0.2: flat over the central 80 %).
    nfft : int, optional
        FFT length, at least ``2M + 1``; default the next power of two.

    Returns
    -------
    f_hz : ndarray
        ``k / (nfft dt)`` for ``k = 0 .. nfft // 2``, Hz.
    psd_m2_hz : ndarray
        One-sided PSD, m^2/Hz (may contain negative values).
    dof : float
        ``2 N / sum w_k^2``.
    params : dict
        ``max_lag``, ``max_lag_fraction``, ``lag_window``, ``alpha``,
        ``nfft``, ``n_negative``.
    """
    n = x.size
    if not 0.0 < max_lag_fraction <= 1.0:
        raise InputError(f"max_lag_fraction must lie in (0, 1], got {max_lag_fraction!r}")
    if not 0.0 <= alpha <= 1.0:
        raise InputError(f"alpha must lie in [0, 1], got {alpha!r}")
    max_lag = max(1, int(round(max_lag_fraction * (n - 1))))
    if nfft is None:
        nfft = 1 << int(np.ceil(np.log2(2 * max_lag + 1)))
    elif int(nfft) < 2 * max_lag + 1:
        raise InputError(f"nfft must be at least 2M + 1 = {2 * max_lag + 1}, got {nfft}")
    nfft = int(nfft)

    xc = x - x.mean()
    acov = _biased_acf(xc, max_lag)
    lag_window = windows.tukey(2 * max_lag + 1, alpha=alpha)[max_lag:]  # lags 0 .. M

    seq = np.zeros(nfft)
    weighted = lag_window * acov
    seq[: max_lag + 1] = weighted
    seq[nfft - max_lag :] = weighted[:0:-1]  # negative lags, circularly
    psd = 2.0 * dt_s * sp_fft.rfft(seq).real
    f_hz = sp_fft.rfftfreq(nfft, dt_s)

    sum_w2 = lag_window[0] ** 2 + 2.0 * np.sum(lag_window[1:] ** 2)
    dof = float(2.0 * n / sum_w2)
    params: dict[str, Any] = {
        "max_lag": max_lag,
        "max_lag_fraction": float(max_lag_fraction),
        "lag_window": "tukey",
        "alpha": float(alpha),
        "nfft": nfft,
        "n_negative": int(np.count_nonzero(psd[1:] < 0.0)),
    }
    return f_hz, psd, dof, params
