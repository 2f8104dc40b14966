"""Lomb-Scargle front (psdbound.periodogram): exact grid-FFT against astropy, grid, scaling."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError
from psdbound.periodogram import (
    frequency_grid,
    lomb_scargle,
    to_one_sided_density,
)

DT_S = 12.0
N_DAY = int(np.ceil(SIDEREAL_DAY_S / DT_S))  # 7181 epochs in one sidereal day


@pytest.mark.parametrize("copies", [1, 7])
def test_gridfft_matches_astropy_exact(copies):
    rng = np.random.default_rng(20 + copies)
    keep = np.zeros(N_DAY, dtype=bool)
    for start, length in ((100, 1500), (3000, 2200), (6000, 900)):
        keep[start : start + length] = True
    t = 1.26e9 + DT_S * np.flatnonzero(keep)
    y = np.cumsum(rng.normal(0, 0.01, t.size)) + np.sin(t / 5000.0)
    f = frequency_grid(DT_S, copies * SIDEREAL_DAY_S)
    sub = np.unique(np.linspace(0, f.size - 1, 300).astype(int))
    ours = lomb_scargle(t, y, f, method="gridfft", copies=copies)[sub]
    exact = lomb_scargle(t, y, f[sub], method="astropy", copies=copies, astropy_method="cython")
    np.testing.assert_allclose(ours, exact, rtol=1e-7)
    # auto picks the grid method here and falls back to astropy for irregular times
    np.testing.assert_allclose(lomb_scargle(t, y, f, copies=copies)[sub], ours, rtol=1e-12)
    jitter = t + rng.uniform(-1, 1, t.size)
    a = lomb_scargle(jitter, y, f[sub], copies=copies)
    assert np.all(np.isfinite(a))


def test_frequency_grid_and_density_scaling():
    f = frequency_grid(DT_S, 7 * SIDEREAL_DAY_S)
    assert f[0] == pytest.approx(1 / (7 * SIDEREAL_DAY_S), rel=1e-4)
    assert f[-1] < 0.99 / (2 * DT_S) + 1e-12 and f[-1] > 0.98 / (2 * DT_S)
    # white noise: the one-sided density integrates to the variance
    rng = np.random.default_rng(5)
    t = DT_S * np.arange(N_DAY)
    y = rng.normal(0, 0.3, t.size)
    fg = frequency_grid(DT_S, SIDEREAL_DAY_S, nyquist_fraction=1.0)
    s = to_one_sided_density(lomb_scargle(t, y, fg), DT_S)
    assert np.sum(s) * (fg[1] - fg[0]) == pytest.approx(np.var(y), rel=0.02)


def test_lomb_scargle_bad_input():
    t = DT_S * np.arange(50000.0)
    with pytest.raises(InputError, match="copies would overlap"):
        lomb_scargle(t, np.ones(t.size), [1e-3, 2e-3], copies=7)
    with pytest.raises(InputError, match="at least 3 samples"):
        lomb_scargle([0.0, 12.0], [1.0, 2.0], [1e-3])
    with pytest.raises(InputError, match="finite"):
        lomb_scargle([0.0, 12.0, 24.0], [1.0, np.nan, 2.0], [1e-3])
