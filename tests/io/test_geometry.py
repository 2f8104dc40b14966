"""Tests of WGS84 / azimuth-elevation geometry (psdbound.io.geometry)."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_SP3, shared_file

from psdbound.constants import OMEGA_E_RAD_S, SPEED_OF_LIGHT_M_S, WGS84_A_M, WGS84_F
from psdbound.io.geometry import (
    OrbitSource,
    azimuth_elevation,
    ecef_to_geodetic,
    enu_rotation,
    geodetic_to_ecef,
    satellite_azel,
)

ESBC_XYZ_M = np.array([3582105.2910, 532589.7313, 5232754.8054])


# ------------------------------------------------------------------ WGS84


def test_known_points():
    np.testing.assert_allclose(geodetic_to_ecef(0.0, 0.0, 0.0), [WGS84_A_M, 0.0, 0.0])
    b = WGS84_A_M * (1 - WGS84_F)
    np.testing.assert_allclose(geodetic_to_ecef(90.0, 0.0, 0.0), [0.0, 0.0, b], atol=1e-9)
    np.testing.assert_allclose(
        geodetic_to_ecef(0.0, 90.0, 100.0), [0.0, WGS84_A_M + 100, 0.0], atol=1e-9
    )
    lat, lon, h = ecef_to_geodetic([0.0, 0.0, -b - 50.0])
    assert lat == pytest.approx(-90.0) and h == pytest.approx(50.0, abs=1e-6)


def test_round_trip_grid():
    lat, lon, h = np.meshgrid(
        np.linspace(-90.0, 90.0, 37),
        np.linspace(-179.0, 180.0, 37),
        np.array([-5000.0, 0.0, 1234.5, 4e5, 2.02e7, 3.6e7]),
        indexing="ij",
    )
    xyz = geodetic_to_ecef(lat, lon, h)
    assert xyz.shape == lat.shape + (3,)
    lat2, lon2, h2 = ecef_to_geodetic(xyz)
    np.testing.assert_allclose(lat2, lat, rtol=0, atol=1e-9)
    pole = np.abs(lat) == 90.0  # longitude undefined at the poles
    dlon = (lon2 - lon + 180.0) % 360.0 - 180.0
    np.testing.assert_allclose(dlon[~pole], 0.0, atol=1e-9)
    np.testing.assert_allclose(h2, h, rtol=0, atol=1e-6)
    # and back to ECEF
    np.testing.assert_allclose(geodetic_to_ecef(lat2, lon2, h2), xyz, rtol=0, atol=1e-6)


def test_esbc_position():
    lat, lon, h = ecef_to_geodetic(ESBC_XYZ_M)
    assert lat == pytest.approx(55.4936, abs=1e-4)  # Esbjerg, Denmark
    assert lon == pytest.approx(8.4568, abs=1e-4)
    assert 0.0 < h < 100.0


def test_enu_rotation_orthonormal():
    r = enu_rotation(np.array([10.0, -45.0, 89.0]), np.array([0.0, 120.0, -60.0]))
    assert r.shape == (3, 3, 3)
    np.testing.assert_allclose(
        r @ np.swapaxes(r, -1, -2), np.broadcast_to(np.eye(3), r.shape), atol=1e-15
    )
    np.testing.assert_allclose(np.linalg.det(r), 1.0)
    # up is the ellipsoid normal
    lat, lon = 30.0, 40.0
    p0 = geodetic_to_ecef(lat, lon, 0.0)
    p1 = geodetic_to_ecef(lat, lon, 1000.0)
    np.testing.assert_allclose(enu_rotation(lat, lon) @ (p1 - p0), [0, 0, 1000.0], atol=1e-6)


# ------------------------------------------------------------------ az/el


@pytest.mark.parametrize(("lat", "lon"), [(55.49, 8.46), (-33.0, 151.0), (0.0, 0.0), (78.9, 11.9)])
def test_azimuth_elevation_cardinal_directions(lat, lon):
    rx = geodetic_to_ecef(lat, lon, 10.0)
    r = enu_rotation(lat, lon)
    east, north, up = r[0], r[1], r[2]
    d = 2.0e7
    sats = np.stack(
        [
            rx + d * up,
            rx + d * north,
            rx + d * east,
            rx - d * north,
            rx - d * east,
            rx + d * (north + up) / np.sqrt(2),
        ]
    )
    az, el = azimuth_elevation(rx, sats)
    assert el[0] == pytest.approx(90.0, abs=1e-9)
    np.testing.assert_allclose(el[1:5], 0.0, atol=1e-9)
    np.testing.assert_allclose(az[1:5], [0.0, 90.0, 180.0, 270.0], atol=1e-9)
    assert az[5] == pytest.approx(0.0, abs=1e-9) and el[5] == pytest.approx(45.0, abs=1e-9)
    assert np.all((az >= 0.0) & (az < 360.0))


def test_azimuth_just_west_of_north_in_range():
    rx = geodetic_to_ecef(10.0, 20.0, 0.0)
    r = enu_rotation(10.0, 20.0)
    sat = rx + 1e7 * r[1] - 1e-3 * r[0]  # a hair west of north
    az, _ = azimuth_elevation(rx, sat)
    assert 359.9 < az < 360.0


def test_nan_positions_propagate():
    az, el = azimuth_elevation(ESBC_XYZ_M, np.full((2, 3), np.nan))
    assert np.isnan(el).all()


class _LinearOrbit:
    """Satellite on a straight line in ECEF; records the times asked for."""

    def __init__(self, p0: np.ndarray, v: np.ndarray, t0: float) -> None:
        self.p0, self.v, self.t0 = p0, v, t0
        self.calls: list[np.ndarray] = []

    def positions_ecef_m(self, sat, t_gps_s):
        t = np.atleast_1d(np.asarray(t_gps_s, dtype=float))
        self.calls.append(t)
        return self.p0 + np.outer(t - self.t0, self.v)


def _rot_z(xyz: np.ndarray, angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.stack(
        [c * xyz[..., 0] + s * xyz[..., 1], -s * xyz[..., 0] + c * xyz[..., 1], xyz[..., 2]],
        axis=-1,
    )


def test_satellite_azel_light_time_and_earth_rotation():
    rx = geodetic_to_ecef(45.0, 10.0, 100.0)
    up = enu_rotation(45.0, 10.0)[2]
    t0 = 1000.0  # small, so that t_rx - t_tx is exact to ~1e-13 s
    orbit = _LinearOrbit(rx + 2.0e7 * up, np.array([3000.0, -1500.0, 500.0]), t0)
    assert isinstance(orbit, OrbitSource)
    t_rx = t0 + np.array([0.0, 10.0, 20.0])
    az, el = satellite_azel(orbit, "G01", t_rx, rx)
    t_tx = orbit.calls[-1]
    tau = t_rx - t_tx
    # the light-time equation is satisfied (to far better than a nanosecond)
    pos = _rot_z(orbit.positions_ecef_m("G01", t_tx), OMEGA_E_RAD_S * tau)
    np.testing.assert_allclose(
        np.linalg.norm(pos - rx, axis=1) / SPEED_OF_LIGHT_M_S, tau, rtol=0, atol=1e-11
    )
    assert np.all((tau > 0.066) & (tau < 0.067))
    az_ref, el_ref = azimuth_elevation(rx, pos)
    np.testing.assert_allclose(el, el_ref, atol=1e-12)
    np.testing.assert_allclose(az, az_ref, atol=1e-9)
    # Earth rotation during the travel time matters: omega_e * tau * r ~ 30 m
    _, el_no_rot = azimuth_elevation(rx, orbit.positions_ecef_m("G01", t_tx))
    assert np.all(np.abs(el_no_rot - el) > 1e-5)


def test_satellite_azel_nan_where_no_orbit():
    class _Nowhere:
        def positions_ecef_m(self, sat, t_gps_s):
            return np.full((np.atleast_1d(t_gps_s).shape[0], 3), np.nan)

    az, el = satellite_azel(_Nowhere(), "G01", np.array([0.0, 1.0]), ESBC_XYZ_M)
    assert az.shape == (2,) and np.isnan(az).all() and np.isnan(el).all()


@pytest.mark.realdata
def test_navigation_and_sp3_are_orbit_sources():
    from psdbound.io.nav import read_nav
    from psdbound.io.sp3 import read_sp3

    nav = read_nav(shared_file(ESBC_NAV))
    sp3 = read_sp3(shared_file(ESBC_SP3))
    assert isinstance(nav, OrbitSource) and isinstance(sp3, OrbitSource)
    t = sp3.t_gps_s[10] + np.arange(0.0, 3600.0, 30.0)
    az, el = satellite_azel(sp3, "G05", t, ESBC_XYZ_M)
    assert np.isfinite(el).all() and np.all((el >= -90) & (el <= 90))
    assert np.all((az >= 0) & (az < 360))
