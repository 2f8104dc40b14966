"""The limits behind the pooled statement, against closed forms and seeded simulations."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats
from scipy.signal import lfilter

import psdbound
from psdbound.errors import InputError
from psdbound.spectra import gm_psd_sampled
from psdbound.spectra.limits import (
    chi_bar_squared_sf,
    design_effect_dof,
    mean_upper_limit,
    spread_upper_limit,
    tolerance_factor,
)


@pytest.mark.parametrize("nu", [2.0, 4.0, 14.0, 100.0])
def test_single_estimate_limit_misses_at_the_stated_rate(nu: float) -> None:
    rng = np.random.default_rng(int(nu))
    a, true = 0.01, 3.0e-6
    est = true * rng.chisquare(nu, 200_000) / nu
    limits = np.array([mean_upper_limit(np.array([s]), np.array([nu]), a) for s in est[:20_000]])
    miss = np.mean(limits < true)
    assert abs(miss - a) < 4 * np.sqrt(a * (1 - a) / limits.size)


def test_pooled_limit_of_unequal_dof_is_exact() -> None:
    rng = np.random.default_rng(3)
    nus, a, misses = np.array([4.0, 10.0, 30.0]), 0.05, 0
    n = 20_000
    for _ in range(n):
        s = rng.chisquare(nus) / nus
        misses += mean_upper_limit(s, nus, a) < 1.0
    assert abs(misses / n - a) < 4 * np.sqrt(a * (1 - a) / n)


def test_design_effect() -> None:
    nu = np.array([10.0, 10.0, 10.0, 10.0])
    assert design_effect_dof(nu, None, 0.5) == 40.0
    assert design_effect_dof(nu, np.array([0, 0, 1, 1]), 1.0) == pytest.approx(20.0)
    assert design_effect_dof(nu, np.array([0, 0, 0, 0]), 0.5) == pytest.approx(16.0)


def test_chi_bar_squared_against_simulation() -> None:
    rng = np.random.default_rng(0)
    t = (np.maximum(rng.normal(size=(200_000, 8)), 0.0) ** 2).sum(axis=1)
    for q in (0.1, 0.01, 0.001):
        assert chi_bar_squared_sf(float(np.quantile(t, 1 - q)), 8) == pytest.approx(q, rel=0.15)


def test_tolerance_factor_is_the_binomial_quantile() -> None:
    z = tolerance_factor(24, 0, 0.05)
    assert stats.binom.sf(0, 24, stats.norm.sf(z)) == pytest.approx(0.05, rel=1e-6)
    assert tolerance_factor(100, 1, 0.05) < tolerance_factor(100, 0, 0.05)


def test_spread_upper_limit_covers_the_true_spread() -> None:
    rng = np.random.default_rng(7)
    a, sigma, n, hits = 0.05, 0.2, 2000, 0
    for _ in range(n):
        se = rng.uniform(0.05, 0.3, 15)
        d = rng.normal(0.0, sigma, 15) + rng.normal(0.0, se)
        hits += spread_upper_limit(d, se, a) >= sigma**2
    assert hits / n >= 1 - a - 3 * np.sqrt(a * (1 - a) / n)


def _gm(rng, n, dt, sigma, tau, wn):
    phi = np.exp(-dt / tau)
    e = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    e[0] = rng.normal(0.0, sigma)
    return lfilter([1.0], [1.0, -phi], e) + rng.normal(0.0, wn, n)


def _covered(res, truths, dt) -> int:
    f = np.geomspace(res.f_min_hz, 0.5 / dt, 300)
    b = res.bound
    bound = gm_psd_sampled(f, b.sigma_gm_m, b.tau_s, dt) + 2 * dt * b.sigma_wn_m**2
    return sum(
        bool(np.all(bound >= gm_psd_sampled(f, s, t, dt) + 2 * dt * w**2)) for s, t, w in truths
    )


def test_bound_series_covers_a_minority_of_slow_strong_reflectors() -> None:
    """22 windows of 3 mm / 30 s and 2 of 6 mm / 200 s: the earlier rules missed the two.

    With a level only per window (no tilt) 6 of these 10 seeds had every window covered,
    with the tests on the bands 7 of 10: the pair's excess lies below the lowest band.
    The shape groups now also test each window's narrow estimate at its lowest Fourier
    frequencies against the others' (``psdbound.spectra.ordinates.low_excess_z``): 10 of
    10 with the ordinates alone, 9 of 10 with the joint test of the ordinates and the
    lowest band (``psdbound.spectra.groups.low_end_p``; seed 6: docs/method/bound.rst).
    The test asserts the stated level (9 of 10 allows Monte-Carlo error).
    """
    dt, n, ok = 1.0, 1800, 0
    for seed in range(10):
        rng = np.random.default_rng(seed)
        truths = [(0.003, 30.0, 0.001)] * 22 + [(0.006, 200.0, 0.001)] * 2
        res = psdbound.bound_series([_gm(rng, n, dt, *t) for t in truths], dt)
        assert res.verdict == "bounded"
        assert res.f_min_hz <= 5.0 / (n * dt)
        ok += _covered(res, truths, dt) == len(truths)
    assert ok >= 9


def test_bound_series_splits_gaps_and_reports_short_stretches() -> None:
    rng = np.random.default_rng(2)
    x = rng.normal(0.0, 0.002, 3000)
    x[1000] = np.nan
    x[1010:1020] = np.nan
    res = psdbound.bound_series([x, rng.normal(0.0, 0.002, 30)], 1.0)
    assert res.n_windows == 2
    assert any("shorter than" in n for n in res.notes)
    assert "bounded" in res.summary()
    with pytest.raises(InputError, match="no stretch"):
        psdbound.bound_series([np.ones(10)], 1.0)
    with pytest.raises(InputError, match="sampling interval"):
        psdbound.bound_series([x], 0.0)


def test_reference_clusters_and_their_correlation() -> None:
    from psdbound.spectra.dependence import overlap_correlation, reference_clusters

    rng = np.random.default_rng(4)
    ref = rng.normal(size=2000)
    series = [
        ref[:1000] + rng.normal(size=1000),
        ref[500:1500] + rng.normal(size=1000),
        rng.normal(size=1000),
    ]
    labels = reference_clusters(
        ["G01-G06", "G02-G06", "G03-G09"],
        np.array([0.0, 500.0, 0.0]),
        np.array([999.0, 1499.0, 999.0]),
    )
    assert labels is not None and labels[0] == labels[1] != labels[2]
    rho, n_pairs = overlap_correlation(series, np.array([0.0, 500.0, 0.0]), 1.0, labels)
    assert n_pairs == 1 and rho == pytest.approx(0.5, abs=0.1)  # var(ref) / (var(ref) + 1)
    assert reference_clusters(["G01", "G02"], np.zeros(2), np.ones(2)) is None


def test_sidereal_repeats_are_one_cluster() -> None:
    from psdbound.constants import SIDEREAL_DAY_S
    from psdbound.spectra.dependence import repeat_clusters

    t0 = np.array([1000.0, 1000.0 + SIDEREAL_DAY_S + 120.0, 1000.0 + 0.5 * SIDEREAL_DAY_S])
    labels = repeat_clusters(["G05", "G05", "G05"], t0, np.full(3, 1800.0))
    assert labels[0] == labels[1] != labels[2]
    assert len(set(repeat_clusters(["G05", "G07"], t0[:2], np.full(2, 1800.0)))) == 2


def test_dependent_windows_loosen_the_group_limit() -> None:
    from psdbound.spectra.bands import band_spectra
    from psdbound.spectra.pooled import pool_bands

    rng = np.random.default_rng(5)
    psds = [psdbound.spectra.estimate_psd(rng.normal(size=1024), 1.0) for _ in range(12)]
    bands = band_spectra(psds, f_min_hz=0.01)
    free = pool_bands(bands)
    tied = pool_bands(bands, clusters=np.zeros(12, dtype=np.int64), cluster_correlation=0.5)
    assert np.all(tied.effective_dof[0] < free.effective_dof[0])
    assert np.all(tied.mean_upper_m2_hz[0] > free.mean_upper_m2_hz[0])
