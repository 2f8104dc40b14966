"""What a multitaper band average expects: the exact mean of the estimate of a mean-removed window.

A multitaper estimate at ``f`` is not the PSD at ``f``: each eigenspectrum of
the mean-removed window is ``|sum_t a_t x_t|^2`` with ``a_t = h_t e^{-i 2 pi f t}
- H(f) / N`` (the taper ``h`` and the subtraction of the window's mean), so its
expectation is ``sum_l R(l) c(l)``, ``c`` the autocorrelation of ``a`` and ``R``
the process's autocovariance (Percival and Walden 1993, section 7.3). Near the
lowest resolved frequencies of a steep spectrum that expectation lies well
above the band-mean PSD (the taper averages over ``f +- W``) and below the
boxcar average over ``f +- W`` (the mean removal empties the zero
frequency): for a Gauss-Markov process of time constant 300 s in windows of
1200 s at 1 s, twice the band-mean PSD at 1.25 W, 1.18 times at 2.2 W, 1.06
times at 10 W (``tests/spectra/test_intervals.py``).

:func:`lag_kernels` and :func:`gm_band_expectation` give, for a window of
``N`` samples and the default multitaper (``K = floor(2 NW) - 1`` DPSS tapers),
the expected band average of a unit-variance sampled Gauss-Markov process.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray
from scipy import fft as sp_fft

from psdbound.spectra._multitaper import dpss_tapers

__all__ = ["far_lag_kernels", "gm_band_expectation", "lag_kernels", "mean_cosine"]

#: Bands from this many smoothing half-widths up use :func:`far_lag_kernels` (the mean
#: removal no longer matters there); below it :func:`lag_kernels`.
EXACT_BELOW = 12.0


def _tapers(n: int, nw: float) -> NDArray[np.float64]:
    """Return the default multitaper's DPSS tapers, ``K = max(1, floor(2 NW) - 1)`` (read-only)."""
    return dpss_tapers(n, nw, max(1, int(np.floor(2.0 * nw)) - 1))[0]


