"""Exact Lomb-Scargle of a gappy regularly sampled series, replicated, by FFT.

The series is sampled on a regular grid ``t_i = t_0 + n_i dt`` (integer
``n_i``, gaps allowed) and optionally replicated ``copies`` times at spacing
``period_s`` (which need not be a multiple of ``dt``). Every trigonometric
sum of the Lomb-Scargle periodogram then factorises:

    sum_{r, i} a_i exp(j w (t_i + r P)) = G(w) * exp(j w t_0) * sum_i a_i exp(j w n_i dt),
    G(w) = sum_{r=0}^{R-1} exp(j w r P)

and on the frequency grid ``f_k = k / (M dt)`` the last sum is one entry of
the length-``M`` FFT of the zero-filled series (``2 w`` maps to index
``2k mod M``). So the periodogram is *exact* (to rounding), not an
extirpolation/NUFFT approximation, at O(M log M) cost. The formulas are the
floating-mean (generalised) periodogram of Zechmeister & Kurster (2009) with
the time shift tau, unit weights, as astropy's ``LombScargle`` with
``fit_mean=True, center_data=True`` computes it; ``normalization="psd"``
matches astropy's. With ``fit_mean=False`` (and the data not centred) the
mean terms vanish and the formulas are the classical periodogram's
(astropy ``fit_mean=False, center_data=False``).
"""

from __future__ import annotations

import numpy as np
import scipy.fft
from numpy.typing import NDArray

__all__ = ["grid_indices", "lombscargle_gridfft"]


def grid_indices(t_s: NDArray[np.float64], dt_s: float) -> NDArray[np.int64] | None:
    """Integer sample indices of ``t_s`` on a ``dt_s`` grid, or None if off-grid."""
    rel = (t_s - t_s[0]) / dt_s
    n = np.round(rel).astype(np.int64)
    if np.max(np.abs(rel - n), initial=0.0) > 1e-6 or np.any(np.diff(n) <= 0):
        return None
    return n


def lombscargle_gridfft(
    t_s: NDArray[np.float64],
    y: NDArray[np.float64],
    frequency_hz: NDArray[np.float64],
    *,
    dt_s: float,
    copies: int = 1,
    period_s: float = 0.0,
    normalization: str = "psd",
    fit_mean: bool = True,
) -> NDArray[np.float64]:
    """Exact Lomb-Scargle power of on-grid (gappy, replicated) samples by FFT.

    Parameters
    ----------
    t_s : ndarray of float64
        Sample times, s, on a grid of step ``dt_s`` (gaps allowed).
    y : ndarray of float64
        Values (any unit ``u``).
    frequency_hz : ndarray of float64
        Regular grid ``k / (M dt_s)``, Hz (integer ``k``, ``M`` at least the span in samples).
    dt_s : float
        Grid step, s.
    copies : int, default 1
        Replicas of the series.
    period_s : float, default 0
        Shift between replicas, s.
    normalization : {"psd", "standard"}
        As astropy's.
    fit_mean : bool, default True
        Floating mean and centred data (astropy ``fit_mean=True, center_data=True``);
        False: neither (``fit_mean=False, center_data=False``).

    Returns
    -------
    ndarray of float64
        Power at each frequency (``u^2`` for ``"psd"``).
    """
    n, m, k = _fft_grid(t_s, frequency_hz, dt_s)
    n_total = y.size * copies
    w = 1.0 / n_total
    yc = y - np.mean(y) if fit_mean else np.asarray(y, dtype=np.float64)
    g1, g2 = _replica_sums(2.0 * np.pi * frequency_hz, copies, period_s)
    ones = _half_spectrum(np.ones(y.size), n, m)
    zy = w * g1 * _at(_half_spectrum(yc, n, m), k, m)
    zw1 = w * g1 * _at(ones, k, m)
    zw2 = w * g2 * _at(ones, 2 * k, m)
    power = _power(zy, zw1, zw2, fit_mean)
    if normalization == "psd":
        return power * 0.5 * n_total
    yy = w * copies * np.sum(yc * yc)
    if normalization == "standard":
        return power / yy
    raise ValueError(f"normalization {normalization!r} not supported (psd, standard)")


