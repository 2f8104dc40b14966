"""The multitaper expectation's lag kernels against their definitions, term by term.

:func:`psdbound.spectra.expectation.lag_kernels` and ``far_lag_kernels`` use
closed forms (the Dirichlet sum of a band's cosines, the mean removal from
partial sums); these tests rebuild each kernel from its definition, the
zero-padded autocorrelation of every tapered, mean-removed complex exponential
of the band, and compare.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import windows

from psdbound.spectra.expectation import (
    far_lag_kernels,
    gm_band_expectation,
    lag_kernels,
    mean_cosine,
)


def _kernel_by_definition(n: int, js: np.ndarray, nw: float, *, mean_removed: bool) -> np.ndarray:
    """``w(l)`` from ``c(l) = sum_t a_{t+l} conj(a_t)``, averaged over tapers and ordinates."""
    tapers = np.atleast_2d(windows.dpss(n, nw, Kmax=max(1, int(np.floor(2.0 * nw)) - 1)))
    t = np.arange(n)
    acc = np.zeros(n)
    for j in js:
        for h in tapers:
            a = h * np.exp(-2j * np.pi * j * t / n)
            if mean_removed:
                a = a - a.mean()
            c = np.fft.ifft(np.abs(np.fft.fft(a, 2 * n)) ** 2)[:n].real
            acc += np.where(t == 0, c, 2.0 * c)
    return acc / (len(js) * tapers.shape[0])


def _check_kernels(
    got: tuple[np.ndarray, np.ndarray],
    n: int,
    nw: float,
    lo: np.ndarray,
    hi: np.ndarray,
    *,
    mean_removed: bool,
) -> None:
    """Every band's kernel equals its definition over the band's ordinates (dt = 1 s)."""
    kernels, has = got
    assert has.all()
    js_all = np.arange(1, n // 2 + 1)
    for b in range(lo.size):
        js = js_all[(js_all / n >= lo[b]) & (js_all / n < hi[b])]
        ref = _kernel_by_definition(n, js, nw, mean_removed=mean_removed)
        np.testing.assert_allclose(kernels[b], ref, rtol=0, atol=1e-12 * np.abs(ref).max())


@pytest.mark.parametrize(
    ("j0", "j1", "n"), [(1, 1, 10), (3, 17, 100), (50, 400, 1800), (900, 1800, 3600)]
)
def test_mean_cosine_is_the_band_average(j0: int, j1: int, n: int) -> None:
    js = np.arange(j0, j1 + 1)
    direct = np.mean(np.cos(2.0 * np.pi * np.outer(js, np.arange(n)) / n), axis=0)
    np.testing.assert_allclose(mean_cosine(j0, j1, n), direct, rtol=0, atol=1e-12)


@pytest.mark.parametrize(("n", "nw"), [(64, 4.0), (300, 4.0), (1000, 1.5), (1200, 4.0)])
def test_exact_kernels_match_their_definition(n: int, nw: float) -> None:
    w = nw / n  # smoothing half-width, dt = 1 s
    lo = np.array([1.0, 3.0, 5.0, 9.0]) / n
    hi = np.array([3.0, 5.0, 9.0, 20.0]) / n
    _check_kernels(lag_kernels(n, 1.0, lo, hi, nw=nw), n, nw, lo, hi, mean_removed=True)
    assert lo[0] < 12.0 * w  # the bands the exact form is for


@pytest.mark.parametrize(("n", "nw"), [(256, 4.0), (1000, 4.0)])
def test_far_kernels_match_their_definition(n: int, nw: float) -> None:
    lo = np.array([0.06, 0.2])  # Hz at dt = 1 s: cycles per sample
    hi = np.array([0.08, 0.45])
    _check_kernels(far_lag_kernels(n, 1.0, lo, hi, nw=nw), n, nw, lo, hi, mean_removed=False)


def test_far_kernels_agree_with_exact_ones_far_from_zero() -> None:
    """50 smoothing half-widths from 0 Hz the mean removal changes the expectation by < 1e-3."""
    n, nw = 2000, 4.0
    lo, hi = np.array([0.1]), np.array([0.125])
    taus = np.array([5.0, 30.0, 300.0])
    exact = gm_band_expectation(lag_kernels(n, 1.0, lo, hi, nw=nw)[0], taus, 1.0)
    far = gm_band_expectation(far_lag_kernels(n, 1.0, lo, hi, nw=nw)[0], taus, 1.0)
    np.testing.assert_allclose(far, exact, rtol=1e-3)
