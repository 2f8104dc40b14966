"""Bound fitting: exact recovery, provable bound, global tightness (hypothesis)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from psdbound.errors import InputError
from psdbound.spectra.bound import fit_bound
from psdbound.spectra.models import gm_psd_sampled


def psd(f, s):
    return SimpleNamespace(f_hz=np.asarray(f, float), psd_m2_hz=np.asarray(s, float))


@pytest.mark.parametrize(
    ("sigma", "tau", "sigma_wn", "dt"),
    [(0.005, 45.0, 0.002, 1.0), (0.04, 70.0, 0.009, 30.0), (0.01, 10.0, 0.001, 1.0)],
)
@pytest.mark.parametrize("objective", ["variance", "area"])
def test_exact_model_is_recovered(sigma, tau, sigma_wn, dt, objective):
    f = np.linspace(0.5 / (200 * dt), 0.5 / dt, 400)
    s = gm_psd_sampled(f, sigma, tau, dt) + 2 * sigma_wn**2 * dt
    b = fit_bound([psd(f, s)], dt, objective=objective)
    assert b.sigma_gm_m == pytest.approx(sigma, rel=1e-4)
    assert b.tau_s == pytest.approx(tau, rel=1e-3)
    assert b.sigma_wn_m == pytest.approx(sigma_wn, rel=1e-3)
    assert b.margins.min() >= 1.0
    assert "sigma_GM" in b.summary()


@st.composite
def psd_sets(draw):
    dt = draw(st.sampled_from([1.0, 5.0, 30.0]))
    nyq = 0.5 / dt
    sets = []
    for _ in range(draw(st.integers(1, 4))):
        n = draw(st.integers(3, 25))
        f = np.sort(
            np.array(
                draw(st.lists(st.floats(1e-3 * nyq, nyq), min_size=n, max_size=n, unique=True))
            )
        )
        logs = np.array(draw(st.lists(st.floats(-12.0, -3.0), min_size=n, max_size=n)))
        sets.append(psd(f, 10.0**logs))
    return dt, sets


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(psd_sets())
def test_fitted_bound_bounds_and_is_tightest(case):
    dt, sets = case
    b = fit_bound(sets, dt)
    # 1. a bound: model >= data at every frequency of every PSD
    for p in sets:
        assert np.all(b.psd(p.f_hz) >= p.psd_m2_hz * (1 - 1e-12))
    # 2. tightest: no feasible point of a (sigma^2, tau, sigma_wn^2) grid does better
    f = np.concatenate([p.f_hz for p in sets])
    s = np.concatenate([p.psd_m2_hz for p in sets])
    smax = s.max()
    var_grid = np.r_[0.0, np.geomspace(1e-6, 10.0, 60)] * smax / (2 * dt)
    lo, hi = 0.5 * dt, 20.0 / f.min()
    for tau in np.geomspace(lo, hi, 25):
        g = gm_psd_sampled(f, 1.0, tau, dt)
        a = var_grid[:, None, None]
        w = var_grid[None, :, None]
        feasible = np.all(a * g + w * 2 * dt >= s, axis=2)
        if feasible.any():
            best = (a[:, :, 0] + w[:, :, 0])[feasible].min()
            assert best >= b.objective_value * (1 - 1e-6)


def test_upper_confidence_target_is_higher():
    f = np.linspace(0.01, 0.5, 100)
    true = gm_psd_sampled(f, 0.01, 30.0, 1.0) + 2e-6
    dof = 10.0

    class Est:
        f_hz = f
        psd_m2_hz = true

        def confidence_interval(self, level):
            from scipy.stats import chi2

            return (
                dof * true / chi2.ppf(1 - (1 - level) / 2, dof),
                dof * true / chi2.ppf((1 - level) / 2, dof),
            )

    point = fit_bound([Est()], 1.0)
    upper = fit_bound([Est()], 1.0, target="upper", level=0.95)
    assert upper.total_variance_m2 > point.total_variance_m2
    assert upper.target == "upper" and upper.level == 0.95


def test_bad_inputs():
    f = np.linspace(0.01, 0.5, 10)
    with pytest.raises(InputError, match="above the Nyquist"):
        fit_bound([psd(f, np.ones(10))], 2.0)
    with pytest.raises(InputError, match="no positive PSD values"):
        fit_bound([psd(f, np.zeros(10))], 1.0)
    with pytest.raises(InputError, match="unknown objective"):
        fit_bound([psd(f, np.ones(10))], 1.0, objective="magic")


def test_a_variance_the_solver_returns_as_minus_zero_is_zero():
    """Found by hypothesis: HiGHS returned -1e-18 for the white variance (sqrt gave NaN)."""
    from types import SimpleNamespace

    f = np.array(
        [0.00195312, 0.0078125, 0.015625, 0.01763473, 0.0234375, 0.03125, 0.03248409, 0.0625]
    )
    s = np.array([1e-3, 1e-3, 1e-3, 1e-3, 1e-4, 1e-4, 5.233e-4, 1e-4])
    fit = fit_bound([SimpleNamespace(f_hz=f, psd_m2_hz=s)], 5.0)
    m = fit.model
    assert np.isfinite([m.sigma_gm_m, m.tau_s, m.sigma_wn_m]).all() and m.sigma_wn_m >= 0
    assert np.all(m.sampled_psd(f) >= s * (1 - 1e-9))
