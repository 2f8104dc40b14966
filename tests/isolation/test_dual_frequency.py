"""Dual-frequency isolation, high-pass filters and the filter safety check."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, GRAS_OBS, NYA1_NAV, NYA1_OBS, shared_file
from samples import LAM1, LAM2, make_obs

from psdbound.arcs import find_arcs
from psdbound.errors import InputError, NoDataError
from psdbound.io import read_obs, read_orbit
from psdbound.isolation import (
    DF_SCALING,
    HighPass,
    filter_safety_check,
    isolate_dual_frequency,
)

F1, F2 = 1575.42e6, 1227.60e6
FC = 9.55e-4


def gmrp(n, sigma, tau_s, dt_s, rng):
    phi = np.exp(-dt_s / tau_s)
    w = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    x = np.empty(n)
    x[0] = rng.normal(0.0, sigma)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + w[k]
    return x


def simulate_df(n=7200, dt=1.0, seed=0, sigma=0.003, tau=5.0, sine_m=0.004):
    """Phases (m): slow ionosphere, ambiguities, per-carrier multipath.

    Multipath per carrier = GMRP(sigma, tau) + a sinusoid of amplitude
    ``sine_m`` and random period 150-400 s (a reflector seen by a moving
    platform), i.e. mostly above the 9.55e-4 Hz cutoff.
    """
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    rho = 2.2e7 + 700.0 * t
    tec_m = 3.0 + 1.5 * np.sin(2 * np.pi * t / 14400.0) + 0.4 * np.sin(2 * np.pi * t / 5400.0)
    i1, i2 = tec_m, tec_m * (F1 / F2) ** 2
    mp1 = gmrp(n, sigma, tau, dt, rng)
    mp2 = gmrp(n, sigma, tau, dt, rng)
    for mp in (mp1, mp2):
        mp += sine_m * np.sin(2 * np.pi * t / rng.uniform(150, 400) + rng.uniform(0, 6.3))
    l1 = rho - i1 + 1234 * LAM1 + mp1
    l2 = rho - i2 - 567 * LAM2 + mp2
    truth = (mp1 - mp2) * DF_SCALING
    return make_obs(l1, l2, interval_s=dt, t=1.3e9 + t), truth


@pytest.mark.parametrize("kind", ["butter", "cheby2", "fir"])
@pytest.mark.parametrize("seed", [0, 1])
def test_recovers_injected_multipath(kind, seed):
    obs, truth = simulate_df(seed=seed)
    arcs = find_arcs(obs, min_length_s=600)
    s = isolate_dual_frequency(arcs, FC, highpass=HighPass(kind=kind))
    assert s.method == "DF" and s.scaling == pytest.approx(1 / np.sqrt(2))
    rec = s.value_m
    truth = truth[np.isin(obs.t_gps_s, s.t_gps_s)]
    r = np.corrcoef(rec, truth)[0, 1]
    err = np.sqrt(np.mean((rec - truth) ** 2)) / np.sqrt(np.mean(truth**2))
    print(f"{kind} seed {seed}: correlation {r:.3f}, RMS error {100 * err:.1f} % of truth")
    assert r >= 0.9 and err <= 0.2


@pytest.mark.parametrize("tau", [10.0, 20.0, 60.0])
def test_removed_multipath_matches_filter_response(tau):
    """Error power = integral of S_GM(f) (1 - G(f))^2 with G the zero-phase response.

    This is the price of the DF method: multipath power below f_c goes with
    the ionosphere. A first-order GMRP loses more the longer its tau.
    """
    dt, n = 1.0, 86400
    obs, truth = simulate_df(n=n, tau=tau, sigma=0.004, sine_m=0.0, seed=7)
    s = isolate_dual_frequency(find_arcs(obs, min_length_s=600), FC)
    truth = truth[np.isin(obs.t_gps_s, s.t_gps_s)]
    err2 = np.mean((s.value_m - truth) ** 2) / np.mean(truth**2)
    f = np.linspace(0.0, 0.5 / dt, 400001)[1:]
    psd = 1.0 / (1.0 + (2 * np.pi * f * tau) ** 2)
    g = HighPass().response(f, dt, FC)
    predicted = np.trapezoid(psd * (1 - g) ** 2, f) / np.trapezoid(psd, f)
    print(f"tau {tau:g} s: error power {100 * err2:.2f} %, predicted {100 * predicted:.2f} %")
    assert err2 == pytest.approx(predicted, rel=0.2)


def test_trim_removes_edges_and_is_recorded():
    obs, truth = simulate_df(n=5000)
    s = isolate_dual_frequency(find_arcs(obs, min_length_s=600), FC)
    k = int(np.ceil(1 / FC))
    assert s.t_gps_s.size == 5000 - 2 * k
    assert s.meta["filter"]["edge"] == "trim" and s.meta["filter"]["trim_s"] == k
    np.testing.assert_allclose(s.t_gps_s[0] - obs.t_gps_s[0], k)


def test_zero_phase_response_closed_form():
    """Butterworth forward-backward: |H|^2 = 1 / (1 + (f_c/f)^(2n)) squared."""
    hp = HighPass(order=4)
    f = np.array([2e-4, 5e-4, FC, 2e-3, 1e-2])
    expected = 1.0 / (1.0 + (FC / f) ** 8)
    # scipy designs with a bilinear transform: close to the analog form far below Nyquist
    np.testing.assert_allclose(hp.response(f, 1.0, FC), expected, rtol=2e-3, atol=1e-9)
    assert hp.response(np.array([FC]), 1.0, FC)[0] == pytest.approx(0.5, abs=1e-6)


@pytest.mark.parametrize("kind", ["butter", "cheby2", "fir"])
def test_sinusoids_pass_and_stop(kind):
    dt = 1.0
    t = np.arange(20000) * dt
    fast = 0.01 * np.sin(2 * np.pi * 2e-2 * t)
    slow = 5.0 * np.sin(2 * np.pi * 1e-4 * t)
    y, keep = HighPass(kind=kind).apply(fast + slow, dt, FC)
    assert np.sqrt(np.mean((y - fast)[keep] ** 2)) < 1e-3 * 5.0  # slow term 60+ dB down
    assert keep.sum() == 20000 - 2 * 1048
    y, keep = HighPass(kind=kind, edge="pad").apply(fast + slow, dt, FC)
    assert keep.all()


def test_safety_check_synthetic():
    obs, _ = simulate_df()
    s = isolate_dual_frequency(find_arcs(obs, min_length_s=600), FC)
    chk = filter_safety_check(s)
    assert chk.removed_below[0] > 0.99  # the ionosphere is gone
    assert chk.removed_above[0] < 0.15  # tau = 20 s multipath mostly kept


def test_bad_inputs():
    obs, _ = simulate_df(n=1000)
    with pytest.raises(InputError, match="must lie between 0 and the Nyquist"):
        isolate_dual_frequency(find_arcs(obs, min_length_s=600), 0.6)
    with pytest.raises(NoDataError, match="no arc long enough"):
        isolate_dual_frequency(find_arcs(obs, min_length_s=3600), FC)
    l1 = obs.phase_m("G07", "L1C")
    no_l2 = make_obs(l1, np.full(l1.size, np.nan), interval_s=1.0)
    with pytest.raises(NoDataError, match="second frequency is missing"):
        isolate_dual_frequency(find_arcs(no_l2), FC)
    with pytest.raises(InputError, match="unknown filter kind"):
        HighPass(kind="magic")


@pytest.mark.realdata
@pytest.mark.parametrize(
    ("obs_name", "nav_name", "median_max_mm"),
    [(ESBC_OBS, ESBC_NAV, 10.0), (NYA1_OBS, NYA1_NAV, 25.0)],
)
def test_real_df_residuals_are_millimetres(obs_name, nav_name, median_max_mm):
    obs = read_obs(shared_file(obs_name), systems="G")
    nav = read_orbit(shared_file(nav_name))
    s = isolate_dual_frequency(find_arcs(obs, ("L1C", "L2W"), orbit=nav), FC)
    rms_mm = 1e3 * s.rms_per_arc_m()
    print(
        f"{obs_name}: {s.n_arcs} arcs, per-arc RMS median {np.median(rms_mm):.2f} mm, "
        f"95th percentile {np.percentile(rms_mm, 95):.2f} mm"
    )
    assert s.n_arcs > 40
    assert 0.5 < np.median(rms_mm) < median_max_mm
    assert rms_mm.max() < 50.0  # no metre-level (or decimetre) arc
    assert np.isfinite(s.elevation_deg).all()
    chk = filter_safety_check(s)
    assert np.nanmedian(chk.removed_below) > 0.95


@pytest.mark.realdata
def test_gras_has_no_arc_long_enough():
    obs = read_obs(shared_file(GRAS_OBS), systems="G")
    with pytest.raises(NoDataError, match="no arc long enough: all 10 tracking stretches"):
        isolate_dual_frequency(find_arcs(obs), FC)
