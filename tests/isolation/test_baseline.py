"""Dual-antenna baseline from the double differences: closed form, simulated pair, UPC."""

from __future__ import annotations

import json

import numpy as np
import pytest
import statsmodels.api as sm
from conftest import UPC1_OBS, UPC2_OBS, UPC_NAV, shared_file
from scipy.signal import lfilter

import psdbound
from psdbound.io import read_obs, read_orbit
from psdbound.io.geometry import ecef_to_geodetic, enu_rotation
from psdbound.isolation import (
    baseline_note,
    estimate_baseline_correction,
    isolate_dual_antenna,
)
from psdbound.simulate import preset, simulate

RX1 = np.array([4789013.0, 176610.2, 4195034.8])  # UPC1, near Barcelona
ROT = enu_rotation(*ecef_to_geodetic(RX1)[:2])  # ECEF -> east, north, up


def _arcs(rng, d_m, n_arcs=12, n=600, noise_m=0.003, rho=0.99):
    """Arcs of DD = G.d + ambiguity + AR(1) noise, G from slowly turning LOS vectors."""
    dd, los = [], []
    for _ in range(n_arcs):
        t = np.linspace(0.0, 1.0, n)
        a0, w = rng.uniform(0, 2 * np.pi, 2), rng.uniform(0.3, 1.0, 2)
        u = [
            np.stack(
                [np.cos(a0[k] + w[k] * t), np.sin(a0[k] + w[k] * t), 0.5 + 0.3 * t * (k - 0.5)],
                axis=1,
            )
            for k in range(2)
        ]
        u = [x / np.linalg.norm(x, axis=1, keepdims=True) for x in u]
        g = u[0] - u[1]
        e = lfilter(
            [np.sqrt(1 - rho**2)],
            [1.0, -rho],
            rng.normal(0, noise_m, n),
            zi=[rho * rng.normal(0, noise_m)],
        )[0]
        dd.append(g @ d_m + rng.uniform(-5, 5) + e)
        los.append(g)
    return dd, los


def test_recovers_a_known_correction_within_its_standard_error():
    """Point estimate = statsmodels OLS; jackknife errors honest where CV1 is too small."""
    rng = np.random.default_rng(4)
    d = np.array([1.2, -0.8, 0.5])
    z_jack, z_cv1 = [], []
    for _ in range(100):
        dd, los = _arcs(rng, d)
        est, why = estimate_baseline_correction(dd, los, RX1)
        assert est is not None and why == ""
        assert est.rms_before_m > 0.1 and est.rms_after_m < 0.01
        assert est.n_arcs == 12 and est.n_arcs_excluded == 0
        x = np.concatenate([g - g.mean(axis=0) for g in los])
        y = np.concatenate([v - v.mean() for v in dd])
        groups = np.repeat(np.arange(len(dd)), [v.size for v in dd])
        ols = sm.OLS(y, x).fit(cov_type="cluster", cov_kwds={"groups": groups})
        np.testing.assert_allclose(est.correction_m, ols.params, rtol=1e-9, atol=1e-12)
        z_jack.append(ROT @ (est.correction_m - d) / est.sigma_enu_m)
        z_cv1.append(ROT @ (ols.params - d) / np.sqrt(np.diag(ROT @ ols.cov_params() @ ROT.T)))
    s_jack, s_cv1 = np.std(z_jack, axis=0), np.std(z_cv1, axis=0)
    print(f"\nstd of z: jackknife {np.round(s_jack, 2)}, CV1 sandwich {np.round(s_cv1, 2)}")
    # with 12 arcs z is roughly Student-t with 11 degrees of freedom (sd 1.1)
    assert np.all(s_jack < 1.4) and np.all(s_jack > 0.8)
    assert s_cv1.mean() > s_jack.mean() + 0.15  # the sandwich is too small with 12 arcs


def test_an_arc_with_a_slip_is_left_out():
    rng = np.random.default_rng(5)
    d = np.array([0.3, 0.2, -0.1])
    dd, los = _arcs(rng, d)
    dd[3] = dd[3].copy()
    dd[3][300:] += 0.19  # one cycle, undetected
    est, _ = estimate_baseline_correction(dd, los, RX1)
    assert est is not None and est.n_arcs_excluded == 1
    assert np.linalg.norm(est.correction_m - d) < 0.01


def test_too_few_arcs_or_no_geometry_change_give_a_reason():
    rng = np.random.default_rng(6)
    dd, los = _arcs(rng, np.zeros(3), n_arcs=3)
    est, why = estimate_baseline_correction(dd, los, RX1)
    assert est is None and "3 double-difference arcs" in why
    dd, los = _arcs(rng, np.zeros(3))
    frozen = [np.repeat(g[:1], g.shape[0], axis=0) for g in los]
    est, why = estimate_baseline_correction(dd, frozen, RX1)
    assert est is None and "geometry" in why
    assert "not checked" in baseline_note({"estimate": None, "reason": why})