def _band_ordinates(
    n: int, dt_s: float, lo_hz: NDArray[np.float64], hi_hz: NDArray[np.float64]
) -> Iterator[tuple[int, NDArray[np.int64]]]:
    """Each band with Fourier frequencies ``lo <= j / (n dt) < hi``: (band index, the j)."""
    j_all = np.arange(1, n // 2 + 1)
    f_all = j_all / (n * dt_s)
    for b, (lo, hi) in enumerate(zip(lo_hz, hi_hz, strict=True)):
        js = j_all[(f_all >= lo) & (f_all < hi)]
        if js.size:
            yield b, js


def lag_kernels(
    n: int, dt_s: float, lo_hz: NDArray[np.float64], hi_hz: NDArray[np.float64], *, nw: float
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Lag weights of each band's expected multitaper average (mean-removed window).

    With ``g_t = h_t e^{-i 2 pi f t}`` and the window's mean ``m = sum_t g_t / N``
    removed, ``c(l) = sum_t (g_{t+l} - m) conj(g_t - m)`` splits into the tapers'
    autocorrelation turned to ``f`` (``e^{-i 2 pi f l} rho_h(l)``, in closed form
    over a band's ordinates, :func:`mean_cosine`) and the mean's terms, partial sums
    of ``g`` (:func:`_mean_terms`): O(N) per ordinate and taper, where a zero-padded
    FFT of every ``a_t = g_t - m`` cost O(N log N) with a large constant (9 s of 13 s
    of :func:`psdbound.bound_series` on one stretch of 200,000 samples).

    Parameters
    ----------
    n : int
        Window length, samples.
    dt_s : float
        Sampling interval, seconds.
    lo_hz, hi_hz : ndarray, shape (B,)
        Band edges, Hz (a band holds the Fourier frequencies ``lo <= j / (n dt) < hi``).
    nw : float
        Time-half-bandwidth product; ``K = max(1, floor(2 NW) - 1)`` tapers.

    Returns
    -------
    kernels : ndarray, shape (B, n)
        ``w_b(l)`` such that the expected band average of the one-sided
        estimate is ``2 dt sum_l R(l) w_b(l)`` for an autocovariance ``R``
        (lag ``l`` samples; ``w_b(0) = c(0)``, ``w_b(l) = 2 Re c(l)``).
    has : ndarray of bool, shape (B,)
        Bands that hold at least one Fourier frequency.
    """
    tapers = _tapers(n, nw)
    rho = _taper_autocorrelation(tapers)
    lags = np.arange(n)
    out = np.zeros((lo_hz.size, n))
    has = np.zeros(lo_hz.size, dtype=bool)
    for b, js in _band_ordinates(n, dt_s, lo_hz, hi_hz):
        has[b] = True
        phase = np.exp(-2j * np.pi * np.outer(js, lags) / n)  # (J, n)
        mean_part = sum(_mean_terms(h[None, :] * phase).mean(axis=0) for h in tapers)
        re_c = rho * mean_cosine(int(js[0]), int(js[-1]), n) + mean_part / tapers.shape[0]
        out[b] = 2.0 * re_c
        out[b, 0] = re_c[0]
    return out, has


def _mean_terms(g: NDArray[np.complex128]) -> NDArray[np.float64]:
    """Real part of what removing the mean adds to ``c(l)``, per row of ``g`` (shape (J, n)).

    ``-Re(conj(m) (sum_{s >= l} g_s + sum_{t <= n-1-l} g_t)) + (n - l) |m|^2``, from the
    prefix sums ``P`` of ``g``.
    """
    n = g.shape[1]
    p = np.cumsum(g, axis=1)
    total = p[:, -1]
    m = total / n
    suffix = total[:, None] - np.concatenate([np.zeros((g.shape[0], 1)), p[:, :-1]], axis=1)
    x = suffix + p[:, ::-1]
    return -(np.conj(m)[:, None] * x).real + (n - np.arange(n))[None, :] * (np.abs(m) ** 2)[:, None]


def _taper_autocorrelation(tapers: NDArray[np.float64]) -> NDArray[np.float64]:
    """Return the tapers' mean autocorrelation ``rho(l) = mean_h sum_t h_{t+l} h_t``, ``l < n``."""
    n = tapers.shape[1]
    spec = sp_fft.rfft(tapers, 2 * n, axis=1)
    return np.mean(sp_fft.irfft(np.abs(spec) ** 2, 2 * n, axis=1)[:, :n], axis=0)


def gm_band_expectation(
    kernels: NDArray[np.float64], taus_s: NDArray[np.float64], dt_s: float
) -> NDArray[np.float64]:
    """Return the expected band averages of a unit-variance sampled Gauss-Markov process.

    Parameters
    ----------
    kernels : ndarray, shape (B, n)
        From :func:`lag_kernels`.
    taus_s : ndarray, shape (T,)
        Time constants, seconds.
    dt_s : float
        Sampling interval, seconds.

    Returns
    -------
    ndarray, shape (T, B)
        ``2 dt sum_l phi^l w_b(l)``, ``phi = exp(-dt / tau)``, m^2/Hz per m^2.
    """
    lags = np.arange(kernels.shape[1])
    phi = np.exp(-dt_s / np.asarray(taus_s, dtype=float))
    acf = phi[:, None] ** lags[None, :]
    return 2.0 * dt_s * acf @ kernels.T


def far_lag_kernels(
    n: int, dt_s: float, lo_hz: NDArray[np.float64], hi_hz: NDArray[np.float64], *, nw: float
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Lag weights of the bands far from 0 Hz, where the window's mean removal does not matter.

    There ``c(l) = e^{-i 2 pi f l} rho(l)`` with ``rho`` the tapers' mean
    autocorrelation, so ``w_b(l) = 2 rho(l) mean_j cos(2 pi f_j l)``: exact,
    leakage from the spectral peak at 0 Hz included (a spectral window cut at
    a few ``W`` missed 3.7 % at 14 W for a steep spectrum), and cheap. Same
    returns as :func:`lag_kernels`.
    """
    rho = _taper_autocorrelation(_tapers(n, nw))
    out = np.zeros((lo_hz.size, n))
    has = np.zeros(lo_hz.size, dtype=bool)
    for b, js in _band_ordinates(n, dt_s, lo_hz, hi_hz):
        has[b] = True
        out[b] = 2.0 * rho * mean_cosine(int(js[0]), int(js[-1]), n)
        out[b, 0] = rho[0]
    return out, has


def mean_cosine(j0: int, j1: int, n: int) -> NDArray[np.float64]:
    """Return ``mean_j cos(2 pi j l / n)`` over ``j = j0..j1``, for every lag ``l = 0..n-1``.

    The Dirichlet sum in closed form, ``cos((j0 + j1) theta / 2) sin(J theta / 2) /
    (J sin(theta / 2))`` with ``theta = 2 pi l / n`` and ``J = j1 - j0 + 1`` (1 at
    ``l = 0``): O(n) per band instead of the O(J n) sum over the band's ordinates, which
    for one day at 1 Hz (a band of 10,000 ordinates) took minutes.

    Parameters
    ----------
    j0, j1 : int
        First and last Fourier index of the band (``j0 <= j1``).
    n : int
        Window length, samples.

    Returns
    -------
    ndarray, shape (n,)
    """
    count = j1 - j0 + 1
    half = np.pi * np.arange(n) / n  # theta / 2
    out = np.ones(n)
    l_pos = half[1:]  # sin(theta / 2) > 0 for 0 < l < n
    out[1:] = np.cos((j0 + j1) * l_pos) * np.sin(count * l_pos) / (count * np.sin(l_pos))
    return out
