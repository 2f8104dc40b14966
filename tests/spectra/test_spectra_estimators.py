"""PSD estimators: Blackman-Tukey, Welch, multitaper (psdbound.spectra.estimators).

Simulated data only: white noise, and first-order Gauss-Markov (AR(1), exact
stationary start) + white noise at 1 Hz, checked against the closed-form
sampled PSD of psdbound.spectra.models.

Note on Blackman-Tukey with every lag (the thesis's choice, the default): the
recorded degrees of freedom ``2N / sum w^2`` are ~1.14, so its 95 % interval
spans a factor of ~5000 and coverage is trivially high; the estimate itself
behaves like a periodogram (empirical nu ~ 2). The smoothed tests (averaging
realisations and adjacent bins) are what show it is unbiased.
"""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import numpy as np
import pytest
from scipy import signal, stats
from scipy.signal import windows

from psdbound.errors import InputError
from psdbound.spectra.estimators import METHODS, MIN_SAMPLES, PSDEstimate, estimate_psd
from psdbound.spectra.models import gm_psd_sampled, white_psd

# (method, options); ids used in test names and printed output.
CASES = [
    pytest.param("blackman-tukey", {}, id="bt"),
    pytest.param("blackman-tukey", {"max_lag_fraction": 0.1}, id="bt-M0.1"),
    pytest.param("welch", {}, id="welch"),
    pytest.param("multitaper", {}, id="mt"),
    pytest.param("multitaper", {"adaptive": True}, id="mt-adaptive"),
]

# (sigma_GM m, tau s, sigma_WN m): thesis DA, thesis DF, short correlation time.
GM_SETS = [
    pytest.param((0.005, 45.0, 0.002), id="DA"),
    pytest.param((0.04, 70.0, 0.009), id="DF"),
    pytest.param((0.01, 10.0, 0.001), id="short"),
]


def simulate_gm_wn(n, sigma, tau_s, sigma_wn, dt_s, rng):
    """AR(1) sampled Gauss-Markov (stationary start) plus white noise, metres."""
    phi = np.exp(-dt_s / tau_s)
    u = rng.normal(0.0, sigma * np.sqrt(1.0 - phi**2), n)
    u[0] = rng.normal(0.0, sigma)
    return signal.lfilter([1.0], [1.0, -phi], u) + rng.normal(0.0, sigma_wn, n)


@lru_cache(maxsize=8)
def realisations(params, n, count, seed):
    rng = np.random.default_rng(seed)
    xs = np.array([simulate_gm_wn(n, *params, 1.0, rng) for _ in range(count)])
    xs.setflags(write=False)
    return xs


def model_psd(f, params, dt_s=1.0):
    sigma, tau, sigma_wn = params
    return gm_psd_sampled(f, sigma, tau, dt_s) + white_psd(f, sigma_wn, dt_s)


def resolution_hz(est):
    """Frequency resolution of an estimate, Hz (used to skip the lowest bins)."""
    if est.method == "welch":
        return 1.0 / (est.params["nperseg"] * est.dt_s)
    if est.method == "multitaper":
        return 2.0 * est.params["bandwidth_hz"]
    return 1.0 / (est.params["max_lag"] * est.dt_s)


# --------------------------------------------------------------------------- white noise


@pytest.mark.parametrize(("method", "options"), CASES)
def test_white_noise_level_and_parseval(method, options):
    sigma, dt, n = 0.003, 0.5, 2**14
    x = np.random.default_rng(11).normal(0.0, sigma, n)
    est = estimate_psd(x, dt, method=method, **options)
    level = 2.0 * sigma**2 * dt

    assert est.f_hz[0] > 0.0
    assert est.f_hz[-1] == pytest.approx(est.nyquist_hz) == 1.0
    lower, upper = est.confidence_interval(0.95)
    coverage = np.mean((lower <= level) & (level <= upper))
    mean_level = np.mean(est.psd_m2_hz)
    df = est.f_hz[1] - est.f_hz[0]
    parseval = np.sum(est.psd_m2_hz) * df / np.var(x)
    print(
        f"\nwhite {method} {options}: mean/level={mean_level / level:.4f} "
        f"CI coverage={coverage:.3f} Parseval={parseval:.4f}"
    )
    assert coverage >= 0.90
    assert mean_level == pytest.approx(level, rel=0.04)
    assert parseval == pytest.approx(1.0, rel=0.02)


