"""Kalman-filter tools: bound object, state-space export, augmentation, covariance
analysis (bounded and violated cases) and the aviation utilities (seed numbers)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import trapezoid
from scipy.stats import norm

from psdbound.errors import InputError
from psdbound.kalman import (
    CovarianceAnalysis,
    ErrorProcess,
    ErrorSequences,
    GaussMarkovBound,
    SampledPSD,
    alpha_for_inflation,
    alpha_from_tau,
    analyze_covariance,
    augment_gm_states,
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
from psdbound.spectra.bound import fit_bound
from psdbound.spectra.models import gm_acf, gm_psd_sampled, white_psd
from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping

# (sigma_gm, tau, sigma_wn, data dt, filter dt)
SS_CASES = [
    (0.005, 45.0, 0.002, 1.0, 1.0),  # thesis DA
    (0.04, 70.0, 0.009, 30.0, 30.0),  # thesis DF at 30 s
    (0.01, 10.0, 0.001, 1.0, 5.0),  # filter slower than the data
    (0.02, 300.0, 0.0, 30.0, 1.0),  # filter faster, no white noise
    (0.003, 2.0, 0.004, 0.5, 0.5),  # dt comparable to tau
]


def result_doc(**over):
    doc = {
        "schema_version": "1",
        "bound": {
            "sigma_gm_m": 0.005,
            "tau_s": 45.0,
            "sigma_wn_m": 0.002,
            "n_wn_two_sided_m2_hz": 0.002**2 * 30.0,
            "dt_s": 30.0,
        },
        "sampling": {"interval_s": 30.0, "nyquist_hz": 1.0 / 60.0},
        "mapping": {"a": 1.0, "b": 29.0, "c_deg": 10.0},
        "provenance": {"anything": "ignored"},
    }
    for k, v in over.items():
        sec, _, key = k.partition("__")
        if key:
            if v is KeyError:
                del doc[sec][key]
            else:
                doc[sec][key] = v
        elif v is KeyError:
            del doc[sec]
        else:
            doc[sec] = v
    return doc


# --------------------------------------------------------------------------- bound object
def test_from_result_reads_the_schema(tmp_path):
    p = tmp_path / "result.json"
    p.write_text(json.dumps(result_doc()))
    b = GaussMarkovBound.from_result(p)
    assert (b.sigma_gm_m, b.tau_s, b.sigma_wn_m, b.dt_s) == (0.005, 45.0, 0.002, 30.0)
    assert b.n_wn_two_sided_m2_hz == pytest.approx(0.002**2 * 30.0, rel=1e-15)
    assert b.nyquist_hz == pytest.approx(1 / 60)
    assert b.mapping == ElevationMapping(1.0, 29.0, 10.0)
    assert b.source == str(p)
    p.write_text(json.dumps(result_doc(mapping=None)))
    assert GaussMarkovBound.from_result(p).mapping is None


@pytest.mark.parametrize(
    ("over", "message"),
    [
        ({"bound__tau_s": KeyError}, "missing key 'bound.tau_s'"),
        ({"sampling": KeyError}, "missing key 'sampling'"),
        ({"mapping": KeyError}, "missing key 'mapping'"),
        ({"mapping__c_deg": KeyError}, "missing key 'mapping.c_deg'"),
        ({"schema_version": "2"}, "unsupported schema_version '2'"),
        ({"schema_version": 1}, "unsupported schema_version 1"),
        ({"schema_version": KeyError}, "missing key 'schema_version'"),
        ({"bound__sigma_gm_m": -0.001}, "'bound.sigma_gm_m' must be >= 0"),
        ({"bound__sigma_wn_m": -1.0}, "'bound.sigma_wn_m' must be >= 0"),
        ({"bound__tau_s": 0.0}, "'bound.tau_s' must be > 0"),
        ({"bound__dt_s": "30"}, "'bound.dt_s' must be a finite number"),
        ({"bound__n_wn_two_sided_m2_hz": 1.0}, "disagrees with sigma_wn_m^2 * dt_s"),
        ({"sampling__interval_s": 1.0}, "'sampling.interval_s' = 1.0 disagrees"),
        ({"sampling__nyquist_hz": 0.5}, "'sampling.nyquist_hz' = 0.5 disagrees"),
        ({"bound": [1, 2]}, "key 'bound' must hold a JSON object"),
    ],
)
def test_from_result_specific_errors(tmp_path, over, message):
    p = tmp_path / "result.json"
    p.write_text(json.dumps(result_doc(**over)))
    with pytest.raises(InputError) as e:
        GaussMarkovBound.from_result(p)
    assert message in str(e.value)
    assert str(p) in str(e.value)


def test_from_result_not_json_or_missing(tmp_path):
    p = tmp_path / "result.json"
    p.write_text("sigma_gm_m = 0.005\n")
    with pytest.raises(InputError, match="not valid JSON") as e:
        GaussMarkovBound.from_result(p)
    assert e.value.line == 1
    p.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(InputError, match="not UTF-8|not valid JSON"):
        GaussMarkovBound.from_result(p)
    p.write_text("[1, 2]")
    with pytest.raises(InputError, match="JSON object at top level"):
        GaussMarkovBound.from_result(p)
    with pytest.raises(InputError, match="cannot read result file"):
        GaussMarkovBound.from_result(tmp_path / "absent.json")


def test_from_params_validation_and_from_fit():
    with pytest.raises(InputError, match="sigma_gm_m must be >= 0"):
        GaussMarkovBound.from_params(-1.0, 45.0, 0.0, 1.0)
    with pytest.raises(InputError, match="tau_s must be > 0"):
        GaussMarkovBound.from_params(0.01, 0.0, 0.0, 1.0)
    with pytest.raises(InputError, match="dt_s must be > 0"):
        GaussMarkovBound.from_params(0.01, 10.0, 0.0, -1.0)
    with pytest.raises(InputError, match="must be finite"):
        GaussMarkovBound.from_params(0.01, math.inf, 0.0, 1.0)
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0)
    with pytest.raises(InputError, match="unknown white_noise mode"):
        b.to_state_space(1.0, white_noise="flat")
    with pytest.raises(InputError, match="no elevation mapping"):
        b.to_state_space(1.0, elevation_deg=30.0)
    # from a real fit: same PSD as the BoundFit
    dt = 1.0
    f = np.linspace(1e-3, 0.5, 300)
    s = gm_psd_sampled(f, 0.005, 45.0, dt) + white_psd(f, 0.002, dt)
    from types import SimpleNamespace

    fit = fit_bound([SimpleNamespace(f_hz=f, psd_m2_hz=s)], dt)
    gb = GaussMarkovBound.from_fit(fit, mapping=THESIS_MAPPING)
    np.testing.assert_allclose(gb.sampled_psd(f), fit.psd(f), rtol=1e-13)
    assert gb.total_variance_m2 == pytest.approx(fit.total_variance_m2, rel=1e-13)
    assert gb.params() == pytest.approx(fit.params())
    assert "tau=" in str(gb)


@pytest.mark.parametrize(("sigma", "tau", "sigma_wn", "dt_data", "dt"), SS_CASES)
def test_state_space_reproduces_acf_and_sampled_psd(sigma, tau, sigma_wn, dt_data, dt):
    b = GaussMarkovBound.from_params(sigma, tau, sigma_wn, dt_data)
    phi, qd, r = b.to_state_space(dt, white_noise="psd")
    assert phi == pytest.approx(math.exp(-dt / tau), rel=1e-15)
    assert r == pytest.approx(sigma_wn**2 * dt_data / dt, rel=1e-14)  # N_WN / dt
    # autocorrelation of the AR(1) recursion at lags k dt == continuous sigma^2 exp(-k dt/tau)
    lags = np.arange(0, 400)
    stationary = qd / (1 - phi**2)
    acf_ss = stationary * phi**lags
    np.testing.assert_allclose(acf_ss, gm_acf(lags * dt, sigma, tau), rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(
        b.acf(lags * dt, dt, white_noise="psd"),
        acf_ss + np.where(lags == 0, r, 0.0),
        rtol=1e-12,
        atol=1e-300,
    )
    proc = ErrorProcess.from_bound(b, dt, white_noise="psd")
    np.testing.assert_allclose(
        proc.acf(lags.size), b.acf(lags * dt, dt, white_noise="psd"), rtol=1e-10, atol=1e-300
    )
    # PSD of the state-space model (transfer function of (Phi, Qd, R)) == sampled bound PSD
    nyq = 0.5 / dt
    f = np.r_[0.0, np.geomspace(nyq * 1e-5, nyq, 400)]
    expected = gm_psd_sampled(f, sigma, tau, dt) + white_psd(f, math.sqrt(r), dt)
    np.testing.assert_allclose(proc.psd(f), expected, rtol=1e-9)
    np.testing.assert_allclose(b.sampled_psd(f, dt, white_noise="psd"), expected, rtol=1e-13)
    # ... == 2 dt * (two-sided sum of the autocovariance): ACF and PSD agree
    k = np.arange(1, 20000)
    r_k = stationary * phi**k
    two_sided = dt * (stationary + r + 2 * np.cos(2 * np.pi * np.outer(f[::40], k) * dt) @ r_k)
    np.testing.assert_allclose(2 * two_sided, expected[::40], rtol=1e-8)
    # variance = integral over [0, f_N]
    fg = np.linspace(0, nyq, 200001)
    assert trapezoid(b.sampled_psd(fg, dt, white_noise="psd"), fg) == pytest.approx(
        sigma**2 + r, rel=1e-5
    )


def test_state_space_matches_simulation():
    b = GaussMarkovBound.from_params(0.01, 20.0, 0.004, 1.0)
    x = b.simulate(400, 2.0, n_series=3000, rng=1)
    emp = np.array([np.mean(x[:, 100:300] * x[:, 100 + k : 300 + k]) for k in (0, 1, 5, 20)])
    np.testing.assert_allclose(emp, b.acf(np.array([0, 1, 5, 20]) * 2.0, 2.0), rtol=0.05)


def test_white_noise_conventions_for_another_interval():
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0)
    # filter at 5 s: "psd" keeps N_WN (averaging), "per_sample" keeps sigma_wn^2 (decimation)
    assert b.white_variance_m2(5.0, white_noise="psd") == pytest.approx(0.002**2 / 5)
    assert b.white_variance_m2(5.0) == pytest.approx(0.002**2)  # default: conservative
    assert b.white_variance_m2(5.0, white_noise="per_sample") == pytest.approx(0.002**2)
    assert b.white_variance_m2(5.0, white_noise="conservative") == pytest.approx(0.002**2)
    assert b.white_variance_m2(0.5, white_noise="conservative") == pytest.approx(0.002**2 * 2)
    for mode in ("psd", "per_sample", "conservative"):
        assert b.white_variance_m2(1.0, white_noise=mode) == pytest.approx(0.002**2)
    # the flat PSD level 2 N_WN is invariant under "psd"
    f = np.array([0.05])
    for dt in (0.2, 1.0, 7.0):
        white = b.sampled_psd(f, dt, white_noise="psd") - gm_psd_sampled(f, 0.005, 45.0, dt)
        assert white[0] == pytest.approx(2 * b.n_wn_two_sided_m2_hz, rel=1e-9)
    # decimating by k folds the data-rate bound PSD: that is the "per_sample" model at k dt
    k = 5
    dtf = 5.0
    f = np.linspace(0, 0.5 / dtf, 101)
    folded = np.zeros_like(f)
    for j in range(k):
        g = np.mod(f + j / dtf, 1.0)
        folded += b.sampled_psd(np.minimum(g, 1.0 - g), 1.0)
    np.testing.assert_allclose(b.sampled_psd(f, dtf, white_noise="per_sample"), folded, rtol=1e-10)


def test_elevation_mapping_scales_sigma():
    b = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0, mapping=THESIS_MAPPING)
    m = float(THESIS_MAPPING.factor(15.0))
    be = b.at_elevation(15.0)
    assert be.sigma_gm_m == pytest.approx(0.005 * m)
    assert be.sigma_wn_m == pytest.approx(0.002 * m)
    assert be.tau_s == b.tau_s and be.mapping is None
    phi, qd, r = b.to_state_space(1.0, elevation_deg=[15.0, 90.0])
    np.testing.assert_allclose(qd, [be.to_state_space(1.0).qd_m2, b.to_state_space(1.0).qd_m2])
    np.testing.assert_allclose(r, [be.to_state_space(1.0).r_m2, b.to_state_space(1.0).r_m2 * 1.0])
    assert b.at_elevation(90.0).sigma_gm_m == pytest.approx(0.005, rel=1e-12)
    with pytest.raises(InputError, match="no elevation mapping"):
        be.at_elevation(20.0)


# --------------------------------------------------------------------------- augmentation
def geometry():
    az = np.deg2rad([0.0, 60.0, 130.0, 200.0, 270.0, 320.0])
    el_deg = np.array([75.0, 40.0, 25.0, 55.0, 15.0, 35.0])
    el = np.deg2rad(el_deg)
    los = np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])
    return np.column_stack([-los, np.ones(6)]), el_deg


H6, EL6 = geometry()
BOUND = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0, mapping=THESIS_MAPPING)
SCALE6 = THESIS_MAPPING.factor(EL6)
P0 = np.diag([1.0, 1.0, 1.0, 100.0])
R_OTHER = np.eye(6) * 0.001**2
# a slowly moving receiver (the filter averages: listens to low frequencies) and a
# kinematic one (the filter follows the measurements: listens to all frequencies)
FILTERS = {
    "static": np.diag([1e-6, 1e-6, 1e-6, 1e-2]),
    "kinematic": np.diag([1.0, 1.0, 1.0, 1e2]),
}


def test_augment_structure():
    F = np.eye(4)
    aug = augment_gm_states(F, FILTERS["static"], H6, R_OTHER, BOUND, 1.0, elevation_deg=EL6)
    assert aug.F.shape == (10, 10) and aug.H.shape == (6, 10)
    phi, qd, r = BOUND.to_state_space(1.0)
    np.testing.assert_allclose(np.diag(aug.F)[4:], phi)
    np.testing.assert_allclose(np.diag(aug.Q)[4:], qd)
    np.testing.assert_allclose(aug.H[:, 4:], np.diag(SCALE6))
    np.testing.assert_allclose(aug.R, R_OTHER + np.diag(SCALE6**2 * r))
    np.testing.assert_allclose(aug.p0_gm_m2, 0.005**2)
    p0 = aug.initial_covariance(P0)
    assert p0[aug.gm_slice, aug.gm_slice][0, 0] == 0.005**2 and p0[0, 4] == 0
    # the raw-scale multipath model of measurement i is the bound at its elevation
    i = 4
    be = BOUND.at_elevation(EL6[i])
    assert aug.H[i, 4 + i] ** 2 * aug.p0_gm_m2[i] == pytest.approx(be.sigma_gm_m**2)
    with pytest.raises(InputError, match="one bound per measurement"):
        augment_gm_states(F, FILTERS["static"], H6, R_OTHER, [BOUND] * 5, 1.0)
    with pytest.raises(InputError, match="one elevation per measurement"):
        augment_gm_states(F, FILTERS["static"], H6, R_OTHER, BOUND, 1.0, elevation_deg=[10.0])
    with pytest.raises(InputError, match=r"F must have shape \(4, 4\)"):
        augment_gm_states(np.eye(3), FILTERS["static"], H6, R_OTHER, BOUND, 1.0)
    with pytest.raises(InputError, match="has no elevation mapping"):
        nomap = GaussMarkovBound.from_params(0.005, 45.0, 0.002, 1.0)
        augment_gm_states(F, FILTERS["static"], H6, None, nomap, 1.0, elevation_deg=EL6)


# --------------------------------------------------------------------------- covariance
def analyse(truth, filt="static", n_steps=600, **kw):
    return analyze_covariance(
        np.eye(4),
        FILTERS[filt],
        H6,
        R_OTHER,
        BOUND,
        truth,
        dt_s=1.0,
        n_steps=n_steps,
        p0_base=P0,
        elevation_deg=EL6,
        **kw,
    )


def raw(proc):
    """One independent copy per satellite, scaled to its elevation (raw metres)."""
    return [proc.scaled(s) for s in SCALE6]


UNDER_BOUND = {
    "gauss-markov tau 15 s": ErrorProcess.gauss_markov(0.0031, 15.0, 1.0),
    "second-order": ErrorProcess.second_order(0.0032, 2 * np.pi / 60.0, 1.0, damping=1.0),
    "white": ErrorProcess.white(0.00205, 1.0),
    "gauss-markov + white": ErrorProcess.gauss_markov(0.002, 10.0, 1.0)
    + ErrorProcess.white(0.0015, 1.0),
}


def test_truth_equal_to_bound_gives_the_filter_covariance():
    """Consistency: with the bound itself as truth, P_true == P_filter at every step."""
    truth = [ErrorProcess.from_bound(BOUND, 1.0, elevation_deg=e) for e in EL6]
    res = analyse(truth)
    np.testing.assert_allclose(res.p_true_m2, res.p_filter_m2, rtol=1e-8, atol=1e-16)
    np.testing.assert_allclose(res.p_true_ss_m2, res.p_filter_ss_m2, rtol=1e-8)
    assert res.max_eig_ratio == pytest.approx(1.0, abs=1e-8)
    # steady state is where the recursion ends up
    np.testing.assert_allclose(res.p_filter_m2[-1], res.p_filter_ss_m2, rtol=1e-3)


@pytest.mark.parametrize("filt", ["static", "kinematic"])
@pytest.mark.parametrize("name", list(UNDER_BOUND))
def test_truth_under_the_bound_is_bounded(name, filt):
    res = analyse(raw(UNDER_BOUND[name]), filt)
    # premise: the true sampled PSD is under the bound at every frequency
    assert res.psd_ratio_min.min() >= 1.0
    # conclusion: true variance never exceeds the filter's, at any step, in any direction
    assert res.max_variance_ratio <= 1.0 + 1e-9
    assert res.max_eig_ratio <= 1.0 + 1e-9
    assert res.bounded()
    assert res.p_true_ss_m2 is not None
    assert np.all(np.diag(res.p_true_ss_m2) <= np.diag(res.p_filter_ss_m2))
    assert "bounded" in res.summary()


@pytest.mark.parametrize(
    ("filt", "truth", "min_ratio"),
    [
        # low-frequency excess: same sigma, 4x the correlation time
        ("static", ErrorProcess.gauss_markov(0.005, 180.0, 1.0), 1.5),
        # everywhere 20 % above in PSD: sigma 10 % larger
        ("static", ErrorProcess.gauss_markov(0.0055, 45.0, 1.0), 1.1),
        # high-frequency excess seen by a fast filter: white noise 3 mm instead of 2 mm
        (
            "kinematic",
            ErrorProcess.gauss_markov(0.005, 45.0, 1.0) + ErrorProcess.white(0.003, 1.0),
            1.1,
        ),
    ],
)
def test_truth_over_the_bound_is_detected(filt, truth, min_ratio):
    res = analyse(raw(truth), filt)
    assert res.psd_ratio_min.min() < 1.0
    assert not res.bounded()
    assert res.max_eig_ratio > min_ratio
    assert res.max_variance_ratio > min_ratio
    assert "False" in res.summary()


def test_psd_excess_outside_the_filter_band_can_pass():
    """The PSD condition is sufficient, not necessary: excess white noise that a slow
    filter averages away does not make its covariance wrong."""
    res = analyse(raw(ErrorProcess.white(0.003, 1.0)), "static")
    assert res.psd_ratio_min.min() < 0.5
    assert res.bounded()


def test_psd_path_and_monte_carlo_agree_with_state_space():
    truth = UNDER_BOUND["gauss-markov tau 15 s"]
    ref = analyse(raw(truth), n_steps=300)
    f = np.linspace(0.0, 0.5, 2001)
    via_psd = analyse([SampledPSD.from_process(p, f) for p in raw(truth)], n_steps=300)
    assert via_psd.method == "psd"
    np.testing.assert_allclose(via_psd.p_true_m2, ref.p_true_m2, rtol=1e-3, atol=1e-12)
    np.testing.assert_allclose(via_psd.p_true_ss_m2, ref.p_true_ss_m2, rtol=1e-3)
    # ErrorProcess objects in the PSD path (exact ACF) give the state-space numbers exactly
    mixed = [SampledPSD.from_process(p, f) for p in raw(truth)[:1]] + raw(truth)[1:]
    res = analyse(mixed, n_steps=300)
    assert res.method == "psd"
    np.testing.assert_allclose(res.p_true_m2, ref.p_true_m2, rtol=1e-3, atol=1e-12)
    np.testing.assert_allclose(res.p_true_ss_m2, ref.p_true_ss_m2, rtol=1e-3)
    # a piecewise-linear (here flat) PSD has an exact ACF: agreement to round-off
    white = raw(UNDER_BOUND["white"])
    flat = [SampledPSD(np.array([0.0, 0.5]), p.psd(np.array([0.0, 0.5])), 1.0) for p in white]
    a, b = analyse(white, n_steps=300), analyse(flat, n_steps=300)
    np.testing.assert_allclose(b.p_true_m2, a.p_true_m2, rtol=1e-9, atol=1e-18)
    np.testing.assert_allclose(b.p_true_ss_m2, a.p_true_ss_m2, rtol=1e-4)
    # Monte Carlo from sample paths
    rng = np.random.default_rng(7)
    paths = np.stack(
        [
            GaussMarkovBound.from_params(0.0031 * s, 15.0, 0.0, 1.0).simulate(
                300, n_series=4000, rng=rng
            )
            for s in SCALE6
        ],
        axis=-1,
    )
    mc = analyse(ErrorSequences(paths, 1.0), n_steps=300)
    assert mc.method == "monte_carlo" and mc.n_paths == 4000 and mc.p_true_ss_m2 is None
    d_ref = np.diagonal(ref.p_true_m2, axis1=1, axis2=2)
    d_mc = np.diagonal(mc.p_true_m2, axis1=1, axis2=2)
    np.testing.assert_allclose(d_mc[50:], d_ref[50:], rtol=0.1)


def test_covariance_recursion_matches_a_simulated_filter():
    """Independent check of the error equations: run the actual augmented Kalman filter
    on simulated data (true random-walk states + true multipath) and compare the sample
    covariance of its errors with the analysed P_true."""
    n_steps, n_paths = 150, 3000
    Q = FILTERS["kinematic"] * 1e-2
    truth = raw(ErrorProcess.second_order(0.003, 2 * np.pi / 30.0, 1.0, damping=0.5))
    res = analyze_covariance(
        np.eye(4), Q, H6, R_OTHER, BOUND, truth, dt_s=1.0, n_steps=n_steps, p0_base=P0,
        elevation_deg=EL6,
    )  # fmt: skip
    aug = augment_gm_states(np.eye(4), Q, H6, R_OTHER, BOUND, 1.0, elevation_deg=EL6)
    rng = np.random.default_rng(3)
    x = rng.multivariate_normal(np.zeros(4), P0, n_paths)
    xi = [rng.multivariate_normal(np.zeros(2), p.stationary_covariance(), n_paths) for p in truth]
    xh = np.zeros((n_paths, 10))
    p = aug.initial_covariance(P0)
    lq = np.linalg.cholesky(Q)
    lr = np.linalg.cholesky(R_OTHER)
    errs = np.empty((n_steps, 4, 4))
    for k in range(n_steps):
        if k > 0:
            x = x + rng.standard_normal((n_paths, 4)) @ lq.T
            for i, pr in enumerate(truth):
                lw = np.linalg.cholesky(pr.q_m2 + 1e-30 * np.eye(2))
                xi[i] = xi[i] @ pr.a.T + rng.standard_normal((n_paths, 2)) @ lw.T
            xh = xh @ aug.F.T
            p = aug.F @ p @ aug.F.T + aug.Q
        mp = np.column_stack([xi[i] @ pr.c for i, pr in enumerate(truth)])
        y = x @ H6.T + mp + rng.standard_normal((n_paths, 6)) @ lr.T
        s = aug.H @ p @ aug.H.T + aug.R
        kg = np.linalg.solve(s, aug.H @ p).T
        xh = xh + (y - xh @ aug.H.T) @ kg.T
        a = np.eye(10) - kg @ aug.H
        p = a @ p @ a.T + kg @ aug.R @ kg.T
        e = x - xh[:, :4]
        errs[k] = e.T @ e / n_paths
    np.testing.assert_allclose(p[:4, :4], res.p_filter_m2[-1], rtol=1e-8)
    d_sim = np.diagonal(errs, axis1=1, axis2=2)
    d_res = np.diagonal(res.p_true_m2, axis1=1, axis2=2)
    np.testing.assert_allclose(d_sim, d_res, rtol=0.12)
    assert np.abs(d_sim[20:] / d_res[20:] - 1).mean() < 0.03


def test_time_varying_geometry_and_other_interval():
    """Rotating geometry (H per step; no steady state) and a filter at 5 s with a 1 s bound."""
    n_steps = 200
    hs = []
    for k in range(n_steps):
        rot = np.deg2rad(0.05 * k)
        c, s = np.cos(rot), np.sin(rot)
        h = H6.copy()
        h[:, :2] = h[:, :2] @ np.array([[c, -s], [s, c]])
        hs.append(h)
    res = analyze_covariance(
        np.eye(4), FILTERS["static"] * 5, np.array(hs), R_OTHER, BOUND,
        raw(ErrorProcess.gauss_markov(0.0031, 15.0, 5.0)), dt_s=5.0, n_steps=n_steps,
        p0_base=P0, elevation_deg=EL6,
    )  # fmt: skip
    assert res.p_true_ss_m2 is None
    assert res.psd_ratio_min.min() >= 1.0
    assert res.bounded()
    with pytest.raises(InputError, match="sampled at 1 s, the filter runs at 5 s"):
        analyze_covariance(
            np.eye(4), FILTERS["static"], H6, R_OTHER, BOUND, UNDER_BOUND["white"],
            dt_s=5.0, n_steps=10, p0_base=P0,
        )  # fmt: skip


def test_no_steady_state_is_reported_not_raised():
    q = np.diag([0.0, 0.0, 0.0, 1e-2])  # position a random constant: P -> 0, no DARE solution
    res = analyze_covariance(
        np.eye(4), q, H6, R_OTHER, BOUND, raw(UNDER_BOUND["white"]), dt_s=1.0, n_steps=100,
        p0_base=P0, elevation_deg=EL6,
    )  # fmt: skip
    assert res.p_true_ss_m2 is None and res.p_filter_ss_m2 is None
    assert "no steady state" in res.notes[0] and "note:" in res.summary()
    assert res.bounded()
    # sample paths as a 2-D array are split among the measurements
    x = np.arange(2 * 6 * 5, dtype=float).reshape(12, 5)
    y = ErrorSequences(x, 1.0).paths(6, 5)
    assert y.shape == (2, 5, 6)
    np.testing.assert_array_equal(y[1, :, 2], x[8])
    with pytest.raises(InputError, match="fewer than 2 per measurement"):
        ErrorSequences(x[:6], 1.0).paths(6, 5)


def test_sampled_psd_acf_is_exact_for_piecewise_linear():
    f = np.array([0.0, 0.1, 0.25, 0.5])
    s = np.array([4.0, 2.0, 1.0, 1.0])
    sp = SampledPSD(f, s, 1.0)
    fg = np.linspace(0.0, 0.5, 400001)
    sg = np.interp(fg, f, s)
    for k in (0, 1, 3, 17):
        ref = trapezoid(sg * np.cos(2 * np.pi * fg * k), fg)
        assert sp.acf(20)[k] == pytest.approx(ref, abs=1e-9)
    with pytest.raises(InputError, match="Nyquist"):
        SampledPSD(np.array([0.0, 1.0]), np.array([1.0, 1.0]), 1.0)
    with pytest.raises(InputError, match="strictly increasing"):
        SampledPSD(np.array([0.2, 0.1]), np.array([1.0, 1.0]), 1.0)
    with pytest.raises(InputError, match="spectral radius"):
        ErrorProcess([[1.0]], [[1.0]], [1.0], 0.0, 1.0)


def test_result_object_properties():
    p = np.array([np.eye(2), 2 * np.eye(2)])
    t = np.array([0.5 * np.eye(2), np.array([[2.0, 1.0], [1.0, 1.0]])])
    res = CovarianceAnalysis(p, t, None, None, "state_space", 1.0)
    assert res.max_variance_ratio == pytest.approx(1.0)
    # a combination of the two states exceeds the filter variance although no diagonal does
    assert res.max_eig_ratio == pytest.approx((3 + math.sqrt(5)) / 4)
    assert res.worst_step == 1 and not res.bounded()


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
