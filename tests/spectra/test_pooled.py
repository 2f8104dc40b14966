"""The pooled bound: coverage of known truths, outlier groups, tightening with data."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

import psdbound
from psdbound.errors import InputError
from psdbound.spectra import estimate_psd, gm_psd_sampled
from psdbound.spectra.bands import band_spectra, merge_bands
from psdbound.spectra.pooled import MIN_GROUP_DOF, fit_pooled_bound, group_bands, pool_bands

DT, N, TAU = 30.0, 240, 60.0


def _gm(rng: np.random.Generator, sigma: float, n: int = N) -> np.ndarray:
    phi = np.exp(-DT / TAU)
    e = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    e[0] = rng.normal(0.0, sigma)
    return lfilter([1.0], [1.0, -phi], e) + rng.normal(0.0, 0.001, n)


def _truth(f: np.ndarray, sigma: float) -> np.ndarray:
    return gm_psd_sampled(f, sigma, TAU, DT) + 2 * DT * 1e-6


def _windows(seed: int, m: int, frac_high: float = 0.0, method: str = "multitaper"):
    rng = np.random.default_rng(seed)
    sig = np.where(rng.random(m) < frac_high, 0.004, 0.002)
    return [estimate_psd(_gm(rng, s), DT, method=method) for s in sig]


def _covers(b, sigma: float) -> tuple[bool, float]:
    f = np.geomspace(b.f_min_hz, 0.5 / DT, 200)
    ratio = b.psd(f) / _truth(f, sigma)
    return bool(ratio.min() >= 1.0), b.total_variance_m2 / (sigma**2 + 1e-6)


def test_homogeneous_windows_covered_and_tight() -> None:
    results = [
        _covers(fit_pooled_bound(_windows(s, 60), DT, f_min_hz=2 / (N * DT))[0], 0.002)
        for s in range(20)
    ]
    covered = sum(c for c, _ in results)
    ratios = [r for _, r in results]
    assert covered >= 18  # stated 95 %: 19/20 expected; 18 allows Monte-Carlo error
    # covering every window's truth (not the mean PSD) costs: 2.0-2.3 measured (seeds 0-19),
    # against 1.6 for the earlier mean-only limits, which missed windows that differed
    assert np.median(ratios) <= 2.5


def _sigmas(seed: int, m: int, frac_high: float) -> np.ndarray:
    """The sigmas :func:`_windows` draws first from its generator."""
    return np.where(np.random.default_rng(seed).random(m) < frac_high, 0.004, 0.002)


def test_minority_of_high_windows_is_covered_by_its_own_levels() -> None:
    """5 % of 100 windows at twice the sigma: the statement's count, not the high truth.

    The statement allows floor(0.01 M) = 1 window above the bound; a run with a single high
    window may leave it out (seeds 4, 8 and 22 of 0..23 draw one).
    """
    kept = 0
    for seed in range(24):
        b, _, limits = fit_pooled_bound(_windows(seed, 100, 0.05), DT, f_min_hz=2 / (N * DT))
        above = sum(not _covers(b, s)[0] for s in _sigmas(seed, 100, 0.05))
        kept += above <= int(np.floor(0.01 * 100))
        if seed == 0:  # same shape, higher level: one group, the level term reaches them
            assert limits.n_groups == 1
            assert np.all(limits.window_term_log[0] > np.log(3.0))
    assert kept >= 22  # stated 95 %: 22.8 expected at least; 22 allows Monte-Carlo error


def test_bound_tightens_as_windows_accumulate() -> None:
    few = [
        _covers(fit_pooled_bound(_windows(s, 10), DT, f_min_hz=2 / (N * DT))[0], 0.002)[1]
        for s in range(8)
    ]
    many = [
        _covers(fit_pooled_bound(_windows(s, 150), DT, f_min_hz=2 / (N * DT))[0], 0.002)[1]
        for s in range(8)
    ]
    assert np.median(many) < np.median(few)


def test_estimators_agree_within_1p3_in_variance() -> None:
    var = []
    for method in ("multitaper", "welch", "blackman-tukey"):
        b, _, _ = fit_pooled_bound(_windows(3, 80, method=method), DT, f_min_hz=2 / (N * DT))
        var.append(b.total_variance_m2)
    assert max(var) / min(var) <= 1.3


def test_band_dof_and_merging() -> None:
    psds = _windows(1, 5)
    bands = band_spectra(psds, f_min_hz=2 / (N * DT), bands_per_decade=10)
    assert np.all(bands.dof[np.isfinite(bands.psd_m2_hz)] >= 14.0 - 1e-9)  # at least nu_0 = 2K
    merged = merge_bands(bands, min_window_dof=40.0)
    assert merged.centres_hz.size < bands.centres_hz.size
    have = merged.dof > 0
    assert np.median(merged.dof[have]) >= 40.0


def test_small_group_bands_are_merged_by_width() -> None:
    """A one-window group's bands reach MIN_GROUP_DOF, counted from the merged width."""
    bands = band_spectra(_windows(1, 1), f_min_hz=2 / (N * DT), bands_per_decade=10)
    merged, index = group_bands(bands, np.array([0]))
    have = merged.dof[0] > 0
    width = np.diff(merged.edges_hz)
    assert merged.centres_hz.size < bands.centres_hz.size
    # the width's degrees of freedom, not the parts' sum (narrow bands share ordinates)
    assert np.all(merged.dof[0, have] <= np.maximum(2 * N * DT * width[have], 14.0) + 1e-9)
    assert np.all(merged.dof[0, have][:-1] >= MIN_GROUP_DOF - 1e-9)
    lo = bands.edges_hz[:-1]
    inside = index >= 0
    assert np.all(merged.edges_hz[index[inside]] <= lo[inside] * (1 + 1e-12))
    assert np.all(merged.edges_hz[index[inside] + 1] > lo[inside])
    five = band_spectra(_windows(1, 5), f_min_hz=2 / (N * DT), bands_per_decade=10)
    kept, identity = group_bands(five, np.arange(5))  # 5 x 14 >= 40: the common bands
    assert np.array_equal(kept.edges_hz, five.edges_hz)
    data = five.dof.sum(axis=0) > 0  # the lowest bands lie below every window's resolution
    assert np.array_equal(identity, np.where(data, np.arange(data.size), -1))