# ------------------------------------------------------------------------ Gauss-Markov


@pytest.mark.parametrize("gm", GM_SETS)
@pytest.mark.parametrize(("method", "options"), CASES)
def test_gm_model_inside_confidence_interval(method, options, gm):
    x = realisations(gm, 2**16, 1, 101)[0]
    est = estimate_psd(x, 1.0, method=method, **options)
    truth = model_psd(est.f_hz, gm)
    lower, upper = est.confidence_interval(0.95)
    inside = (lower <= truth) & (truth <= upper)
    a = 0.05
    width = np.median(stats.chi2.ppf(1 - a / 2, est.dof) / stats.chi2.ppf(a / 2, est.dof))
    print(
        f"\nGM {gm} {method} {options}: 95% CI coverage={inside.mean():.3f} "
        f"dof={np.mean(est.dof):.3f} median upper/lower={width:.3g}"
    )
    assert inside.mean() >= 0.90


@pytest.mark.parametrize("gm", GM_SETS)
@pytest.mark.parametrize(("method", "options"), CASES)
def test_gm_smoothed_estimate_converges(method, options, gm):
    """Mean over 32 realisations and log-spaced blocks of bins matches the model."""
    n, count = 2**15, 32
    xs = realisations(gm, n, count, 202)
    ests = [estimate_psd(x, 1.0, method=method, **options) for x in xs]
    f = ests[0].f_hz
    psd = np.array([e.psd_m2_hz for e in ests])
    truth = model_psd(f, gm)

    f_min = 4.0 * resolution_hz(ests[0])  # lowest bins: mean removal and taper bias
    edges = [f_min]
    while edges[-1] < 0.5:
        edges.append(max(1.25 * edges[-1], edges[-1] + 64.0 / n))  # >= 64 Fourier bins
    block = np.digitize(f, edges) - 1
    ratios, errors = [], []
    for b in np.unique(block[(block >= 0) & (block < len(edges) - 1)]):
        sel = block == b
        per_realisation = psd[:, sel].mean(axis=1) / truth[sel].mean()
        ratios.append(per_realisation.mean())
        errors.append(per_realisation.std(ddof=1) / np.sqrt(count))
    dev = np.abs(np.array(ratios) - 1.0)
    print(
        f"\nGM {gm} {method} {options}: {len(ratios)} blocks above {f_min:.2e} Hz, "
        f"max|ratio-1|={dev.max():.4f} median={np.median(dev):.4f} "
        f"max z={np.max(dev / np.array(errors)):.2f}"
    )
    assert dev.max() < 0.05
    assert np.median(dev) < 0.015
    assert np.all(dev < 4.0 * np.array(errors) + 0.01)


# ------------------------------------------------------------------ degrees of freedom


def test_multitaper_dof_is_2k():
    x = np.random.default_rng(1).normal(size=4096)
    assert estimate_psd(x, 1.0, method="multitaper").dof == 14.0
    est = estimate_psd(x, 1.0, method="multitaper", nw=3, k=5)
    assert est.dof == 10.0
    assert est.params["k"] == 5
    assert len(est.params["eigenvalues"]) == 5


def test_multitaper_adaptive_dof_per_frequency():
    x = realisations((0.04, 70.0, 0.009), 2**12, 1, 5)[0]
    est = estimate_psd(x, 1.0, method="multitaper", adaptive=True)
    assert isinstance(est.dof, np.ndarray)
    assert est.dof.shape == est.f_hz.shape
    assert np.all((est.dof > 2.0) & (est.dof <= 14.0 + 1e-9))
    lower, upper = est.confidence_interval()
    assert np.all(lower < est.psd_m2_hz) and np.all(est.psd_m2_hz < upper)


def test_welch_dof_hann_half_overlap():
    x = np.random.default_rng(2).normal(size=2**15)
    est = estimate_psd(x, 1.0, method="welch")
    k = est.params["n_segments"]
    assert (est.params["nperseg"], est.params["noverlap"], k) == (4096, 2048, 15)
    # Percival & Walden (1993) p. 294: Hann, 50 % overlap
    assert est.dof == pytest.approx(36.0 * k**2 / (19.0 * k - 1.0), rel=1e-3)
    assert est.dof == pytest.approx(1.89 * k, rel=0.01)
    assert estimate_psd(x, 1.0, method="welch", noverlap=0).dof == 2.0 * 8


