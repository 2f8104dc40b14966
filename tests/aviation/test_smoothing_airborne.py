"""Aviation utilities (seed numbers): smoothing inflation, Hatch filter, airborne
sigma curves, iono-free factor, Gaussian overbound."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import norm

from psdbound.aviation import (
    alpha_for_inflation,
    alpha_from_tau,
    gaussian_overbound_sigma,
    hatch_filter_variance,
    iono_free_factor,
    qq_ratio,
    running_mean_variance,
    sigma_air_m,
    sigma_multipath_airborne_m,
    sigma_noise_airborne_m,
    smoothing_sigma_factor,
    smoothing_time_ratio,
    smoothing_variance_factor,
)
from psdbound.errors import InputError


# --------------------------------------------------------------------------- aviation
def test_seed_000_alpha_for_variance_inflation_100_and_200():
    """Seed 000 eqs. (12) + (20): phi_alpha(1) = 100 -> alpha 0.57; 200 -> alpha 0.28."""
    a1 = alpha_for_inflation(100.0, n_ref=360)
    a2 = alpha_for_inflation(200.0, n_ref=360)
    assert a1 == pytest.approx(0.57, abs=0.005)  # 0.5668
    assert 0.28 <= a2 <= 0.29  # 0.2865 (seed text: 0.28)
    assert float(smoothing_variance_factor(1, a1)) == pytest.approx(100.0, rel=1e-9)
    assert float(smoothing_variance_factor(360, a1)) == pytest.approx(1.0)
    assert float(smoothing_variance_factor(1000, a1)) == 1.0


def test_seed_001_alpha_for_sigma_inflation_3():
    """Seed 001 M(t) with tau = 100 s: M(1) = 3 -> alpha = 0.84."""
    a = alpha_for_inflation(3.0, n_ref=100, kind="sigma")
    assert a == pytest.approx(0.84, abs=0.005)  # 0.8438
    assert float(smoothing_sigma_factor(1, 0.84)) == pytest.approx(3.0, rel=0.02)
    t = np.arange(1, 101)
    m = smoothing_sigma_factor(t, 0.84)
    assert np.all(np.diff(m) < 0) and m[-1] == pytest.approx(1.0)


def test_running_mean_and_hatch_variance():
    a = 0.57
    k = np.arange(1, 101)
    w = np.arange(200)
    c = a ** np.abs(w[:, None] - w[None, :])
    direct = np.array([c[:n, :n].sum() / n**2 for n in k])
    np.testing.assert_allclose(running_mean_variance(k, a), direct, rtol=1e-12)
    np.testing.assert_allclose(running_mean_variance(k, 0.0), 1.0 / k, rtol=1e-14)
    h = hatch_filter_variance(300, a, time_constant=100)
    np.testing.assert_allclose(h[:100], direct, rtol=1e-12)
    # beyond K: quadratic form of the exact filter weights
    for n in (101, 180, 300):
        wt = np.zeros(n)
        for j in range(1, n + 1):
            kk = min(j, 100)
            wt = (1 - 1 / kk) * wt
            wt[j - 1] += 1 / kk
        i = np.arange(n)
        assert h[n - 1] == pytest.approx(wt @ (a ** np.abs(i[:, None] - i[None, :])) @ wt)
    # seed 000 eq. (19) with the cross term counted twice (and eps_K, alpha^K) agrees
    A, K, kk = 1 - 1 / 100, 100, 200 - 100
    t1 = A ** (2 * kk) * ((1 + a) / (K * (1 - a)) - 2 * a / (K**2 * (1 - a) ** 2) * (1 - a**K))
    t2 = 2 * a * A ** (2 * kk - 1) / K**2 * (1 - (a / A) ** kk) / (1 - a / A) * (1 - a**K) / (1 - a)
    geo = (1 - A ** (2 * kk)) / (1 - A**2)
    t3 = (geo + 2 / (1 - A / a) * ((1 - (a * A) ** kk) / (1 - a * A) - geo)) / K**2
    eq19 = t1 + t2 + t3
    assert h[199] == pytest.approx(eq19, rel=1e-10)


def test_seed_004_smoothing_time_ratio():
    """Seed 004 Table 1: xi = 1.1486, 1.3026, 1.3997 for tau = 60, 30, 15 s, tau_corr 30 s."""
    table = np.array([1.1486, 1.3026, 1.3997])
    exact = smoothing_time_ratio([60.0, 30.0, 15.0], tau_corr_s=30.0)
    np.testing.assert_allclose(exact, table, rtol=0.02)  # 1.1505, 1.3106, 1.4214
    seed = smoothing_time_ratio([60.0, 30.0, 15.0], tau_corr_s=30.0, formula="seed")
    np.testing.assert_allclose(seed, table, atol=6e-5)  # eq. (A6) as printed
    assert smoothing_time_ratio(100.0, tau_corr_s=30.0) == pytest.approx(1.0)
    # finer sampling: the exact ratio converges on the table (continuous limit)
    fine = smoothing_time_ratio([60.0, 30.0, 15.0], tau_corr_s=30.0, dt_s=0.1)
    np.testing.assert_allclose(fine, table, rtol=2e-3)
    # white input: ratio sqrt(100 / tau) up to truncation; steady state of the real smoother
    ss = smoothing_time_ratio([60.0, 30.0, 15.0], tau_corr_s=30.0, formula="steady_state")
    assert np.all(ss > exact)
    with pytest.raises(InputError, match="unknown formula"):
        smoothing_time_ratio(60.0, tau_corr_s=30.0, formula="table")


def test_sigma_curves_and_iono_free_factor():
    assert iono_free_factor() == pytest.approx(2.5883, abs=1e-4)
    f1, f2 = 1575.42e6, 1227.60e6
    assert iono_free_factor(f1, f2) == pytest.approx(math.hypot(f1**2, f2**2) / (f1**2 - f2**2))
    el = np.array([5.0, 30.0, 90.0])
    np.testing.assert_allclose(sigma_multipath_airborne_m(el), 0.13 + 0.53 * np.exp(-el / 10))
    np.testing.assert_allclose(sigma_noise_airborne_m(el), 0.15 + 0.43 * np.exp(-el / 6.9))
    s = sigma_air_m(el)
    ref = iono_free_factor() * np.hypot(sigma_multipath_airborne_m(el), sigma_noise_airborne_m(el))
    np.testing.assert_allclose(s, ref)
    s1 = sigma_air_m(
        el,
        dual_frequency=False,
        multipath_variance_factor=smoothing_variance_factor(1, 0.57),
        noise_variance_factor=smoothing_variance_factor(1, 0.28),
    )
    assert np.all(s1 > 9 * np.hypot(sigma_multipath_airborne_m(el), sigma_noise_airborne_m(el)))
    assert alpha_from_tau(1.78) == pytest.approx(0.57, abs=0.001)


def test_gaussian_overbound():
    p = (np.arange(1, 2001) - 0.5) / 2000
    exact = 2.0 * norm.ppf(p)
    assert gaussian_overbound_sigma(exact) == pytest.approx(2.0, rel=1e-12)
    assert gaussian_overbound_sigma(exact, sigma=2.0) == pytest.approx(1.0, rel=1e-12)
    rng = np.random.default_rng(0)
    x = rng.laplace(0.0, 1.0, 20000)  # std sqrt(2), heavier tails
    sig = gaussian_overbound_sigma(x)
    assert sig > x.std()
    z, xs, _ = qq_ratio(x)
    tail = np.abs(z) >= 1
    assert np.all(xs[tail & (z > 0)] <= sig * z[tail & (z > 0)] + 1e-12)
    assert np.all(xs[tail & (z < 0)] >= sig * z[tail & (z < 0)] - 1e-12)
    with pytest.raises(InputError, match="at least 2"):
        gaussian_overbound_sigma([1.0])
