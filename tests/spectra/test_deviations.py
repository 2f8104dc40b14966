"""The windows' deviations from their group's shape, and the smoothed filter response.

Both are computed for all windows at once; each is checked here against the
per-window computation it replaces and against closed forms.
"""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.spectra.bands import smoothed_response, smoothed_responses
from psdbound.spectra.limits import window_deviations


def _reference_backfit(z, v, ok, x, model):
    """Per-window weighted least squares, alternated with the band levels (the definition)."""
    m, n_b = z.shape
    w = np.where(ok, 1.0 / np.where(ok, v, 1.0), 0.0)
    zz = np.where(ok, z, 0.0)
    full = np.column_stack([np.ones_like(x), x])
    n_par = [2 if model == "tilt" and k >= 3 else 1 for k in ok.sum(axis=1)]
    mu = (w * zz).sum(axis=0) / w.sum(axis=0)
    coef, cov, dev = np.zeros((m, 2)), np.zeros((m, 2, 2)), np.zeros((m, n_b))
    for _ in range(50):
        for i in range(m):
            p, rows = n_par[i], ok[i]
            d = full[rows, :p]
            c = np.linalg.pinv((d.T * w[i, rows]) @ d)
            coef[i, :p] = c @ ((d.T * w[i, rows]) @ (zz[i, rows] - mu[rows]))
            cov[i, :p, :p] = c
        coef -= coef.mean(axis=0)
        new = coef @ full.T
        mu_new = (w * (zz - new)).sum(axis=0) / w.sum(axis=0)
        done = np.allclose(new, dev, atol=1e-9) and np.allclose(mu_new, mu, atol=1e-9)
        dev, mu = new, mu_new
        if done:
            break
    return mu, dev, coef, cov


@pytest.mark.parametrize("model", ["tilt", "level"])
@pytest.mark.parametrize("seed", range(6))
def test_deviations_equal_the_per_window_backfit(model: str, seed: int) -> None:
    rng = np.random.default_rng(seed)
    m, n_b = int(rng.integers(2, 25)), int(rng.integers(3, 20))
    z = rng.normal(size=(m, n_b))
    v = rng.uniform(0.05, 0.5, (m, n_b))
    ok = rng.random((m, n_b)) > 0.3
    ok[0, :2] = True
    ok[0, 2:] = False  # one window with two bands: a level only, beside tilted ones
    x = np.linspace(-1.0, 1.0, n_b)
    got = window_deviations(z, v, ok, x, model=model)
    mu, dev, coef, cov = _reference_backfit(z, v, ok, x, model)
    np.testing.assert_allclose(got.mu, mu, rtol=0, atol=1e-12)
    np.testing.assert_allclose(got.dev, dev, rtol=0, atol=1e-12)
    np.testing.assert_allclose(got.coef, coef, rtol=0, atol=1e-12)
    np.testing.assert_allclose(got.cov, cov, rtol=0, atol=1e-12)
    assert got.n_params[0] == 1


def test_deviations_recover_exact_levels_and_tilts() -> None:
    x = np.linspace(-1.0, 1.0, 12)
    shape = np.sin(3.0 * x)
    levels, tilts = np.array([0.3, -0.1, -0.2]), np.array([0.05, -0.15, 0.1])
    z = shape + levels[:, None] + tilts[:, None] * x
    got = window_deviations(z, np.full(z.shape, 0.1), np.ones(z.shape, bool), x, model="tilt")
    np.testing.assert_allclose(got.coef, np.column_stack([levels, tilts]), atol=1e-9)
    np.testing.assert_allclose(got.mu, shape, atol=1e-9)


def test_smoothed_responses_equal_one_call_each() -> None:
    def response(f: np.ndarray) -> np.ndarray:
        return (f / 0.01) ** 8 / (1.0 + (f / 0.01) ** 8)

    rng = np.random.default_rng(3)
    fs = [np.sort(rng.uniform(0.0, 0.5, n)) for n in (0, 5, 40)]
    ws = [0.002, 0.0, 0.004]
    many = smoothed_responses(response, fs, ws)
    for f, w, got in zip(fs, ws, many, strict=True):
        np.testing.assert_allclose(got, smoothed_response(response, f, w), rtol=1e-15)
    np.testing.assert_array_equal(many[1], response(fs[1]))  # W = 0: the point value


def test_smoothed_responses_in_bounded_calls(monkeypatch: pytest.MonkeyPatch) -> None:
    """Many windows are evaluated in calls of at most about _RESPONSE_POINTS (memory)."""
    import psdbound.spectra.bands as bands_module

    sizes: list[int] = []

    def response(f: np.ndarray) -> np.ndarray:
        sizes.append(f.size)
        return (f / 0.01) ** 8 / (1.0 + (f / 0.01) ** 8)

    rng = np.random.default_rng(4)
    fs = [np.sort(rng.uniform(0.0, 0.5, n)) for n in (30, 50, 10, 70, 20)]
    ws = [0.002] * len(fs)
    whole = smoothed_responses(response, fs, ws)
    assert sizes == [180 * 17]
    sizes.clear()
    monkeypatch.setattr(bands_module, "_RESPONSE_POINTS", 60 * 17)
    chunked = smoothed_responses(response, fs, ws)
    assert sizes == [80 * 17, 80 * 17, 20 * 17]  # a call closes once it reaches the size
    for a, b in zip(whole, chunked, strict=True):
        np.testing.assert_array_equal(a, b)


def test_smoothed_response_of_a_line_is_its_value() -> None:
    f = np.array([0.1, 0.2, 0.3])
    got = smoothed_response(lambda g: 2.0 + 5.0 * g, f, 0.05)  # symmetric average, f > W
    np.testing.assert_allclose(got, 2.0 + 5.0 * f, rtol=1e-12)
