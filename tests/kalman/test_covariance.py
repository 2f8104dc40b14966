"""Augmentation of a filter with the bound's states, and the covariance analysis
(bounded and violated cases, the three methods, the result object)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import trapezoid

from psdbound.errors import InputError
from psdbound.kalman import (
    CovarianceAnalysis,
    ErrorProcess,
    ErrorSequences,
    GaussMarkovBound,
    SampledPSD,
    analyze_covariance,
    augment_gm_states,
)
from psdbound.stationarity.mapping import THESIS_MAPPING


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
        np.eye(4),
        Q,
        H6,
        R_OTHER,
        BOUND,
        truth,
        dt_s=1.0,
        n_steps=n_steps,
        p0_base=P0,
        elevation_deg=EL6,
    )
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
        np.eye(4),
        FILTERS["static"] * 5,
        np.array(hs),
        R_OTHER,
        BOUND,
        raw(ErrorProcess.gauss_markov(0.0031, 15.0, 5.0)),
        dt_s=5.0,
        n_steps=n_steps,
        p0_base=P0,
        elevation_deg=EL6,
    )
    assert res.p_true_ss_m2 is None
    assert res.psd_ratio_min.min() >= 1.0
    assert res.bounded()
    with pytest.raises(InputError, match="sampled at 1 s, the filter runs at 5 s"):
        analyze_covariance(
            np.eye(4),
            FILTERS["static"],
            H6,
            R_OTHER,
            BOUND,
            UNDER_BOUND["white"],
            dt_s=5.0,
            n_steps=10,
            p0_base=P0,
        )


def test_no_steady_state_is_reported_not_raised():
    q = np.diag([0.0, 0.0, 0.0, 1e-2])  # position a random constant: P -> 0, no DARE solution
    res = analyze_covariance(
        np.eye(4),
        q,
        H6,
        R_OTHER,
        BOUND,
        raw(UNDER_BOUND["white"]),
        dt_s=1.0,
        n_steps=100,
        p0_base=P0,
        elevation_deg=EL6,
    )
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


def test_matrices_that_cannot_be_covariances_are_refused():
    """A negative Q or R (or initial covariance) was accepted, or failed deep in numpy."""
    F = np.eye(4)
    for name, q, r in (("Q", -FILTERS["static"], R_OTHER), ("R", FILTERS["static"], -R_OTHER)):
        with pytest.raises(InputError, match=f"{name} must be positive semi-definite"):
            augment_gm_states(F, q, H6, r, BOUND, 1.0, elevation_deg=EL6)
    aug = augment_gm_states(F, FILTERS["static"], H6, R_OTHER, BOUND, 1.0, elevation_deg=EL6)
    with pytest.raises(InputError, match="p0_base must be positive semi-definite"):
        aug.initial_covariance(-P0)