# --------------------------------------------------------------------------- simulated pair

HEADER_ERROR_ENU_M = (1.2, -0.7, 0.6)  # 1.51 m


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    sc = preset("demo").replace(
        name="pair", header_error_enu_m=HEADER_ERROR_ENU_M, duration_s=2 * 3600.0, seed=3
    )
    return simulate(sc, tmp_path_factory.mktemp("pair"))


def test_simulated_header_error_is_found_and_corrected(pair):
    a, b = (read_obs(p) for p in pair.obs_paths)
    nav = read_orbit(pair.nav_path)
    auto = isolate_dual_antenna(a, b, nav)
    info = auto.meta["baseline_estimate"]
    est = info["estimate"]
    assert info["used"] is True
    # correction = truth - header = -error, within three of its standard errors (the
    # simulated multipath, 3 mm at zenith with b = 9, leaves about 1-3 cm on 2 h)
    miss = np.asarray(est["correction_enu_m"]) + np.asarray(HEADER_ERROR_ENU_M)
    assert np.all(np.abs(miss) < 3 * np.asarray(est["sigma_enu_m"])) and np.all(np.abs(miss) < 0.05)
    assert est["dd_rms_before_m"] > 0.05 and est["dd_rms_after_m"] < 0.02
    truth = json.loads(pair.truth_json_path.read_text())["antenna_positions_m"][1]
    assert np.linalg.norm(np.asarray(auto.meta["positions_m"][1]) - truth) < 0.05
    note = baseline_note(info, auto.meta["markers"])
    assert "PAIR-B 1.5" in note and "corrected" in note
    given = isolate_dual_antenna(a, b, nav, baseline="given")
    assert given.meta["baseline_estimate"]["used"] is False
    assert "kept" in baseline_note(given.meta["baseline_estimate"], given.meta["markers"])
    rms = [
        np.sqrt(np.mean(np.concatenate([x.value_m for x in s.arcs()]) ** 2)) for s in (auto, given)
    ]
    assert rms[1] > 5 * rms[0]


def test_simulated_pair_windows_come_back(pair):
    files = [str(p) for p in pair.obs_paths]
    res = {
        mode: psdbound.fit(files, nav=pair.nav_path, pair=tuple(files), baseline=mode)
        for mode in ("auto", "given")
    }
    cov = {m: r.document["windows"]["covered_fraction"] for m, r in res.items()}
    print(
        f"\ncovered fraction: {cov}; sigma_GM: "
        f"{ {m: round(1e3 * r.bound.sigma_gm_m, 2) for m, r in res.items()} } mm"
    )
    assert cov["auto"] >= 0.95 and res["auto"].verdict == "bounded"
    assert res["given"].bound.sigma_gm_m > 2 * res["auto"].bound.sigma_gm_m
    assert any("antenna position corrected" in w for w in res["auto"].warnings)
    assert res["auto"].document["isolation"]["baseline_estimate"]["used"] is True


# --------------------------------------------------------------------------- UPC (real)


@pytest.mark.realdata
def test_upc_header_positions_agree_and_a_wrong_position_is_corrected():
    o1, o2 = read_obs(shared_file(UPC1_OBS)), read_obs(shared_file(UPC2_OBS))
    nav = read_orbit(shared_file(UPC_NAV))
    header = isolate_dual_antenna(o1, o2, nav)
    info = header.meta["baseline_estimate"]
    assert info["used"] is False  # the header positions agree with the phases to ~2 cm
    assert info["estimate"]["correction_length_m"] < 0.03
    p2 = np.array(o2.header.approx_position_m)
    lat, lon, _ = ecef_to_geodetic(p2)
    offset_enu = np.array([1.2, -0.8, 0.5])
    wrong = p2 + enu_rotation(lat, lon).T @ offset_enu
    fixed = isolate_dual_antenna(o1, o2, nav, receiver2_xyz_m=wrong)
    f = fixed.meta["baseline_estimate"]
    assert f["used"] is True
    # back to where the header puts it, within the header's own 2 cm disagreement
    corr_to_header = np.array(f["estimate"]["correction_enu_m"]) + offset_enu
    assert np.linalg.norm(corr_to_header - info["estimate"]["correction_enu_m"]) < 0.005
    assert f["estimate"]["dd_rms_before_m"] > 0.1 and f["estimate"]["dd_rms_after_m"] < 0.005
    low = [a.rms_m for a in fixed.arcs()]
    ref = [a.rms_m for a in header.arcs()]
    np.testing.assert_allclose(low, ref, atol=5e-4)
