"""Windows -> PSDs -> bound: simulated GMRP + white noise and real data."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, UPC1_OBS, UPC2_OBS, UPC_NAV, shared_file
from scipy.signal import lfilter

from psdbound.arcs import find_arcs
from psdbound.errors import InputError, NoDataError
from psdbound.io import read_obs, read_orbit
from psdbound.isolation import MultipathSeries, isolate_dual_antenna, isolate_dual_frequency
from psdbound.spectra import BoundModel, estimate_psd, fit_bound
from psdbound.stationarity import find_stationary_windows

SETS = [(0.005, 45.0, 0.002), (0.04, 70.0, 0.009), (0.01, 10.0, 0.001)]


def gm_plus_white(n, sigma, tau, sigma_wn, dt, seed):
    rng = np.random.default_rng(seed)
    phi = np.exp(-dt / tau)
    w = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    w[0] = rng.normal(0.0, sigma)  # exact stationary start
    return lfilter([1.0], [1.0, -phi], w) + rng.normal(0.0, sigma_wn, n)


@pytest.mark.slow
@pytest.mark.parametrize(("sigma", "tau", "sigma_wn"), SETS)
@pytest.mark.parametrize(
    ("method", "options"),
    [("welch", {"nperseg": 2048}), ("multitaper", {"nw": 64})],
)
def test_bound_of_long_simulation_is_tight(sigma, tau, sigma_wn, method, options):
    """24 h at 1 Hz: bound variance <= 1.5 x true variance (and >= it)."""
    dt = 1.0
    x = gm_plus_white(86400, sigma, tau, sigma_wn, dt, seed=2)
    p = estimate_psd(x, dt, method=method, **options)
    b = fit_bound([p], dt)
    true = sigma**2 + sigma_wn**2
    ratio = b.total_variance_m2 / true
    print(
        f"{method} {options} (dof {np.median(p.dof):.0f}) sigma={sigma} tau={tau} "
        f"wn={sigma_wn}: bound {b.sigma_gm_m:.4f} m / {b.tau_s:.1f} s / {b.sigma_wn_m:.4f} m, "
        f"variance ratio {ratio:.2f}"
    )
    assert 1.0 <= ratio <= 1.5
    assert b.margins.min() >= 1.0


def test_windows_psds_bound_pipeline():
    """The model/results pair on a simulated arc: every window bounded, summary complete."""
    dt, n = 1.0, 4 * 3600
    x = gm_plus_white(n, 0.005, 45.0, 0.002, dt, seed=4)
    series = MultipathSeries(
        "DA",
        1.3e9 + dt * np.arange(n),
        x,
        np.full(n, 90.0),
        np.zeros(n, dtype=np.intp),
        ("G01-G02",),
        ("L1C",),
        0.5,
        dt,
    )
    ws = find_stationary_windows(series, min_length_s=600, test="thesis", overlap=True)
    for est in ("multitaper", "welch", "blackman-tukey"):
        res = BoundModel(ws, estimator=est).fit(rule="envelope")
        assert len(res.psds) == len(ws) and res.margins.size == len(ws)
        assert res.margins.min() >= 1.0
        for p in res.psds:
            assert np.all(res.bound.psd(p.f_hz) >= p.psd_m2_hz * (1 - 1e-12))
        text = res.summary()
        assert est in text and "elevation mapping" in text and "windows" in text


def test_pooled_rule_refuses_overlapping_windows():
    rng = np.random.default_rng(1)
    n, dt = 4000, 1.0
    series = MultipathSeries(
        "DA",
        1.3e9 + dt * np.arange(n),
        rng.normal(0, 0.003, n),
        np.full(n, 90.0),
        np.zeros(n, dtype=np.intp),
        ("G01-G02",),
        ("L1C",),
        0.5,
        dt,
    )
    slid = find_stationary_windows(series, min_length_s=600, test="thesis", overlap=True)
    with pytest.raises(InputError, match="disjoint windows"):
        BoundModel(slid).fit()
    tiled = find_stationary_windows(series, min_length_s=600)
    res = BoundModel(tiled).fit()
    assert res.rule == "pooled" and res.bound.margins.min() >= 1.0
    assert "95 % confidence" in res.confidence_statement()


def test_no_window_is_an_error():
    from psdbound.stationarity import THESIS_MAPPING, WindowSet

    empty = WindowSet((), np.zeros(0), 1.0, THESIS_MAPPING, {}, n_tests=3)
    with pytest.raises(NoDataError, match="no stationary window to bound"):
        BoundModel(empty)


@pytest.mark.realdata
def test_real_bounds_esbc_df_and_upc_da():
    obs = read_obs(shared_file(ESBC_OBS), systems="G")
    nav = read_orbit(shared_file(ESBC_NAV))
    df = isolate_dual_frequency(
        find_arcs(obs, ("L1C", "L2W"), orbit=nav, elevation_mask_deg=10.0), 9.55e-4
    )
    res_df = BoundModel(find_stationary_windows(df)).fit()
    o1, o2 = read_obs(shared_file(UPC1_OBS)), read_obs(shared_file(UPC2_OBS))
    da = isolate_dual_antenna(o1, o2, read_orbit(shared_file(UPC_NAV)))
    res_da = BoundModel(find_stationary_windows(da)).fit()
    for name, res in (("ESBC DF", res_df), ("UPC DA", res_da)):
        b = res.bound
        print(
            f"{name}: {res.estimator}: sigma_GM {100 * b.sigma_gm_m:.2f} cm, tau {b.tau_s:.0f} s, "
            f"sigma_WN {100 * b.sigma_wn_m:.2f} cm ({len(res.windows)} windows)"
        )
        assert 1e-4 < b.sigma_gm_m < 0.05  # millimetres to centimetres, not metres
        assert b.margins.min() >= 1.0
    assert res_df.bound.dt_s == 30.0 and res_da.bound.dt_s == 1.0
    assert res_df.bound.f_max_hz <= 1 / 60 + 1e-12  # never past Nyquist
