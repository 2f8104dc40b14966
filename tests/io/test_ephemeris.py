"""Tests of broadcast-ephemeris propagation (psdbound.io.ephemeris)."""

from __future__ import annotations

from dataclasses import fields

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_SP3, shared_file

from psdbound.io.ephemeris import (
    GM_M3_S2,
    OMEGA_E_BY_SYSTEM_RAD_S,
    kepler_positions_ecef_m,
    satellite_clock_s,
    select_records,
    solve_kepler,
)
from psdbound.io.geometry import satellite_azel
from psdbound.io.nav import KeplerEphemerides, read_nav
from psdbound.io.sp3 import read_sp3

A_GPS = 26_559_700.0
# ICD values, written out here so that a wrong constant in the module fails
MU = {"G": 3.986005e14, "J": 3.986005e14, "E": 3.986004418e14, "C": 3.986004418e14}
OMEGA_E = {"G": 7.2921151467e-5, "J": 7.2921151467e-5, "E": 7.2921151467e-5, "C": 7.292115e-5}
T0 = 2100 * 604800.0 + 302400.0  # a toe in the middle of GPS week 2100


def make_eph(n: int = 1, **over) -> KeplerEphemerides:
    """Ephemerides of a circular equatorial orbit, overridable per field."""
    base = {f.name: np.zeros(n) for f in fields(KeplerEphemerides)}
    base["sat"] = np.array(["G01"] * n)
    base["toc_gps_s"] = np.full(n, T0)
    base["toe_gps_s"] = np.full(n, T0)
    base["toe_sow_s"] = np.full(n, T0 % 604800.0)
    base["sqrt_a"] = np.full(n, np.sqrt(A_GPS))
    for k in ("health", "iode", "data_source"):
        base[k] = np.zeros(n, dtype=np.int64)
    for k, v in over.items():
        base[k] = np.asarray(v, dtype=base[k].dtype) if k != "sat" else np.asarray(v)
    return KeplerEphemerides(**base)


# ------------------------------------------------------------------ closed form


@pytest.mark.parametrize("sat", ["G01", "E01", "C20", "J02"])
def test_circular_equatorial_orbit(sat):
    eph = make_eph(sat=[sat])
    t = T0 + np.linspace(-3 * 3600, 3 * 3600, 721)
    xyz = kepler_positions_ecef_m(eph, sat, t)
    r = np.linalg.norm(xyz, axis=1)
    np.testing.assert_allclose(r, A_GPS, rtol=0, atol=1e-6)
    np.testing.assert_allclose(xyz[:, 2], 0.0, atol=1e-6)
    # angular rate in the Earth-fixed frame = mean motion - Earth rotation
    ang = np.unwrap(np.arctan2(xyz[:, 1], xyz[:, 0]))
    rate = np.polyfit(t - T0, ang, 1)[0]
    n0 = np.sqrt(MU[sat[0]] / A_GPS**3)
    assert rate == pytest.approx(n0 - OMEGA_E[sat[0]], rel=1e-12)
    # at toe the satellite sits at longitude OMEGA0 + omega + M0 - omega_e * toe_sow
    lon0 = -OMEGA_E[sat[0]] * (T0 % 604800.0)
    got = np.arctan2(xyz[360, 1], xyz[360, 0])
    assert np.angle(np.exp(1j * (got - lon0))) == pytest.approx(0.0, abs=1e-12)


def test_module_constants():
    assert GM_M3_S2 == MU
    assert OMEGA_E_BY_SYSTEM_RAD_S == OMEGA_E


def test_system_constants_differ():
    # GPS and Galileo mean motions differ through mu: 1.6 ppm -> ~ 1 m/h along track
    t = T0 + 3600.0
    g = kepler_positions_ecef_m(make_eph(sat=["G01"]), "G01", t)
    e = kepler_positions_ecef_m(make_eph(sat=["E01"]), "E01", t)
    d = np.linalg.norm(g - e)
    n_g = np.sqrt(MU["G"] / A_GPS**3)
    n_e = np.sqrt(MU["E"] / A_GPS**3)
    assert d == pytest.approx(abs(n_g - n_e) * 3600.0 * A_GPS, rel=1e-3)


@pytest.mark.parametrize("e", [0.0, 0.001, 0.02, 0.1, 0.2, 0.3])
def test_kepler_equation(e):
    rng = np.random.default_rng(1)
    m = rng.uniform(-10.0, 10.0, 2000)
    big_e = solve_kepler(m, e)
    np.testing.assert_allclose(big_e - e * np.sin(big_e), m, rtol=0, atol=1e-12)


def test_eccentric_orbit_radius_and_inclination():
    e, inc, a = 0.2, np.radians(55.0), A_GPS
    eph = make_eph(e=[e], i0_rad=[inc], omega_rad=[0.7], m0_rad=[0.3])
    t = T0 + np.linspace(-14000, 14000, 200)
    xyz = kepler_positions_ecef_m(eph, "G01", t)
    r = np.linalg.norm(xyz, axis=1)
    assert r.min() >= a * (1 - e) - 1e-6
    assert r.max() <= a * (1 + e) + 1e-6
    lat = np.degrees(np.arcsin(xyz[:, 2] / r))
    assert np.all(np.abs(lat) <= 55.0 + 1e-9)


