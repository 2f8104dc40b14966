"""The set of GM + white-noise models consistent with pooled spectra: coverage of the truth."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

from psdbound.spectra import estimate_psd
from psdbound.spectra.bands import band_spectra, merge_bands
from psdbound.spectra.intervals import model_set
from psdbound.spectra.pooled import pool_bands

DT = 1.0


def _windows(rng, sigma_gm, tau, sigma_wn, n_windows=16, n=1200):
    phi = np.exp(-DT / tau)
    out = []
    for _ in range(n_windows):
        e = rng.normal(0.0, sigma_gm * np.sqrt(1 - phi**2), n)
        gm = lfilter([1.0], [1.0, -phi], e, zi=[phi * rng.normal(0.0, sigma_gm)])[0]
        out.append(gm + rng.normal(0.0, sigma_wn, n))
    return out


def _set(xs):
    psds = [estimate_psd(x, DT) for x in xs]
    bands = merge_bands(band_spectra(psds, f_min_hz=2.0 / (len(xs[0]) * DT)))
    w = float(np.median([p.params["bandwidth_hz"] for p in psds]))
    return model_set(bands, pool_bands(bands), DT, smoothing_hz=w)


@pytest.mark.slow
def test_truth_inside_the_intervals_at_the_stated_level():
    rng = np.random.default_rng(20)
    truth = {"sigma_gm_m": 0.003, "tau_s": 30.0, "sigma_wn_m": 0.001}
    hits, widths = 0, []
    n_trials = 40
    for _ in range(n_trials):
        ms, why = _set(_windows(rng, 0.003, 30.0, 0.001))
        assert ms is not None, why
        inside = (
            ms.tau_interval_s[0] <= truth["tau_s"] <= ms.tau_interval_s[1]
            and ms.sigma_gm_interval_m[0] <= truth["sigma_gm_m"] <= ms.sigma_gm_interval_m[1]
            and ms.sigma_wn_interval_m[0] <= truth["sigma_wn_m"] <= ms.sigma_wn_interval_m[1]
        )
        hits += int(inside)
        widths.append(ms.tau_interval_s[1] / ms.tau_interval_s[0])
    print(f"\njoint coverage {hits}/{n_trials}; median tau interval ratio {np.median(widths):.2f}")
    # nominal 95 % (Bonferroni over bands: at least); measured 39/40 with the exact
    # expectation of the estimator (the likelihood-ratio set it replaced: 29-35/40)
    assert hits >= 36
    assert np.median(widths) < 2.5  # informative: 16 windows of 20 min pin tau within x2.5


def test_more_data_narrow_the_set_and_the_best_fit_is_close():
    rng = np.random.default_rng(21)
    small, _ = _set(_windows(rng, 0.004, 60.0, 0.002, n_windows=4))
    large, _ = _set(_windows(rng, 0.004, 60.0, 0.002, n_windows=32))
    ratio = [s.tau_interval_s[1] / s.tau_interval_s[0] for s in (small, large)]
    assert ratio[1] < ratio[0]
    assert large.tau_interval_s[0] <= 60.0 <= large.tau_interval_s[1]
    # the best fit is a point estimate inside the set (81 s for this seed; the set holds 60 s)
    assert large.tau_interval_s[0] <= large.best["tau_s"] <= large.tau_interval_s[1]
    assert 60.0 / 1.5 <= large.best["tau_s"] <= 60.0 * 1.5
    assert large.best["sigma_gm_m"] == pytest.approx(0.004, rel=0.2)


def test_too_few_bands_give_a_reason():
    rng = np.random.default_rng(22)
    xs = [rng.normal(size=40) for _ in range(3)]
    psds = [estimate_psd(x, DT) for x in xs]
    bands = merge_bands(band_spectra(psds, f_min_hz=0.2))
    w = float(np.median([p.params["bandwidth_hz"] for p in psds]))
    ms, why = model_set(bands, pool_bands(bands), DT, smoothing_hz=w)
    assert ms is None and "bands" in why
    ms, why = model_set(bands, pool_bands(bands), DT)  # no smoothing width: no exact model
    assert ms is None and "multitaper" in why


def test_demo_result_carries_the_intervals_around_the_injected_truth():
    import psdbound

    res = psdbound.fit()
    b = res.document["bound"]
    truth = res.document["demo"]["truth_model"]
    assert b["tau_interval_s"][0] <= truth["tau_s"] <= b["tau_interval_s"][1]
    assert b["sigma_gm_interval_m"][0] <= truth["sigma_gm_m"] <= b["sigma_gm_interval_m"][1]
    assert res.bound.sigma_gm_m >= b["model_set"]["best"]["sigma_gm_m"]  # a bound, above the fit


def test_exact_multitaper_expectation_against_simulation():
    from psdbound.spectra import gm_psd_sampled
    from psdbound.spectra.expectation import far_lag_kernels, gm_band_expectation, lag_kernels

    n, tau, nw = 1200, 300.0, 4.0
    rng = np.random.default_rng(0)
    w = nw / (n * DT)
    lo = np.array([1.25, 2.2, 5.0, 14.0]) * w
    hi = lo * 1.26
    kernels, has = lag_kernels(n, DT, lo, hi, nw=nw)
    exact = gm_band_expectation(kernels, np.array([tau]), DT)[0]
    far = gm_band_expectation(far_lag_kernels(n, DT, lo, hi, nw=nw)[0], np.array([tau]), DT)[0]
    acc = np.zeros(lo.size)
    for x in _windows(rng, 1.0, tau, 0.0, n_windows=300, n=n):
        p = estimate_psd(x, DT)
        acc += [
            p.psd_m2_hz[(p.f_hz >= a) & (p.f_hz < b)].mean() for a, b in zip(lo, hi, strict=True)
        ]
    assert has.all()
    np.testing.assert_allclose(acc / 300, exact, rtol=0.06)
    # away from 0 Hz the form without the mean removal agrees with the exact one
    assert far[-1] == pytest.approx(exact[-1], rel=5e-3)
    # the band-mean PSD is about half the expectation at 1.25 W: why the exact form is needed
    band_mean = gm_psd_sampled(np.linspace(lo[0], hi[0], 50), 1.0, tau, DT).mean()
    assert band_mean < 0.6 * exact[0]
