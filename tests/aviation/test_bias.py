"""Bias propagation through a Kalman filter and the alert-limit probability (seed 003)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from psdbound.aviation import (
    bias_response,
    fault_threshold,
    los_from_az_el,
    prob_horizontal_exceeds,
    projection_matrix,
)
from psdbound.errors import InputError
from psdbound.kalman import pvt_model

AZ = np.array([10.0, 80.0, 150.0, 200.0, 260.0, 320.0, 45.0, 120.0])
EL = np.array([12.0, 25.0, 38.0, 47.0, 60.0, 75.0, 85.0, 30.0])
U = los_from_az_el(AZ, EL)
G = np.column_stack([-U, np.ones(EL.size)])
R = 0.3**2 * np.eye(EL.size)


def _static(n_steps: int, onset: int, bias: np.ndarray):
    return bias_response(
        np.eye(4),
        np.zeros((4, 4)),
        G,
        R,
        bias,
        n_steps=n_steps,
        onset_step=onset,
        p0=1e6 * np.eye(4),
    )


def test_static_least_squares_limit_is_s_times_bias():
    # bias from the first epoch, static state, diffuse prior: error = -S b at every step
    b = np.zeros(EL.size)
    b[1] = 5.0
    s = projection_matrix(U, np.full(EL.size, 0.3))
    res = _static(20, 0, b)
    assert res.mean_error == pytest.approx(np.tile(-s @ b, (20, 1)), rel=1e-5, abs=1e-8)


def test_static_onset_after_k_clean_epochs():
    # recursive least squares: after K clean and n biased epochs, error = -n/(K+n) S b
    b = np.zeros(EL.size)
    b[1] = 5.0
    k = 10
    s = projection_matrix(U, np.full(EL.size, 0.3))
    res = _static(40, k, b)
    for n in (1, 5, 30):
        assert res.mean_error[k + n - 1] == pytest.approx(
            -n / (k + n) * (s @ b), rel=1e-5, abs=1e-8
        )
    assert (res.mean_error[:k] == 0).all()


def test_pvt_filter_converges_to_a_constant_error():
    # seed 003 Fig. 4: after a transient the deterministic error settles
    f, q, h = pvt_model(U, 1.0, accel_psd_m2_s3=1e-4)
    b = np.zeros(EL.size)
    b[1] = 5.0
    res = bias_response(f, q, h, R, b, n_steps=600, onset_step=200)
    e = np.linalg.norm(res.mean_error[:, :2], axis=1)
    assert e[:200] == pytest.approx(np.zeros(200), abs=1e-9)
    assert e[-1] == pytest.approx(e[-50], rel=1e-3)
    assert res.peak_to_final() >= 1.0


def test_exceedance_closed_forms():
    # isotropic zero mean: Rayleigh tail exp(-AL^2 / (2 s^2))
    for al in (1.0, 3.0, 6.0):
        assert prob_horizontal_exceeds([0, 0], np.eye(2) * 0.25, al) == pytest.approx(
            np.exp(-(al**2) / 0.5), rel=1e-7
        )
    # isotropic with a mean: non-central chi-square with 2 dof
    p = prob_horizontal_exceeds([1.2, -0.9], np.eye(2) * 0.49, 4.5)
    assert p == pytest.approx(stats.ncx2.sf(4.5**2 / 0.49, 2, (1.2**2 + 0.9**2) / 0.49), rel=1e-6)


def test_exceedance_anisotropic_against_monte_carlo():
    rng = np.random.default_rng(5)
    c = np.array([[1.0, 0.6], [0.6, 0.5]])
    m = np.array([0.5, -0.3])
    x = rng.multivariate_normal(m, c, 400_000)
    mc = np.mean(np.hypot(x[:, 0], x[:, 1]) > 2.0)
    assert prob_horizontal_exceeds(m, c, 2.0) == pytest.approx(mc, rel=0.02)


def test_fault_threshold_seed003_criterion():
    # seed 003 Table 1 / eq. 14: taxi HAL 4.5 m, P_IR 1e-9, fault if P >= 0.1 P_IR.
    # Isotropic 0.3 m error, 1 m of bias -> 0.8 m of horizontal error: the threshold
    # is where the non-central chi-square tail reaches 1e-10.
    c = np.eye(2) * 0.09
    b = fault_threshold([0.8, 0.0], c, 4.5, 0.1 * 1e-9)
    lam = (0.8 * b) ** 2 / 0.09
    assert stats.ncx2.sf(4.5**2 / 0.09, 2, lam) == pytest.approx(1e-10, rel=1e-5)
    assert 0 < b < 4.5 / 0.8


def test_bad_input():
    with pytest.raises(InputError, match="bias_m"):
        _static(3, 0, np.zeros(3))
    with pytest.raises(InputError, match="positive definite"):
        prob_horizontal_exceeds([0, 0], np.zeros((2, 2)), 1.0)