def test_week_crossover():
    # toe at the very end of a week, times in the next week: continuous motion
    toe = 2100 * 604800.0 + 597600.0
    eph = make_eph(toe_gps_s=[toe], toc_gps_s=[toe], toe_sow_s=[597600.0], e=[0.01], i0_rad=[0.96])
    t = toe + np.array([7199.0, 7200.0, 7201.0])  # crosses the week boundary at +7200
    xyz = kepler_positions_ecef_m(eph, "G01", t)
    v1 = xyz[1] - xyz[0]
    v2 = xyz[2] - xyz[1]
    assert np.linalg.norm(v1) == pytest.approx(np.linalg.norm(v2), rel=1e-4)
    assert 2000.0 < np.linalg.norm(v1) < 5000.0


# ------------------------------------------------------------------ selection


def test_nearest_healthy_record_within_fit_interval():
    toes = T0 + np.array([0.0, 7200.0, 14400.0])
    eph = make_eph(3, toe_gps_s=toes, toc_gps_s=toes, health=[0, 1, 0])
    t = T0 + np.array(
        [-14400.0, -14401.0, 3000.0, 7300.0, 11000.0, 14400.0 + 14400.0, 14400.0 + 14401.0, np.nan]
    )
    idx = select_records(eph, "G01", t)
    # record 1 is unhealthy: 7300 -> record 0 (7300 s) vs record 2 (7100 s) -> 2
    np.testing.assert_array_equal(idx, [0, -1, 0, 2, 2, 2, -1, -1])
    xyz = kepler_positions_ecef_m(eph, "G01", t)
    assert np.isnan(xyz[[1, 6, 7]]).all()
    assert np.isfinite(xyz[[0, 2, 3, 4, 5]]).all()


def test_other_satellite_records_ignored():
    eph = make_eph(2, sat=["G01", "G02"], toe_gps_s=[T0, T0 + 3600], toc_gps_s=[T0, T0 + 3600])
    assert select_records(eph, "G02", [T0])[0] == 1
    assert select_records(eph, "G03", [T0])[0] == -1


def test_galileo_prefers_inav():
    toes = T0 + np.array([0.0, 600.0, 1200.0])
    eph = make_eph(
        3,
        sat=["E05"] * 3,
        toe_gps_s=toes,
        toc_gps_s=toes,
        data_source=[258, 517, 258],
        health=[0, 0, 0],
    )
    # F/NAV record 2 is nearer to t = T0 + 1200, yet the I/NAV record 1 is used
    assert list(select_records(eph, "E05", T0 + np.array([0.0, 1200.0]))) == [1, 1]
    # without a healthy I/NAV record, the F/NAV ones are the fall-back
    eph2 = make_eph(
        3,
        sat=["E05"] * 3,
        toe_gps_s=toes,
        toc_gps_s=toes,
        data_source=[258, 517, 258],
        health=[0, 390, 0],
    )
    assert list(select_records(eph2, "E05", T0 + np.array([0.0, 1200.0]))) == [0, 2]


def test_beidou_geo_is_nan():
    eph = make_eph(2, sat=["C03", "C20"])
    assert np.isnan(kepler_positions_ecef_m(eph, "C03", [T0])).all()
    assert np.isfinite(kepler_positions_ecef_m(eph, "C20", [T0])).all()


def test_clock_polynomial():
    eph = make_eph(af0_s=[1e-4], af1=[1e-11], af2=[1e-18])
    dt = np.array([-3600.0, 0.0, 5000.0])
    got = satellite_clock_s(eph, "G01", T0 + dt)
    # e = 0: no relativistic term
    np.testing.assert_allclose(got, 1e-4 + 1e-11 * dt + 1e-18 * dt**2, rtol=1e-14)


# ------------------------------------------------------------------ real data

ESBC_XYZ_M = np.array([3582105.2910, 532589.7313, 5232754.8054])


@pytest.mark.realdata
def test_broadcast_matches_sp3_esbc():
    """Key acceptance test: broadcast vs precise orbits for a whole day."""
    nav = read_nav(shared_file(ESBC_NAV))
    sp3 = read_sp3(shared_file(ESBC_SP3))
    t = sp3.t_gps_s[0] + np.arange(0.0, 86400.0, 300.0)
    report = {}
    max_del = 0.0
    n_el = 0
    for system in ("G", "E"):
        sats = [s for s in nav.satellites if s[0] == system and s in sp3.sats]
        assert len(sats) >= (28 if system == "G" else 20)
        diffs = []
        for sat in sats:
            d = np.linalg.norm(nav.positions_ecef_m(sat, t) - sp3.positions_ecef_m(sat, t), axis=1)
            diffs.append(d[np.isfinite(d)])
            _, el_b = satellite_azel(nav, sat, t, ESBC_XYZ_M)
            _, el_p = satellite_azel(sp3, sat, t, ESBC_XYZ_M)
            ok = np.isfinite(el_b) & np.isfinite(el_p) & (el_p > 5.0)
            n_el += int(ok.sum())
            if ok.any():
                max_del = max(max_del, float(np.max(np.abs(el_b - el_p)[ok])))
        d = np.concatenate(diffs)
        report[system] = (d.size, float(np.median(d)), float(np.percentile(d, 95)), float(d.max()))
    for system, (n, med, p95, mx) in report.items():
        print(
            f"\n{system}: {n} samples, 3-D broadcast-SP3 median {med:.2f} m, "
            f"95% {p95:.2f} m, max {mx:.2f} m"
        )
    print(f"elevation > 5 deg: {n_el} samples, max |del| {max_del:.2e} deg")
    for system, (n, med, _, _) in report.items():
        assert n > 5000
        assert med < 5.0, system
    assert n_el > 3000
    assert max_del < 0.01
