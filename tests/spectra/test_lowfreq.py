"""Below the lowest band: the bound covers every admitted model down to 0 Hz (issue 28, part 1)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

import psdbound
from psdbound.spectra.bound import fit_bound
from psdbound.spectra.lowfreq import envelope_below, low_frequency_reasons
from psdbound.spectra.models import gm_psd_sampled

DT = 30.0
#: Every frequency a filter sees: 0 Hz and a dense log grid up to Nyquist.
F_ALL = np.r_[0.0, np.geomspace(1e-8, 0.5 / DT, 600)]


def _windows(rng, sigma_gm, tau, sigma_wn, n_windows, n):
    phi = np.exp(-DT / tau)
    out = []
    for _ in range(n_windows):
        e = rng.normal(0.0, sigma_gm * np.sqrt(1.0 - phi**2), n)
        e[0] = rng.normal(0.0, sigma_gm)
        out.append(lfilter([1.0], [1.0, -phi], e) + rng.normal(0.0, sigma_wn, n))
    return out


def _truth(sigma_gm, tau, sigma_wn):
    return gm_psd_sampled(F_ALL, sigma_gm, tau, DT) + 2.0 * sigma_wn**2 * DT


@pytest.mark.parametrize("tau_s", [30.0, 120.0, 600.0, 900.0])
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_bound_covers_a_gm_truth_at_every_frequency(tau_s, seed):
    """2-h windows at 30 s see a 600-900 s plateau only as a 1/f^2 tail: the prior covers it."""
    rng = np.random.default_rng(seed)
    res = psdbound.bound_series(_windows(rng, 0.003, tau_s, 0.001, 30, 240), DT)
    assert res.verdict == "bounded"
    ratio = res.bound.sampled_psd(F_ALL) / _truth(0.003, tau_s, 0.001)
    assert ratio.min() >= 1.0, (res.low_frequency.to_dict(), ratio.min())
    low = res.low_frequency
    if tau_s >= 600.0:  # the data cannot bound tau above: said, and the prior used
        assert low.status == "prior" and low.raised
        assert "prior 900 s" in res.covers
    if tau_s <= 30.0:  # the plateau is resolved: nothing is raised
        assert low.status == "covered" and np.isfinite(low.tau_upper_s)
    # the clause is on the main shape group's models, and says what it leaves out
    assert "the main shape group's pooled spectrum admits" in low.sentence()
    assert low.sentence().endswith("is not covered by this clause")


def test_tightest_bound_over_the_bands_alone_under_bounds_a_slow_truth():
    """What the rule fixes: the bound before it lies under a 600 s truth at 0 Hz."""
    rng = np.random.default_rng(7)
    res = psdbound.bound_series(_windows(rng, 0.003, 600.0, 0.001, 30, 240), DT)
    b = res.low_frequency.before
    before = gm_psd_sampled(np.array([0.0]), b["sigma_gm_m"], b["tau_s"], DT)
    assert before[0] < 0.8 * _truth(0.003, 600.0, 0.001)[0]


def test_refuse_policy_and_a_prior_below_the_data():
    rng = np.random.default_rng(4)
    # 1200 s in 2 h windows: the data admit time constants above the 900 s prior
    xs = _windows(rng, 0.003, 1200.0, 0.001, 30, 240)
    res = psdbound.bound_series(xs, DT, low_frequency_policy="refuse")
    assert res.verdict == "not-bounded"
    assert any("policy is 'refuse'" in r for r in res.verdict_reasons)
    res = psdbound.bound_series(xs, DT, tau_max_s=20.0)  # the data exclude tau <= 20 s
    assert res.verdict == "not-bounded"
    assert any("only time constants above the prior" in r for r in res.verdict_reasons)
    with pytest.raises(psdbound.InputError):
        psdbound.bound_series(xs, DT, low_frequency_policy="maybe")


def test_envelope_lies_above_every_admitted_model():
    """The envelope from the polygons' corners is above every model inside the polygons."""
    rng = np.random.default_rng(5)
    res = psdbound.bound_series(_windows(rng, 0.003, 60.0, 0.001, 30, 240), DT)
    ms = res.model_set
    f, env, _ = envelope_below(ms, DT, res.f_min_hz, tau_max_s=1e9)
    assert ms.vertices[:, 1:].min() >= 0.0
    for tau in np.unique(ms.vertices[:, 0]):
        corners = ms.vertices[ms.vertices[:, 0] == tau, 1:]
        # points inside a polygon are convex combinations of its corners
        for weights in rng.dirichlet(np.ones(len(corners)), 20):
            v, w = weights @ corners
            psd = v * gm_psd_sampled(f, 1.0, tau, DT) + w * 2.0 * DT
            assert np.all(psd * ms.window_factor <= env * (1 + 1e-9))


def test_floor_points_constrain_but_do_not_count_as_data():
    class P:
        def __init__(self, f, s):
            self.f_hz, self.psd_m2_hz = f, s

    f = np.geomspace(1e-3, 0.5 / DT, 30)
    data = P(f, gm_psd_sampled(f, 0.003, 30.0, DT))
    plain = fit_bound([data], DT)
    floor_f = np.array([1e-6])
    floor_s = np.array([10.0 * plain.psd(floor_f)[0]])
    raised = fit_bound([data], DT, floor=(floor_f, floor_s))
    assert raised.psd(floor_f)[0] >= floor_s[0] * (1 - 1e-9)
    assert raised.n_points == plain.n_points
    assert raised.margins.min() >= 1.0


