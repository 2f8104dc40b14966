"""KF-safe design for a set of Gauss-Markov processes (issue 20, parts 2 and 3), and the
KF-ARAIM building blocks (part 4): covariance checks over grids of true processes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import toeplitz

from psdbound.errors import InputError
from psdbound.kalman import (
    ErrorProcess,
    GaussMarkovBound,
    GaussMarkovSet,
    UncertainGMBound,
    analyze_covariance,
    minimum_initial_variance_m2,
    monte_carlo_position_covariance,
    predict_position_covariance,
    pvt_model,
    verify_design,
)

# multipath-like set: tau 20..200 s, sigma 3..5 mm, 2 mm white noise at 1 s
SET = GaussMarkovSet(20.0, 200.0, 0.003, 0.005, sigma_wn_m=0.002, dt_s=1.0)
N_STEPS = 800  # 4 tau_hi: covers the transient of every process of the set


def _six_satellites():
    az = np.deg2rad([0.0, 60.0, 130.0, 200.0, 270.0, 320.0])
    el = np.deg2rad([75.0, 40.0, 25.0, 55.0, 15.0, 35.0])
    los = np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])
    return np.column_stack([-los, np.ones(6)])


# (F, Q, H, R, P0): a 1-state filter (Langel et al.'s one-dimensional problem: a slowly
# drifting scalar seen through the multipath), a 2-state position-velocity filter, and the
# 6-satellite position + clock filters of test_covariance.py (static and kinematic)
H6 = _six_satellites()
FILTERS = {
    "1-state": (np.eye(1), np.eye(1) * 1e-8, np.ones((1, 1)), None, np.eye(1)),
    "2-state": (
        np.array([[1.0, 1.0], [0.0, 1.0]]),
        1e-6 * np.array([[1 / 3, 1 / 2], [1 / 2, 1.0]]),
        np.array([[1.0, 0.0]]),
        None,
        np.eye(2),
    ),
    "6-sat static": (
        np.eye(4),
        np.diag([1e-6] * 3 + [1e-2]),
        H6,
        np.eye(6) * 1e-6,
        np.diag([1.0, 1.0, 1.0, 100.0]),
    ),
    "6-sat kinematic": (
        np.eye(4),
        np.diag([1.0] * 3 + [1e2]),
        H6,
        np.eye(6) * 1e-6,
        np.diag([1.0, 1.0, 1.0, 100.0]),
    ),
}
GRID = SET.grid(n_tau=4, n_sigma=2)  # tau 20, 43, 93, 200 s x sigma 5, 3 mm


def check(design, filt, truths=GRID):
    F, Q, H, R, P0 = FILTERS[filt]
    return verify_design(design, F, Q, H, R, dt_s=1.0, n_steps=N_STEPS, p0_base=P0, truths=truths)


# --------------------------------------------------------------------------- the design
def test_design_formulas_and_export():
    d = SET.design()  # Langel et al. 2021: tau_lo, PSD-dominating variance, minimum P0
    assert d.tau_s == 20.0
    assert d.sigma_gm_m**2 == pytest.approx(0.005**2 * 200 / 20)
    assert d.p0_m2 == pytest.approx(2 * 0.005**2 * 200 / 220)
    assert 0.005**2 < d.p0_m2 < d.sigma_gm_m**2 and not d.stationary
    tight = SET.design("tight")
    assert tight.tau_s == pytest.approx(math.sqrt(20 * 200))
    assert tight.sigma_gm_m**2 == pytest.approx(0.005**2 * math.sqrt(10))
    assert tight.p0_m2 == pytest.approx(2 * 0.005**2 * math.sqrt(10) / (1 + math.sqrt(10)))
    assert SET.design("tight", stationary=True).stationary
    # the state-space export: phi, q constant; P0 the initial variance
    phi, qd, r, p0 = d.to_state_space(1.0)
    assert phi == pytest.approx(math.exp(-1 / 20))
    assert qd == pytest.approx(d.sigma_gm_m**2 * (1 - phi**2))
    assert r == pytest.approx(0.002**2) and p0 == d.p0_m2
    # the design variance grows from P0 to the steady state (non-stationary model)
    v = d.variance_m2(400, 1.0)
    assert v[0] == pytest.approx(d.p0_m2) and v[-1] == pytest.approx(d.sigma_gm_m**2, rel=1e-6)
    assert np.all(np.diff(v) >= -1e-18)
    # the existing single-model export is the steady-state part
    assert isinstance(d.bound, GaussMarkovBound) and d.bound.tau_s == 20.0
    # PSD dominance of the steady-state part over the set (sampled PSDs, 1 s)
    f = np.linspace(0.0, 0.5, 2001)
    for tau, sigma in SET.grid(6, 2):
        truth = SET.process(tau, sigma, 1.0)
        assert np.all(d.bound.sampled_psd(f, 1.0) >= truth.psd(f) * (1 - 1e-12))
    assert "non-stationary" in str(d)
    with pytest.raises(InputError, match="outside"):
        SET.design(500.0)
    with pytest.raises(InputError, match="empty"):
        GaussMarkovSet(50.0, 20.0, 0.003, 0.005)


@pytest.mark.parametrize("filt", list(FILTERS))
@pytest.mark.parametrize("tau_d", ["langel2021", "tight"])
def test_design_bounds_every_process_of_the_set(filt, tau_d):
    """Max generalised eigenvalue of (P_true, P_design) <= 1 at every step (transient
    included) and in steady state, for every true (tau, sigma) of the grid."""
    res = check(SET.design(tau_d), filt)
    assert res.max_eig.shape == (len(GRID),)
    assert res.bounded(rtol=1e-9), (res.worst, res.worst_truth)


@pytest.mark.parametrize(
    ("filt", "min_eig"), [("1-state", 1.3), ("2-state", 1.3), ("6-sat static", 1.1)]
)
def test_naive_single_model_fails(filt, min_eig):
    """Mid-interval tau with the largest sigma, stationary: PSD too low at low (tau_hi)
    or high (tau_lo) frequencies; the filter's covariance is then too small."""
    res = check(SET.naive(), filt)
    assert not res.bounded()
    assert res.worst > min_eig