@pytest.mark.parametrize("fraction", [1.0, 0.1])
def test_blackman_tukey_dof_formula(fraction):
    n = 5000
    x = np.random.default_rng(3).normal(size=n)
    est = estimate_psd(x, 1.0, method="blackman-tukey", max_lag_fraction=fraction)
    m = round(fraction * (n - 1))
    assert est.params["max_lag"] == m
    w = windows.tukey(2 * m + 1, alpha=0.2)
    assert est.dof == pytest.approx(2.0 * n / np.sum(w**2), rel=1e-12)
    if fraction == 1.0:
        assert est.dof == pytest.approx(2.0 / (2.0 * (0.8 + 0.2 * 3.0 / 8.0)), rel=1e-3)


@pytest.mark.parametrize(("method", "options"), CASES)
def test_recorded_dof_against_empirical(method, options):
    """Empirical nu = 2 mean^2 / var over 200 white-noise realisations, per bin."""
    rng = np.random.default_rng(4)
    xs = rng.normal(size=(200, 2048))
    ests = [estimate_psd(x, 1.0, method=method, **options) for x in xs]
    psd = np.array([e.psd_m2_hz for e in ests])[:, 20:-20]  # away from 0 and Nyquist
    recorded = np.median(np.atleast_1d(ests[0].dof))
    empirical = np.median(2.0 * psd.mean(axis=0) ** 2 / psd.var(axis=0, ddof=1))
    print(f"\n{method} {options}: recorded dof={recorded:.3f} empirical={empirical:.3f}")
    if method == "blackman-tukey" and options.get("max_lag_fraction", 1.0) == 1.0:
        # the asymptotic formula (M << N) is conservative with every lag
        assert recorded < empirical
        assert empirical == pytest.approx(2.0, rel=0.1)
    else:
        assert recorded == pytest.approx(empirical, rel=0.1)


# ------------------------------------------------------------ implementations, details


def test_blackman_tukey_matches_direct_sum():
    n, dt = 40, 2.0
    x = np.random.default_rng(6).normal(size=n)
    est = estimate_psd(x, dt, method="blackman-tukey", max_lag_fraction=0.5)
    m = est.params["max_lag"]
    assert m == round(0.5 * (n - 1))
    xc = x - x.mean()
    r = np.array([np.dot(xc[: n - k], xc[k:]) / n for k in range(m + 1)])
    w = windows.tukey(2 * m + 1, alpha=0.2)[m:]
    lags = np.arange(1, m + 1)
    direct = [
        2 * dt * (w[0] * r[0] + 2 * np.sum(w[1:] * r[1:] * np.cos(2 * np.pi * f * lags * dt)))
        for f in est.f_hz
    ]
    np.testing.assert_allclose(est.psd_m2_hz, direct, rtol=1e-9, atol=1e-12)
    assert est.params["nfft"] == 64


def test_blackman_tukey_negative_values_counted():
    x = np.random.default_rng(7).normal(size=4096)
    est = estimate_psd(x, 1.0, method="blackman-tukey")
    assert est.params["n_negative"] == np.count_nonzero(est.psd_m2_hz < 0)
    assert est.params["n_negative"] > 0  # the Tukey lag window's side lobes, full lags
    lower, upper = est.confidence_interval()
    assert np.all(lower <= upper)


def test_welch_matches_scipy():
    x = np.random.default_rng(8).normal(size=3000)
    est = estimate_psd(x, 0.2, method="welch", nperseg=256)
    f, p = signal.welch(x, fs=5.0, window="hann", nperseg=256, noverlap=128)
    np.testing.assert_allclose(est.f_hz, f[1:])
    np.testing.assert_allclose(est.psd_m2_hz, p[1:])


