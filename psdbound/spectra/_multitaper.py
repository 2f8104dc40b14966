"""Thomson multitaper PSD estimate with discrete prolate spheroidal (Slepian) tapers.

``K`` orthonormal DPSS tapers of time-half-bandwidth product ``NW``
(:func:`scipy.signal.windows.dpss`) are applied to the mean-removed data;
each gives an eigenspectrum ``S_k(f) = 2 dt |sum_t h_{k,t} x_t e^{-i 2 pi f t dt}|^2``
(one-sided, m^2/Hz; not doubled at 0 and at Nyquist). The tapers have unit
energy, so white noise of variance ``s^2`` gives ``2 s^2 dt``.

* ``adaptive=False`` (default): plain average of the ``K`` eigenspectra,
  ``nu = 2 K`` degrees of freedom.
* ``adaptive=True``: Thomson's adaptive weights (Percival & Walden 1993,
  eqs. 368a, 370a), iterated to convergence; the degrees of freedom
  ``nu(f) = 2 (sum_k b_k^2 lambda_k)^2 / sum_k b_k^4 lambda_k^2`` depend on
  frequency (at most ``2 K``).

The resolution half-bandwidth is ``W = NW / (N dt)`` Hz.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import fft as sp_fft
from scipy.signal import windows

from psdbound.errors import InputError

__all__ = ["dpss_tapers", "multitaper"]

_MAX_ADAPTIVE_ITER = 100


@lru_cache(maxsize=4)
def dpss_tapers(n: int, nw: float, k: int) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return DPSS tapers and their concentration ratios, cached and read-only.

    The one home of the spectra stage's tapers: the estimates, their exact
    expectation (:mod:`psdbound.spectra.expectation`) and the narrow
    lowest-frequency estimates (:mod:`psdbound.spectra.ordinates`) share it.

    Parameters
    ----------
    n : int
        Window length, samples.
    nw : float
        Time-half-bandwidth product.
    k : int
        Number of tapers.

    Returns
    -------
    tapers : ndarray, shape (k, n)
        Unit-energy tapers (:func:`scipy.signal.windows.dpss`).
    ratios : ndarray, shape (k,)
        Their concentration ratios.
    """
    tapers, ratios = windows.dpss(n, nw, Kmax=k, return_ratios=True)
    tapers = np.atleast_2d(tapers)
    ratios = np.atleast_1d(ratios)
    tapers.setflags(write=False)
    ratios.setflags(write=False)
    return tapers, ratios


def _adaptive(
    eigen: NDArray[np.float64], ratios: NDArray[np.float64], broadband: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Thomson's adaptive weighting; returns the PSD and the per-frequency DOF."""
    lam = ratios[:, None]
    psd = eigen[:2].mean(axis=0) if eigen.shape[0] > 1 else eigen[0].copy()
    for _ in range(_MAX_ADAPTIVE_ITER):
        b = psd / (lam * psd + (1.0 - lam) * broadband)
        weight = b**2 * lam
        new = np.sum(weight * eigen, axis=0) / np.sum(weight, axis=0)
        done = np.allclose(new, psd, rtol=1e-10, atol=0.0)
        psd = new
        if done:
            break
    b = psd / (lam * psd + (1.0 - lam) * broadband)
    weight = b**2 * lam
    dof = 2.0 * np.sum(weight, axis=0) ** 2 / np.sum(weight**2, axis=0)
    return psd, dof


def multitaper(
    x: NDArray[np.float64],
    dt_s: float,
    *,
    nw: float = 4.0,
    k: int | None = None,
    adaptive: bool = False,
    nfft: int | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64], float | NDArray[np.float64], dict[str, Any]]:
    """One-sided multitaper PSD.

    Parameters
    ----------
    x : ndarray
        Finite samples, metres (1-D).
    dt_s : float
        Sampling interval, seconds.
    nw : float, default 4.0
        Time-half-bandwidth product ``NW`` (``0 < NW < N / 2``).
    k : int, optional
        Number of tapers, ``1 <= K <= N``; default ``2 NW - 1`` (rounded
        down, at least 1).
    adaptive : bool, default False
        Thomson adaptive weighting instead of the plain average.
    nfft : int, optional
        FFT length (zero padding), at least ``N``; default ``N``.

    Returns
    -------
    f_hz : ndarray
        Frequencies ``0 .. f_N``, Hz.
    psd_m2_hz : ndarray
        One-sided PSD, m^2/Hz.
    dof : float or ndarray
        ``2 K``, or per frequency when ``adaptive``.
    params : dict
        ``nw``, ``k``, ``adaptive``, ``nfft``, ``bandwidth_hz`` (``W``),
        ``eigenvalues`` (concentration ratios, tuple).
    """
    n = x.size
    nw = float(nw)
    if not 0.0 < nw < n / 2.0:
        raise InputError(f"nw must lie in (0, N/2) = (0, {n / 2.0:g}), got {nw!r}")
    k = max(1, int(np.floor(2.0 * nw)) - 1) if k is None else int(k)
    if not 1 <= k <= n:
        raise InputError(f"k (number of tapers) must lie in [1, {n}], got {k}")
    nfft = n if nfft is None else int(nfft)
    if nfft < n:
        raise InputError(f"nfft must be at least the number of samples {n}, got {nfft}")

    tapers, ratios = dpss_tapers(n, nw, k)
    xc = x - x.mean()
    spec = sp_fft.rfft(tapers * xc, nfft, axis=-1)
    eigen = 2.0 * dt_s * (spec.real**2 + spec.imag**2)
    eigen[:, 0] /= 2.0
    if nfft % 2 == 0:
        eigen[:, -1] /= 2.0
    f_hz = sp_fft.rfftfreq(nfft, dt_s)

    dof: float | NDArray[np.float64]
    broadband = 2.0 * dt_s * float(np.mean(xc**2))
    if adaptive and k > 1 and broadband > 0.0:
        psd, dof = _adaptive(eigen, ratios, broadband)
    else:
        psd = eigen.mean(axis=0)
        dof = float(2 * k)
    params: dict[str, Any] = {
        "nw": nw,
        "k": k,
        "adaptive": bool(adaptive),
        "nfft": nfft,
        "bandwidth_hz": nw / (n * dt_s),
        "eigenvalues": tuple(float(v) for v in ratios),
    }
    return f_hz, psd, dof, params
