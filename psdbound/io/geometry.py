"""Receiver-satellite geometry: WGS84 coordinates, azimuth and elevation.

Conventions: ECEF coordinates in metres, angles in degrees, geodetic
latitude/height on the WGS84 ellipsoid, azimuth clockwise from north in
[0, 360), elevation above the plane normal to the ellipsoid normal.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import OMEGA_E_RAD_S, SPEED_OF_LIGHT_M_S, WGS84_A_M, WGS84_F

__all__ = [
    "OrbitSource",
    "ecef_to_geodetic",
    "geodetic_to_ecef",
    "enu_rotation",
    "azimuth_elevation",
    "satellite_azel",
    "signal_path",
]

_E2 = WGS84_F * (2.0 - WGS84_F)
_B_M = WGS84_A_M * (1.0 - WGS84_F)
_EP2 = _E2 / (1.0 - _E2)
_LIGHT_TIME_ITERATIONS = 3


@runtime_checkable
class OrbitSource(Protocol):
    """Anything that gives satellite ECEF positions at given times.

    Implemented by :class:`psdbound.io.nav.Navigation` (broadcast) and
    :class:`psdbound.io.sp3.PreciseOrbit` (precise orbits).
    """

    def positions_ecef_m(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """Return ECEF positions (m), shape (n, 3), of ``sat`` at GPS seconds ``t_gps_s``."""
        ...


def ecef_to_geodetic(
    xyz_m: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Convert ECEF coordinates to WGS84 geodetic latitude, longitude, height.

    Bowring's formula iterated (4 iterations, sub-micrometre from the Earth's
    centre region out to beyond geostationary altitude); height from the
    pole-safe expression ``p cos(lat) + z sin(lat) - a sqrt(1 - e^2 sin^2 lat)``.

    Parameters
    ----------
    xyz_m : array_like of float, shape (..., 3)
        ECEF coordinates, m.

    Returns
    -------
    lat_deg : ndarray of float64, shape (...)
        Geodetic latitude, degrees in [-90, 90].
    lon_deg : ndarray of float64, shape (...)
        Longitude, degrees in (-180, 180].
    h_m : ndarray of float64, shape (...)
        Height above the ellipsoid, m.

    """
    xyz = np.asarray(xyz_m, dtype=np.float64)
    if xyz.shape[-1:] != (3,):
        raise ValueError(f"xyz_m must have shape (..., 3), got {xyz.shape}")
    x, y, z = xyz[..., 0], xyz[..., 1], xyz[..., 2]
    lon = np.arctan2(y, x)
    p = np.hypot(x, y)
    # parametric latitude start, then Bowring iterations
    beta = np.arctan2(z, (1.0 - WGS84_F) * p)
    lat = beta
    for _ in range(4):
        lat = np.arctan2(
            z + _EP2 * _B_M * np.sin(beta) ** 3, p - _E2 * WGS84_A_M * np.cos(beta) ** 3
        )
        beta = np.arctan2((1.0 - WGS84_F) * np.sin(lat), np.cos(lat))
    s = np.sin(lat)
    h = p * np.cos(lat) + z * s - WGS84_A_M * np.sqrt(1.0 - _E2 * s * s)
    return np.degrees(lat), np.degrees(lon), h


def geodetic_to_ecef(lat_deg: ArrayLike, lon_deg: ArrayLike, h_m: ArrayLike) -> NDArray[np.float64]:
    """Convert WGS84 geodetic coordinates to ECEF.

    Parameters
    ----------
    lat_deg, lon_deg : array_like of float
        Geodetic latitude and longitude, degrees.
    h_m : array_like of float
        Height above the ellipsoid, m.

    Returns
    -------
    ndarray of float64, shape (..., 3)
        ECEF coordinates, m (inputs broadcast together).

    """
    lat = np.radians(np.asarray(lat_deg, dtype=np.float64))
    lon = np.radians(np.asarray(lon_deg, dtype=np.float64))
    h = np.asarray(h_m, dtype=np.float64)
    s = np.sin(lat)
    n = WGS84_A_M / np.sqrt(1.0 - _E2 * s * s)
    x = (n + h) * np.cos(lat) * np.cos(lon)
    y = (n + h) * np.cos(lat) * np.sin(lon)
    z = (n * (1.0 - _E2) + h) * s
    return np.stack(np.broadcast_arrays(x, y, z), axis=-1)


