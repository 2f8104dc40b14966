"""Tapered periodograms, replication, and the periodogram package's import boundary."""

from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest
from astropy.timeseries import LombScargle

import psdbound.periodogram as pg
from psdbound.constants import SIDEREAL_DAY_S
from psdbound.periodogram._ls_gridfft import lombscargle_gridfft

ALLOWED = ("psdbound.errors", "psdbound.common", "psdbound.constants", "psdbound.periodogram")


def test_tapered_lomb_scargle_is_hann_times_series_without_mean_fit():
    rng = np.random.default_rng(3)
    t = np.sort(rng.uniform(0, 20000.0, 900))
    t -= t[0]
    y = np.sin(2 * np.pi * t / 3000.0) + rng.normal(0, 0.1, t.size)
    f = np.arange(1.0 / t[-1], 0.02, 0.25 / t[-1])
    w = np.hanning(t.size)
    w /= np.sqrt(np.mean(w**2))
    expected = LombScargle(t, y * w, fit_mean=False, center_data=False, normalization="psd")
    np.testing.assert_array_equal(pg.tapered_lomb_scargle(t, y, f), expected.power(f))
    np.testing.assert_allclose(np.mean(pg.hann_taper(t.size) ** 2), 1.0)


def test_tapered_lomb_scargle_on_a_grid_uses_the_exact_fft():
    """With dt_s (gappy samples on the grid) the FFT path equals astropy's exact sums."""
    rng = np.random.default_rng(8)
    dt = 30.0
    t = np.arange(2000) * dt
    t = t[rng.uniform(size=t.size) > 0.1]  # 10 % gaps
    t -= t[0]
    y = np.sin(2 * np.pi * t / 5000.0) + rng.normal(0, 0.1, t.size)
    span = t[-1]
    f = np.arange(1.0 / span, 0.98 / (2 * dt), 0.25 / span)
    w = pg.hann_taper(t.size)
    exact = LombScargle(t, y * w, fit_mean=False, center_data=False, normalization="psd")
    np.testing.assert_allclose(
        pg.tapered_lomb_scargle(t, y, f, dt_s=dt),
        exact.power(f, method="slow"),
        rtol=1e-9,
        atol=1e-12,
    )
    # and it was the FFT form (it raises off the grid instead of falling back)
    fft = lombscargle_gridfft(t, y * w, f, dt_s=dt, fit_mean=False)
    np.testing.assert_array_equal(fft, pg.tapered_lomb_scargle(t, y, f, dt_s=dt))


def test_tapered_periodogram_of_a_sine():
    dt, n = 2.0, 4096
    t = np.arange(n) * dt
    f0 = 50.0 / (n * dt)
    f, p = pg.tapered_periodogram(3.0 + np.sin(2 * np.pi * f0 * t), dt)
    assert p[0] == 0.0 and f[1] == pytest.approx(1.0 / (n * dt))
    assert f[np.argmax(p)] == pytest.approx(f0)
    assert np.sum(p) * (f[1] - f[0]) == pytest.approx(0.5, rel=0.02)


def test_replication_and_default_period():
    t, y = np.array([0.0, 12.0, 24.0]), np.array([1.0, 2.0, 3.0])
    tr, yr = pg.replicate_series(t, y, 3, 100.0)
    np.testing.assert_array_equal(tr, [0, 12, 24, 100, 112, 124, 200, 212, 224])
    np.testing.assert_array_equal(yr, np.tile(y, 3))
    # the default replication period is the one sidereal day of psdbound.constants
    import inspect

    period = inspect.signature(pg.lomb_scargle).parameters["period_s"].default
    assert period == SIDEREAL_DAY_S


def test_periodogram_imports_only_low_level_packages():
    root = Path(pg.__file__).parent
    for path in root.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                names = [node.module or ""]
            for name in names:
                if name.startswith("psdbound"):
                    assert name.startswith(ALLOWED), f"{path.name} imports {name}"
                else:
                    top = name.split(".")[0]
                    allowed = ("__future__", "typing", "numpy", "scipy", "astropy")
                    assert top in allowed, (path.name, name)