def test_one_window_limits_cover_at_the_stated_rate() -> None:
    """White noise, one window: every band's limit above the flat truth in >= 97.5 % of runs.

    The group-level share of 1 - confidence_level is (1 - 0.95) / 2; a miss in any band counts.
    """
    rng = np.random.default_rng(11)
    sigma, n, runs, miss = 0.002, 512, 400, 0
    truth = 2 * DT * sigma**2
    for _ in range(runs):
        psd = estimate_psd(rng.normal(0.0, sigma, n), DT)
        limits = pool_bands(band_spectra([psd], f_min_hz=2 / (n * DT)))
        up = limits.upper_m2_hz[0]
        miss += bool(np.any(up[np.isfinite(up)] < truth))
        assert limits.band_span_hz is not None
    rate, a = miss / runs, 0.025
    assert rate <= a + 3 * np.sqrt(a * (1 - a) / runs)


@pytest.mark.parametrize("kw", [{"confidence_level": 1.0}, {"coverage": 0.4}, {"shape_alpha": 0.0}])
def test_bad_options_are_named(kw: dict) -> None:
    bands = band_spectra(_windows(0, 4), f_min_hz=2 / (N * DT))
    with pytest.raises(InputError, match=next(iter(kw)).split("_")[0]):
        pool_bands(bands, **kw)


def test_f_min_must_lie_below_nyquist() -> None:
    with pytest.raises(InputError, match="Nyquist"):
        band_spectra(_windows(0, 2), f_min_hz=1.0)


def test_power_response_is_undone_and_too_weak_refused() -> None:
    psds = _windows(2, 3)
    plain = band_spectra(psds, f_min_hz=2 / (N * DT))
    undone = band_spectra(
        psds, f_min_hz=2 / (N * DT), power_response=lambda f: np.full(f.shape, 0.8)
    )
    have = np.isfinite(plain.psd_m2_hz)
    np.testing.assert_allclose(undone.psd_m2_hz[have], plain.psd_m2_hz[have] / 0.8)
    with pytest.raises(InputError, match="filter passes only 0.40"):
        band_spectra(psds, f_min_hz=2 / (N * DT), power_response=lambda f: np.full(f.shape, 0.4))


def test_pooled_bound_is_stated_from_the_lowest_band_edge_to_nyquist() -> None:
    b, bands, _ = fit_pooled_bound(_windows(4, 20), DT, f_min_hz=2 / (N * DT))
    assert b.f_min_hz == pytest.approx(bands.edges_hz[0]) and b.f_max_hz == pytest.approx(0.5 / DT)


def test_statement_names_the_groups_on_merged_bands() -> None:
    """A strong Gauss-Markov window among white-noise ones: its group's bands are merged."""
    rng = np.random.default_rng(3)
    xs = [rng.normal(0.0, 0.001, 512) for _ in range(12)]
    phi = np.exp(-1.0 / 50.0)
    e = rng.normal(0.0, 0.01 * np.sqrt(1 - phi**2), 512)
    xs.append(lfilter([1.0], [1.0, -phi], e) + rng.normal(0.0, 0.001, 512))
    res = psdbound.bound_series(xs, 1.0)
    g = int(res.limits.groups[-1])
    assert g > 0 and "merged bands" in res.covers
    span = res.limits.band_span_hz[g]
    assert span[0, 1] > res.bands.edges_hz[1]  # wider than the common lowest band
    f = np.geomspace(res.f_min_hz, 0.5, 300)
    assert np.all(res.bound.sampled_psd(f) >= gm_psd_sampled(f, 0.01, 50.0, 1.0) + 2e-6)