def enu_rotation(lat_deg: ArrayLike, lon_deg: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrix from ECEF vectors to local east-north-up.

    Parameters
    ----------
    lat_deg, lon_deg : array_like of float
        Geodetic latitude and longitude of the local origin, degrees.

    Returns
    -------
    ndarray of float64, shape (..., 3, 3)
        ``R`` with ``enu = R @ d_ecef``; rows are the east, north and up unit
        vectors expressed in ECEF.

    """
    lat = np.radians(np.asarray(lat_deg, dtype=np.float64))
    lon = np.radians(np.asarray(lon_deg, dtype=np.float64))
    lat, lon = np.broadcast_arrays(lat, lon)
    sl, cl = np.sin(lat), np.cos(lat)
    so, co = np.sin(lon), np.cos(lon)
    zero = np.zeros_like(lat)
    east = np.stack([-so, co, zero], axis=-1)
    north = np.stack([-sl * co, -sl * so, cl], axis=-1)
    up = np.stack([cl * co, cl * so, sl], axis=-1)
    return np.stack([east, north, up], axis=-2)


def azimuth_elevation(
    receiver_xyz_m: ArrayLike, sat_xyz_m: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Azimuth and elevation of satellites seen from a receiver.

    Parameters
    ----------
    receiver_xyz_m : array_like of float, shape (3,) or (n, 3)
        Receiver ECEF position(s), m.
    sat_xyz_m : array_like of float, shape (3,) or (n, 3)
        Satellite ECEF position(s), m, in the same frame; broadcast against
        the receiver positions.

    Returns
    -------
    az_deg : ndarray of float64
        Azimuth clockwise from geodetic north, degrees in [0, 360).
    el_deg : ndarray of float64
        Elevation above the local horizon (plane normal to the WGS84
        ellipsoid normal), degrees in [-90, 90]. NaN where a satellite
        position is NaN.

    """
    rx = np.asarray(receiver_xyz_m, dtype=np.float64)
    sv = np.asarray(sat_xyz_m, dtype=np.float64)
    lat, lon, _ = ecef_to_geodetic(rx)
    rot = enu_rotation(lat, lon)
    d = sv - rx
    enu = np.einsum("...ij,...j->...i", rot, d)
    e, n, u = enu[..., 0], enu[..., 1], enu[..., 2]
    az = np.degrees(np.arctan2(e, n)) % 360.0
    az = np.where(az >= 360.0, 0.0, az)  # -tiny % 360 can round to 360
    el = np.degrees(np.arctan2(u, np.hypot(e, n)))
    return az, el


def satellite_azel(
    orbit: OrbitSource,
    sat: str,
    t_rx_gps_s: ArrayLike,
    receiver_xyz_m: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Azimuth and elevation of a satellite at reception times.

    The transmit time is found by iterating ``t_tx = t_rx - tau`` with
    ``tau = |R3(omega_e tau) r_sat(t_tx) - r_rx| / c`` three times (from
    ``tau = 0``), where ``R3(omega_e tau)`` rotates the satellite position from
    the Earth-fixed frame at transmission into the frame at reception
    (Earth rotation during the signal travel, Sagnac effect).

    Parameters
    ----------
    orbit : OrbitSource
        Object with ``positions_ecef_m(sat, t_gps_s)``, e.g. a
        :class:`~psdbound.io.nav.Navigation` or a
        :class:`~psdbound.io.sp3.PreciseOrbit`.
    sat : str
        Satellite id such as ``'G05'``.
    t_rx_gps_s : array_like of float
        Reception times, GPS seconds (scalar or 1-D).
    receiver_xyz_m : array_like of float, shape (3,)
        Receiver ECEF position, m.

    Returns
    -------
    az_deg : ndarray of float64, shape (n,)
        Azimuth, degrees in [0, 360).
    el_deg : ndarray of float64, shape (n,)
        Elevation, degrees. Both are NaN where the orbit gives no position.

    """
    rx = np.asarray(receiver_xyz_m, dtype=np.float64)
    _, _, sv = signal_path(orbit, sat, t_rx_gps_s, rx)
    return azimuth_elevation(rx, sv)


def signal_path(
    orbit: OrbitSource,
    sat: str,
    t_rx_gps_s: ArrayLike,
    receiver_xyz_m: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Geometric range, travel time and transmit position of a satellite signal.

    Same light-time iteration and Earth-rotation correction as
    :func:`satellite_azel`.

    Parameters
    ----------
    orbit : OrbitSource
        Object with ``positions_ecef_m(sat, t_gps_s)``.
    sat : str
        Satellite id such as ``'G05'``.
    t_rx_gps_s : array_like of float
        True reception times, GPS seconds (scalar or 1-D).
    receiver_xyz_m : array_like of float, shape (3,)
        Receiver ECEF position, m.

    Returns
    -------
    range_m : ndarray, shape (n,)
        Geometric range, metres.
    travel_s : ndarray, shape (n,)
        Signal travel time, seconds.
    sat_xyz_m : ndarray, shape (n, 3)
        Satellite position at transmission in the Earth-fixed frame at
        reception, metres. All NaN where the orbit gives no position.
    """
    t_rx = np.atleast_1d(np.asarray(t_rx_gps_s, dtype=np.float64))
    rx = np.asarray(receiver_xyz_m, dtype=np.float64)
    tau = np.zeros_like(t_rx)
    sv = np.full((t_rx.shape[0], 3), np.nan)
    rho = np.full(t_rx.shape[0], np.nan)
    for _ in range(_LIGHT_TIME_ITERATIONS):
        sv = _rotate_z(orbit.positions_ecef_m(sat, t_rx - tau), OMEGA_E_RAD_S * tau)
        rho = np.linalg.norm(sv - rx, axis=-1)
        tau = np.where(np.isfinite(rho), rho / SPEED_OF_LIGHT_M_S, 0.0)
    return rho, tau, sv


def _rotate_z(xyz: NDArray[np.float64], angle_rad: NDArray[np.float64]) -> NDArray[np.float64]:
    """Coordinates in a frame rotated by ``angle_rad`` about z (R3 rotation)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    out = np.empty_like(xyz)
    out[..., 0] = c * xyz[..., 0] + s * xyz[..., 1]
    out[..., 1] = -s * xyz[..., 0] + c * xyz[..., 1]
    out[..., 2] = xyz[..., 2]
    return out
