"""Orbit sources of the cutoff: the nominal constellations and the YUMA almanac."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_SP3, shared_file

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError
from psdbound.io.geometry import geodetic_to_ecef, satellite_azel
from psdbound.io.timescales import calendar_to_gps_s
from psdbound.ionosphere import (
    CHICAGO,
    almanac_from_navigation,
    nominal_constellation,
    read_yuma,
    write_yuma,
)


def test_nominal_constellation_geometry():
    gps = nominal_constellation("G")
    assert len(gps.satellites) == 24 and gps.satellites[0] == "G01"
    t = 1.26e9 + np.array([0.0, SIDEREAL_DAY_S / 2, SIDEREAL_DAY_S])
    for sat in ("G01", "G13", "G24"):
        r = gps.positions_ecef_m(sat, t)
        np.testing.assert_allclose(np.linalg.norm(r, axis=1), 26_559.7e3, rtol=1e-12)
        assert gps.period_s(sat) == pytest.approx(SIDEREAL_DAY_S / 2)
        np.testing.assert_allclose(r[2], r[0], atol=1e-3)  # ECEF repeat after a sidereal day
    gal = nominal_constellation("E")
    assert len(gal.satellites) == 24
    r = gal.positions_ecef_m("E07", t)
    np.testing.assert_allclose(np.linalg.norm(r, axis=1), 29_600e3, rtol=1e-12)
    assert gal.period_s("E07") / 3600 == pytest.approx(14.079, abs=1e-3)
    both = nominal_constellation("GE")
    assert len(both.satellites) == 48
    assert np.all(np.isnan(gps.positions_ecef_m("G31", t)))
    with pytest.raises(ValueError, match="no nominal constellation"):
        nominal_constellation("R")


def test_nominal_constellation_visibility_at_chicago():
    gps = nominal_constellation("G")
    rx = geodetic_to_ecef(CHICAGO.lat_deg, CHICAGO.lon_deg, 0.0)
    t = float(calendar_to_gps_s(2020, 1, 6, 0, 0, 0)) + 300.0 * np.arange(288)
    el = np.array([satellite_azel(gps, s, t, rx)[1] for s in gps.satellites])
    in_view = (el >= 10.0).sum(axis=0)
    assert 4 <= in_view.min() and in_view.max() <= 12
    assert 6 <= in_view.mean() <= 10


def test_yuma_round_trip(tmp_path):
    gps = nominal_constellation("G")
    from psdbound.ionosphere.almanac import Almanac

    toa = 1.26e9
    n = 4
    alm = Almanac(
        sats=("G01", "G02", "G03", "G04"),
        toa_gps_s=np.full(n, toa),
        e=np.array([0.01, 0.0, 0.005, 0.02]),
        sqrt_a=np.full(n, 5153.6),
        i0_rad=np.full(n, 0.96),
        omega_dot_rad_s=np.full(n, -8e-9),
        omega0_rad=np.array([0.1, 1.2, -2.0, 3.0]),
        omega_rad=np.array([0.5, 0.0, -1.0, 2.0]),
        m0_rad=np.array([0.0, 1.0, 2.0, -3.0]),
        af0_s=np.zeros(n),
        af1=np.zeros(n),
        health=np.array([0, 0, 0, 63]),
    )
    p = write_yuma(alm, tmp_path / "a.yuma")
    back = read_yuma(p, near_gps_s=toa)
    assert back.satellites == ("G01", "G02", "G03")  # G04 unhealthy
    tt = toa + np.linspace(-86400, 86400, 7)
    for s in back.satellites:
        np.testing.assert_allclose(
            back.positions_ecef_m(s, tt), alm.positions_ecef_m(s, tt), atol=0.5
        )
        assert np.all(
            np.abs(np.linalg.norm(back.positions_ecef_m(s, tt), axis=1) - 5153.6**2)
            < 0.03 * 5153.6**2
        )
    assert gps.satellites  # nominal and almanac objects share the OrbitSource surface
    bad = tmp_path / "bad.yuma"
    bad.write_text("******** Week 109 almanac for PRN-01 ********\nID: 01\nHealth: zero\n")
    with pytest.raises(InputError, match="line 3.*'Health'"):
        read_yuma(bad)


@pytest.mark.realdata
def test_almanac_from_broadcast_matches_sp3_within_a_few_km():
    from psdbound.io import read_orbit

    nav = read_orbit(shared_file(ESBC_NAV))
    sp3 = read_orbit(shared_file(ESBC_SP3))
    t0 = float(calendar_to_gps_s(2020, 6, 25, 12, 0, 0))
    alm = almanac_from_navigation(nav, t0)
    assert len(alm.satellites) >= 30
    t = t0 + np.linspace(-11, 11, 23) * 3600
    errs = []
    for s in alm.satellites:
        d = np.linalg.norm(alm.positions_ecef_m(s, t) - sp3.positions_ecef_m(s, t), axis=1)
        if np.any(np.isfinite(d)):
            errs.append(np.nanmax(d))
    assert np.max(errs) < 5e3