def test_multitaper_matches_direct():
    n, dt = 100, 30.0
    x = np.random.default_rng(9).normal(size=n)
    est = estimate_psd(x, dt, method="multitaper", nw=2.5)
    assert est.params["k"] == 4
    tapers = windows.dpss(n, 2.5, 4)
    t = np.arange(n) * dt
    xc = x - x.mean()
    direct = np.array(
        [
            np.mean(
                [2 * dt * abs(np.sum(h * xc * np.exp(-2j * np.pi * f * t))) ** 2 for h in tapers]
            )
            for f in est.f_hz
        ]
    )
    direct[-1] /= 2.0  # Nyquist (even N): not doubled
    np.testing.assert_allclose(est.psd_m2_hz, direct, rtol=1e-9)


def test_confidence_interval_formula():
    est = estimate_psd(np.random.default_rng(10).normal(size=1024), 1.0, method="welch")
    lower, upper = est.confidence_interval(0.9)
    nu, s = est.dof, est.psd_m2_hz
    np.testing.assert_allclose(lower, nu * s / stats.chi2.ppf(0.95, nu))
    np.testing.assert_allclose(upper, nu * s / stats.chi2.ppf(0.05, nu))


def test_estimate_is_frozen_and_read_only():
    x = np.random.default_rng(12).normal(size=101)
    assert estimate_psd(x, 2.0).method == "multitaper"  # the default, as in fit
    est = estimate_psd(x, 2.0, method="blackman-tukey")
    assert isinstance(est, PSDEstimate)
    assert est.method == "blackman-tukey" and est.n_samples == 101 and est.dt_s == 2.0
    assert est.nyquist_hz == 0.25
    assert est.f_hz[-1] == est.nyquist_hz  # power-of-two FFT length
    odd = estimate_psd(x, 2.0, method="multitaper")
    assert odd.f_hz[-1] < odd.nyquist_hz  # an odd FFT length has no Nyquist bin
    with pytest.raises(dataclasses.FrozenInstanceError):
        est.method = "welch"
    with pytest.raises(ValueError):
        est.psd_m2_hz[0] = 1.0


def test_methods_tuple_and_case_insensitive_name():
    assert METHODS == ("blackman-tukey", "welch", "multitaper")
    x = np.random.default_rng(13).normal(size=256)
    assert estimate_psd(x, 1.0, method="Welch").method == "welch"


# ---------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("x", "dt", "kwargs", "match"),
    [
        (np.zeros(MIN_SAMPLES - 1), 1.0, {}, "at least 16 samples"),
        (np.r_[np.zeros(20), np.nan], 1.0, {}, "NaN"),
        (np.r_[np.zeros(20), np.inf], 1.0, {}, "NaN, infinite or masked"),
        (np.ma.masked_array(np.zeros(32), mask=np.arange(32) == 5), 1.0, {}, "first at index 5"),
        (np.zeros(32) + 1j, 1.0, {}, "complex"),
        (np.zeros((4, 20)), 1.0, {}, "1-D"),
        (np.zeros(32), 0.0, {}, "positive"),
        (np.zeros(32), -1.0, {}, "positive"),
        (np.zeros(32), float("nan"), {}, "positive"),
        (np.zeros(32), 1.0, {"method": "periodogram"}, "blackman-tukey, welch, multitaper"),
        (np.zeros(32), 1.0, {"method": "welch", "nw": 3}, "valid options: nperseg"),
        (
            np.zeros(32),
            1.0,
            {"method": "blackman-tukey", "max_lag_fraction": 0.0},
            "max_lag_fraction",
        ),
        (np.zeros(32), 1.0, {"method": "blackman-tukey", "nfft": 16}, "nfft"),
        (np.zeros(32), 1.0, {"method": "welch", "nperseg": 64}, "nperseg"),
        (np.zeros(32), 1.0, {"method": "welch", "noverlap": 32}, "noverlap"),
        (np.zeros(32), 1.0, {"method": "multitaper", "nw": 16}, "nw"),
        (np.zeros(32), 1.0, {"method": "multitaper", "k": 0}, "k"),
    ],
)
def test_bad_input(x, dt, kwargs, match):
    with pytest.raises(InputError, match=match):
        estimate_psd(x, dt, **kwargs)


@pytest.mark.parametrize("level", [0.0, 1.0, 1.5])
def test_bad_confidence_level(level):
    est = estimate_psd(np.zeros(32), 1.0, method="multitaper")
    with pytest.raises(InputError, match="confidence level"):
        est.confidence_interval(level)