def test_stationary_start_of_the_tight_model_needs_p0_not_lower():
    """Starting below P0_min breaks the bound in the transient (here at the first steps)."""
    d = SET.design("tight")
    low = UncertainGMBound(SET, d.tau_s, d.sigma_gm_m, 0.005**2 * 0.5, "P0 too small")
    res = check(low, "2-state", truths=[(20.0, 0.005), (200.0, 0.005)])
    assert not res.bounded() and res.worst_step.min() < 50


# ------------------------------------------------------------- minimum initial variance
def test_closed_form_p0_is_the_continuous_limit_of_the_exact_minimum():
    """The exact discrete minimum (rank-one Loewner condition over the horizon) is below
    the closed form at every interval and tends to it as dt -> 0 (0.5 %)."""
    s = GaussMarkovSet(5.0, 20.0, 0.5, 1.0)
    for name in ("langel2021", "tight"):
        d = s.design(name)
        for dt, n in ((1.0, 400), (0.25, 1600)):
            exact = minimum_initial_variance_m2(d.tau_s, d.sigma_gm_m, s, dt, n, n_tau=5)
            assert exact <= d.p0_m2
    d = s.design("tight")
    exact = minimum_initial_variance_m2(d.tau_s, d.sigma_gm_m, s, 0.1, 4000, n_tau=5)
    assert exact == pytest.approx(d.p0_m2, rel=5e-3)
    # and it is a minimum: below it the design covariance of the error sequence is not
    # above the true one in the Loewner order
    dt, n = 1.0, 400
    p0 = minimum_initial_variance_m2(d.tau_s, d.sigma_gm_m, s, dt, n, n_tau=5)
    k = np.arange(n)
    v = math.exp(-dt / d.tau_s) ** k
    for p, ok in ((p0 * 1.001, True), (p0 * 0.95, False)):
        design = toeplitz(d.sigma_gm_m**2 * v) - (d.sigma_gm_m**2 - p) * np.outer(v, v)
        worst = min(
            np.linalg.eigvalsh(design - toeplitz(math.exp(-dt / t) ** k)).min() for t in (5.0, 20.0)
        )
        assert bool(worst > -1e-10) is ok