def test_reasons_from_the_result_section():
    assert low_frequency_reasons(None) == []
    unchecked = {"status": "unchecked", "tau_max_s": 900.0, "reason": "3 test bands"}
    assert low_frequency_reasons(unchecked) == []
    (why,) = low_frequency_reasons(unchecked, "refuse")  # the data do not bound tau either
    assert "could not narrow" in why and "3 test bands" in why and "'refuse'" in why
    covered = {"status": "covered", "tau_max_s": 900.0, "envelope_at_0_m2_hz": 1e-3}
    assert low_frequency_reasons(covered, "refuse") == []
    prior = dict(covered, status="prior")
    assert low_frequency_reasons(prior, "prior") == []
    assert len(low_frequency_reasons(prior, "refuse")) == 1


def test_lowest_fourier_frequencies_identify_the_plateau():
    """Below f_min = W + 1/T the exact expectation still identifies tau (issue 27)."""
    from psdbound.spectra.intervals import model_set
    from psdbound.spectra.pooled import smoothing_hz

    rng = np.random.default_rng(4)
    xs = _windows(rng, 0.003, 600.0, 0.001, 30, 240)  # corner 2.7e-4 Hz < f_min 6.9e-4 Hz
    res = psdbound.bound_series(xs, DT)
    low = res.low_frequency
    assert res.f_min_hz > 1.0 / (2.0 * np.pi * 600.0)
    assert low.status == "covered" and low.tau_upper_s < 900.0
    lo, hi = res.model_set.tau_interval_s
    assert lo <= 600.0 <= hi
    # the statement's bands alone leave the time constant open above
    alone, _ = model_set(
        res.bands, res.limits, DT, smoothing_hz=smoothing_hz(res.psds), tau_max_s=900.0
    )
    assert alone.open_ends["tau_s"][1] or alone.tau_interval_s[1] > 900.0


def test_identification_bands_stop_at_f_min_after_a_filter():
    from psdbound.spectra.stated import identification_bands

    rng = np.random.default_rng(6)
    res = psdbound.bound_series(_windows(rng, 0.003, 60.0, 0.001, 10, 240), DT)
    same = identification_bands(res.psds, res.bands, filtered=True)
    assert same is res.bands
    lower = identification_bands(res.psds, res.bands)
    assert lower.edges_hz[0] == pytest.approx(1.0 / (240 * DT), rel=1e-6)
    assert np.isfinite(lower.psd_m2_hz[:, 0]).all()


def test_prior_ceiling_lies_above_every_model_within_the_lowest_limit():
    """Closed form: GM + white models with tau <= tau_max and band mean = U stay under it."""
    from types import SimpleNamespace

    from psdbound.spectra.lowfreq import prior_ceiling

    lo, hi, upper = 0.003, 0.0038, 2e-4
    bands = SimpleNamespace(edges_hz=np.array([lo, hi, 0.005]))
    limits = SimpleNamespace(upper_m2_hz=np.array([[upper, 1e-4]]), band_span_hz=None)
    f, ceiling = prior_ceiling(limits, bands, DT, tau_max_s=900.0)
    assert f[-1] == pytest.approx(lo) and f[0] == pytest.approx(1e-4 * lo)
    band = np.linspace(lo, hi, 2001)
    rng = np.random.default_rng(8)
    worst = 0.0
    for tau in np.r_[np.geomspace(DT, 900.0, 40), rng.uniform(DT, 900.0, 40)]:
        for white_share in (0.0, 0.3, 0.9):
            shape = (1 - white_share) * gm_psd_sampled(band, 1.0, tau, DT) + white_share * 2 * DT
            scale = upper / np.mean(shape)  # the model's band mean is exactly the limit
            below = scale * (
                (1 - white_share) * gm_psd_sampled(f, 1.0, tau, DT) + white_share * 2 * DT
            )
            worst = max(worst, float(np.max(below / ceiling)))
    assert worst <= 1.0 + 1e-9
    assert worst > 0.5  # the ceiling is reached within a factor 2 (tau_max, no white noise)
    slower = gm_psd_sampled(band, 1.0, 3000.0, DT)
    outside = upper / np.mean(slower) * gm_psd_sampled(f, 1.0, 3000.0, DT)
    assert outside[0] > ceiling[0]  # a slower truth is outside the prior, and says so


def test_without_a_model_set_the_prior_still_covers_a_slow_truth():
    """Too few bands for a model set (short windows): the bound below f_min is not left
    to the fitted model's extrapolation, it covers every model up to the prior."""
    rng = np.random.default_rng(21)
    truth = (0.003, 600.0, 0.0005)
    res = psdbound.bound_series(_windows(rng, *truth, 6, 80), DT)  # 40-min windows
    low = res.low_frequency
    assert low.status == "unchecked" and low.envelope_m2_hz is not None
    assert "could not narrow" in low.sentence() and "prior 900 s" in res.covers
    f = F_ALL[F_ALL < res.f_min_hz]
    truth_below = gm_psd_sampled(f, truth[0], truth[1], DT) + 2 * truth[2] ** 2 * DT
    assert np.all(res.bound.sampled_psd(f) >= truth_below)
    before = low.before
    extrapolated = gm_psd_sampled(f, before["sigma_gm_m"], before["tau_s"], DT)
    assert extrapolated[0] < truth_below[0]  # the fitted model alone lay under the truth at 0 Hz


def test_a_prior_below_half_the_interval_is_refused():
    """Below dt/2 no time constant is searched: white noise was 'not-bounded' with the false
    reason that the data admit only longer time constants."""
    rng = np.random.default_rng(6)
    white = [rng.normal(0.0, 0.002, 512) for _ in range(8)]
    with pytest.raises(psdbound.InputError, match="below the shortest time constant"):
        psdbound.bound_series(white, DT, tau_max_s=0.4 * DT)
    assert psdbound.bound_series(white, DT, tau_max_s=DT).verdict == "bounded"