def _fft_grid(
    t_s: NDArray[np.float64], frequency_hz: NDArray[np.float64], dt_s: float
) -> tuple[NDArray[np.int64], int, NDArray[np.int64]]:
    """Return the samples' grid indices, the FFT length ``M`` and the frequencies' indices."""
    n = grid_indices(t_s, dt_s)
    if n is None:
        raise ValueError("times are not on a regular grid of step dt_s")
    df = float(frequency_hz[1] - frequency_hz[0]) if frequency_hz.size > 1 else 0.0
    if df <= 0:
        raise ValueError("frequency grid must be regular and increasing")
    m = int(round(1.0 / (df * dt_s)))
    k = np.round(frequency_hz / df).astype(np.int64)
    if np.max(np.abs(frequency_hz / df - k)) > 1e-6 or abs(m * df * dt_s - 1.0) > 1e-9:
        raise ValueError("frequencies must be integer multiples of 1 / (M dt_s)")
    if n[-1] >= m:
        raise ValueError(f"series spans {n[-1] + 1} samples, more than the FFT length {m}")
    return n, m, k


def _half_spectrum(
    values: NDArray[np.float64], n: NDArray[np.int64], m: int
) -> NDArray[np.complex128]:
    """Return the rFFT of the zero-filled series: entry k is sum_i v_i exp(-2 pi j k n_i / M)."""
    x = np.zeros(m)
    x[n] = values
    return scipy.fft.rfft(x)  # entry k: sum_i v_i exp(-2 pi j k n_i / M), k <= M/2


def _at(half: NDArray[np.complex128], kk: NDArray[np.int64], m: int) -> NDArray[np.complex128]:
    """Return sum_i v_i exp(+2 pi j kk n_i / M) for any integers kk (Hermitian symmetry)."""
    kk = kk % m
    upper = kk > m // 2
    vals = half[np.where(upper, m - kk, kk)]
    return np.where(upper, vals, np.conj(vals))


def _replica_sums(
    omega: NDArray[np.float64], copies: int, period_s: float
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Return G(w) and G(2w) of the replicas (``omega`` in rad/s, shift ``period_s`` in s)."""
    g1 = np.ones(omega.size, dtype=complex)
    g2 = np.ones(omega.size, dtype=complex)
    if copies > 1:  # G(w) = sum_r z^r, z = exp(j w P), by repeated multiplication
        z1 = np.exp(1j * omega * period_s)
        z2 = z1 * z1
        p1, p2 = z1.copy(), z2.copy()
        for _ in range(copies - 1):
            g1 += p1
            g2 += p2
            p1 *= z1
            p2 *= z2
    return g1, g2


def _power(
    zy: NDArray[np.complex128],
    zw1: NDArray[np.complex128],
    zw2: NDArray[np.complex128],
    fit_mean: bool,
) -> NDArray[np.float64]:
    """Return the unnormalised periodogram from the weighted data and window sums."""
    ch, sh = zy.real, zy.imag
    c, s = (zw1.real, zw1.imag) if fit_mean else (np.zeros(zy.size), np.zeros(zy.size))
    c2, s2 = zw2.real, zw2.imag
    two_wtau = np.arctan2(s2 - 2.0 * s * c, c2 - (c * c - s * s))
    cw, sw = np.cos(0.5 * two_wtau), np.sin(0.5 * two_wtau)
    c2w, s2w = np.cos(two_wtau), np.sin(two_wtau)
    yc_ = ch * cw + sh * sw
    ys_ = sh * cw - ch * sw
    cc = 0.5 * (1.0 + c2 * c2w + s2 * s2w) - (c * cw + s * sw) ** 2
    ss = 0.5 * (1.0 - c2 * c2w - s2 * s2w) - (s * cw - c * sw) ** 2
    return yc_ * yc_ / cc + ys_ * ys_ / ss