# ---------------------------------------------------------------------------- KF-ARAIM
def _eight_satellites():
    az = np.deg2rad([10.0, 55.0, 100.0, 150.0, 200.0, 245.0, 290.0, 335.0])
    el = np.deg2rad([80.0, 35.0, 20.0, 50.0, 15.0, 60.0, 30.0, 45.0])
    return np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])


def test_pvt_model_structure():
    u = _eight_satellites()
    F, Q, H = pvt_model(u, 2.0)
    assert F.shape == (8, 8) and H.shape == (8, 8)
    assert F[0, 3] == 2.0 and F[6, 7] == 2.0
    np.testing.assert_allclose(H[:, :3], -u)
    assert np.all(np.linalg.eigvalsh(Q) >= -1e-15)
    with pytest.raises(InputError, match="unit vectors"):
        pvt_model(2 * u, 1.0)


def test_monte_carlo_position_covariance_matches_prediction():
    """True multipath inside the set (GM 60 s, 4 mm + 2 mm white): the empirical position
    covariance from simulated series matches the exact true one within Monte Carlo error
    and stays under the design (predicted) covariance."""
    u = _eight_satellites()
    design = SET.design()
    n_steps, n_paths = 240, 1500
    truth = GaussMarkovBound.from_params(0.004, 60.0, 0.002, 1.0)
    rng = np.random.default_rng(20)
    paths = np.stack(
        [truth.simulate(n_steps, n_series=n_paths, rng=rng) for _ in range(u.shape[0])], axis=-1
    )
    mc = monte_carlo_position_covariance(design, u, paths, 1.0)
    exact = predict_position_covariance(
        design, u, 1.0, n_steps, truth=ErrorProcess.from_bound(truth)
    )
    assert mc.method == "monte_carlo" and exact.method == "state_space"
    np.testing.assert_allclose(mc.p_design_m2, exact.p_design_m2)
    d_mc = np.diagonal(mc.p_true_m2, axis1=1, axis2=2)
    d_ex = np.diagonal(exact.p_true_m2, axis1=1, axis2=2)
    tol = 4 * math.sqrt(2 / n_paths)
    np.testing.assert_allclose(d_mc[10:], d_ex[10:], rtol=tol)
    d_design = np.diagonal(mc.p_design_m2, axis1=1, axis2=2)
    assert np.all(d_mc <= d_design * (1 + tol))
    assert exact.analysis.bounded()
    # design only: the filter's own covariance, no truth
    pred = predict_position_covariance([design] * 8, u, 1.0, 50)
    assert pred.p_true_m2 is None and pred.sigma_true_m is None
    np.testing.assert_allclose(pred.p_design_m2, exact.p_design_m2[:50])
    assert pred.sigma_design_m.shape == (50, 3)
    with pytest.raises(InputError, match="one model per satellite"):
        predict_position_covariance([design] * 3, u, 1.0, 5)
    with pytest.raises(InputError, match="multipath_m must have shape"):
        monte_carlo_position_covariance(design, u, paths[..., :3], 1.0)


def test_analyze_covariance_p0_override():
    F, Q, H, R, P0 = FILTERS["2-state"]
    b = GaussMarkovBound.from_params(0.005, 50.0, 0.002, 1.0)
    truth = ErrorProcess.from_bound(b)
    a = analyze_covariance(F, Q, H, R, b, truth, dt_s=1.0, n_steps=50, p0_base=P0)
    c = analyze_covariance(
        F, Q, H, R, b, truth, dt_s=1.0, n_steps=50, p0_base=P0, p0_gm_m2=0.005**2
    )
    np.testing.assert_allclose(a.p_filter_m2, c.p_filter_m2)
    with pytest.raises(InputError, match="p0_gm_m2"):
        analyze_covariance(F, Q, H, R, b, truth, dt_s=1.0, n_steps=5, p0_base=P0, p0_gm_m2=-1.0)
