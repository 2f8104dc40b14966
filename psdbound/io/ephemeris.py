"""Broadcast-ephemeris propagation (Keplerian user algorithm).

Implements the satellite position algorithm of IS-GPS-200 (Table 20-IV),
which the Galileo OS SIS ICD (section 5.1.1), the BeiDou ICDs (MEO/IGSO) and
the QZSS IS use with their own constants:

========  =================  ==================
system    mu (m^3/s^2)       omega_e (rad/s)
========  =================  ==================
GPS, QZSS 3.986005e14        7.2921151467e-5
Galileo   3.986004418e14     7.2921151467e-5
BeiDou    3.986004418e14     7.292115e-5
========  =================  ==================

Record selection
----------------
For every requested time the record of that satellite with the nearest time of
ephemeris (|t - toe|) is used, among the healthy records (``health == 0``)
with |t - toe| <= :data:`MAX_AGE_S` (4 h for every system). For Galileo the
I/NAV records (data-source bit 0, 2 or 9) are preferred; F/NAV records
(bit 1 or 8) are used only when no valid I/NAV record exists. Positions are
NaN where no record qualifies.

BeiDou GEO satellites (C01-C05, C59-C63) need a different rotation
(BDS-SIS-ICD section 5.2.4.12) that is not implemented; their positions are
NaN.

Positions are Earth-centred Earth-fixed coordinates at the requested time
(the frame of that instant); no light-time or Earth-rotation correction is
applied here (see :func:`psdbound.io.geometry.satellite_azel`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import (
    GM_BEIDOU_GALILEO_M3_S2,
    GM_GPS_M3_S2,
    OMEGA_E_BEIDOU_RAD_S,
    OMEGA_E_RAD_S,
)
from psdbound.io.kepler import KeplerEphemerides

__all__ = [
    "GM_M3_S2",
    "OMEGA_E_BY_SYSTEM_RAD_S",
    "MAX_AGE_S",
    "HALF_WEEK_S",
    "solve_kepler",
    "select_records",
    "kepler_positions_ecef_m",
    "satellite_clock_s",
    "nan_positions",
    "is_beidou_geo",
]

#: Gravitational constant times Earth mass used by each system's ICD, m^3/s^2.
GM_M3_S2 = {
    "G": GM_GPS_M3_S2,
    "J": GM_GPS_M3_S2,
    "E": GM_BEIDOU_GALILEO_M3_S2,
    "C": GM_BEIDOU_GALILEO_M3_S2,
}
#: Earth rotation rate used by each system's ICD, rad/s.
OMEGA_E_BY_SYSTEM_RAD_S = {
    "G": OMEGA_E_RAD_S,
    "J": OMEGA_E_RAD_S,
    "E": OMEGA_E_RAD_S,
    "C": OMEGA_E_BEIDOU_RAD_S,
}
#: Largest |t - toe| for which a record is used, s.
MAX_AGE_S = {"G": 4 * 3600.0, "J": 4 * 3600.0, "E": 4 * 3600.0, "C": 4 * 3600.0}
#: Half a week, s (time-from-ephemeris crossover wrap).
HALF_WEEK_S = 302400.0
#: Relativistic clock correction constant F = -2 sqrt(mu) / c^2 per system, s/m^0.5.
_F_REL = {
    "G": -4.442807633e-10,
    "J": -4.442807633e-10,
    "E": -4.442807309e-10,
    "C": -4.442807309e-10,
}
_BEIDOU_GEO_PRNS = frozenset({1, 2, 3, 4, 5, 59, 60, 61, 62, 63})
_GAL_INAV_BITS = (1 << 0) | (1 << 2) | (1 << 9)


def is_beidou_geo(sat: str) -> bool:
    """Tell whether a satellite id is a BeiDou GEO (C01-C05, C59-C63).

    Parameters
    ----------
    sat : str
        Satellite id such as ``'C03'``.

    Returns
    -------
    bool
        True for BeiDou geostationary PRNs.

    """
    return sat[0] == "C" and int(sat[1:]) in _BEIDOU_GEO_PRNS


def nan_positions(t_gps_s: ArrayLike) -> NDArray[np.float64]:
    """Return an all-NaN position array matching a time array.

    Parameters
    ----------
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of float64, shape (n, 3)
        NaN coordinates, one row per time.

    """
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    return np.full((t.shape[0], 3), np.nan)


def solve_kepler(
    mean_anomaly_rad: ArrayLike,
    e: ArrayLike,
    *,
    tol: float = 1e-14,
    max_iter: int = 30,
) -> NDArray[np.float64]:
    """Solve Kepler's equation ``E - e sin E = M`` for the eccentric anomaly.

    Newton iteration, vectorised; stops when every ``|dE| < tol`` or after
    ``max_iter`` iterations.

    Parameters
    ----------
    mean_anomaly_rad : array_like of float
        Mean anomaly M, rad.
    e : array_like of float
        Eccentricity (0 <= e < 1), broadcast against ``mean_anomaly_rad``.
    tol : float, optional
        Convergence threshold on the Newton step, rad.
    max_iter : int, optional
        Maximum number of iterations.

    Returns
    -------
    ndarray of float64
        Eccentric anomaly E, rad (same shape as the broadcast inputs).

    """
    m = np.asarray(mean_anomaly_rad, dtype=np.float64)
    ecc = np.asarray(e, dtype=np.float64)
    m, ecc = np.broadcast_arrays(m, ecc)
    big_e = m + ecc * np.sin(m)  # good start for small e
    for _ in range(max_iter):
        d = (m - big_e + ecc * np.sin(big_e)) / (1.0 - ecc * np.cos(big_e))
        big_e = big_e + d
        if not np.any(np.abs(d) >= tol):  # also stops on all-NaN input
            break
    return big_e


def _wrap_tk(tk: NDArray[np.float64]) -> NDArray[np.float64]:
    """Account for week crossover: bring tk into [-302400, 302400] s."""
    tk = np.where(tk > HALF_WEEK_S, tk - 2 * HALF_WEEK_S, tk)
    return np.where(tk < -HALF_WEEK_S, tk + 2 * HALF_WEEK_S, tk)


def _nearest(
    toe: NDArray[np.float64], rows: NDArray[np.intp], t: NDArray[np.float64], max_age: float
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """Nearest-toe row among ``rows`` for each t: (row or -1, |t - toe|)."""
    n = t.shape[0]
    if rows.size == 0:
        return np.full(n, -1, dtype=np.intp), np.full(n, np.inf)
    order = np.argsort(toe[rows], kind="stable")
    r = rows[order]
    ts = toe[r]
    k = np.searchsorted(ts, t)
    lo = np.clip(k - 1, 0, ts.size - 1)
    hi = np.clip(k, 0, ts.size - 1)
    d_lo = np.abs(t - ts[lo])
    d_hi = np.abs(t - ts[hi])
    take_hi = d_hi < d_lo
    best = np.where(take_hi, r[hi], r[lo])
    dist = np.where(take_hi, d_hi, d_lo)
    ok = dist <= max_age
    return np.where(ok, best, -1), np.where(ok, dist, np.inf)


def select_records(eph: KeplerEphemerides, sat: str, t_gps_s: ArrayLike) -> NDArray[np.intp]:
    """Choose the ephemeris record to use for each time.

    Parameters
    ----------
    eph : KeplerEphemerides
        Records of the satellite's system.
    sat : str
        Satellite id such as ``'E11'``.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of intp, shape (n,)
        Row index into ``eph`` per time, or -1 where no healthy record lies
        within :data:`MAX_AGE_S` of the time (and for BeiDou GEO satellites).
        Galileo I/NAV records are preferred to F/NAV ones.

    """
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    system = sat[0]
    if is_beidou_geo(sat):
        return np.full(t.shape[0], -1, dtype=np.intp)
    max_age = MAX_AGE_S.get(system, 4 * 3600.0)
    usable = (eph.sat == sat) & (eph.health == 0)
    # NaN times never match (searchsorted puts them at the end; distance NaN)
    t_ok = np.where(np.isfinite(t), t, np.inf)
    if system == "E":
        inav = usable & ((eph.data_source & _GAL_INAV_BITS) != 0)
        other = usable & ~inav
        best, _ = _nearest(eph.toe_gps_s, np.flatnonzero(inav), t_ok, max_age)
        fall, _ = _nearest(eph.toe_gps_s, np.flatnonzero(other), t_ok, max_age)
        return np.where(best >= 0, best, fall)
    best, _ = _nearest(eph.toe_gps_s, np.flatnonzero(usable), t_ok, max_age)
    return best


def _eccentric_anomaly(
    eph: KeplerEphemerides, idx: NDArray[np.intp], tk: NDArray[np.float64], system: str
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return (semi-major axis A in m, eccentric anomaly E in rad)."""
    mu = GM_M3_S2[system]
    a = eph.sqrt_a[idx] ** 2
    n = np.sqrt(mu / a**3) + eph.delta_n_rad_s[idx]
    m = eph.m0_rad[idx] + n * tk
    return a, solve_kepler(m, eph.e[idx])


def kepler_positions_ecef_m(
    eph: KeplerEphemerides, sat: str, t_gps_s: ArrayLike
) -> NDArray[np.float64]:
    """Satellite ECEF positions from broadcast Keplerian ephemerides.

    Parameters
    ----------
    eph : KeplerEphemerides
        Records of the satellite's system (GPS, Galileo, BeiDou or QZSS).
    sat : str
        Satellite id such as ``'G05'``; its letter selects the constants.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of float64, shape (n, 3)
        ECEF coordinates in metres in the Earth-fixed frame at each time;
        NaN rows where no valid record exists (see :func:`select_records`).

    Raises
    ------
    ValueError
        If the satellite's system has no Keplerian constants here.

    """
    system = sat[0]
    if system not in GM_M3_S2:
        raise ValueError(f"no Keplerian broadcast model for system {system!r} ({sat})")
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    out = nan_positions(t)
    sel = select_records(eph, sat, t)
    ok = sel >= 0
    if not np.any(ok):
        return out
    idx = sel[ok]
    tk = _wrap_tk(t[ok] - eph.toe_gps_s[idx])
    a, big_e = _eccentric_anomaly(eph, idx, tk, system)
    e = eph.e[idx]
    v = np.arctan2(np.sqrt(1.0 - e * e) * np.sin(big_e), np.cos(big_e) - e)
    phi = v + eph.omega_rad[idx]
    s2, c2 = np.sin(2.0 * phi), np.cos(2.0 * phi)
    u = phi + eph.cus_rad[idx] * s2 + eph.cuc_rad[idx] * c2
    r = a * (1.0 - e * np.cos(big_e)) + eph.crs_m[idx] * s2 + eph.crc_m[idx] * c2
    inc = eph.i0_rad[idx] + eph.cis_rad[idx] * s2 + eph.cic_rad[idx] * c2 + eph.idot_rad_s[idx] * tk
    xp, yp = r * np.cos(u), r * np.sin(u)
    we = OMEGA_E_BY_SYSTEM_RAD_S[system]
    node = eph.omega0_rad[idx] + (eph.omega_dot_rad_s[idx] - we) * tk - we * eph.toe_sow_s[idx]
    cn, sn, ci = np.cos(node), np.sin(node), np.cos(inc)
    out[ok, 0] = xp * cn - yp * ci * sn
    out[ok, 1] = xp * sn + yp * ci * cn
    out[ok, 2] = yp * np.sin(inc)
    return out


def satellite_clock_s(eph: KeplerEphemerides, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
    """Broadcast satellite clock offset (polynomial plus relativistic term).

    Parameters
    ----------
    eph : KeplerEphemerides
        Records of the satellite's system.
    sat : str
        Satellite id such as ``'G05'``.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of float64, shape (n,)
        ``af0 + af1 dt + af2 dt^2 + F e sqrt(A) sin E`` in seconds, with
        ``dt = t - toc``; no group-delay (TGD/BGD) term. NaN where no valid
        record exists (same selection as :func:`kepler_positions_ecef_m`).

    """
    system = sat[0]
    if system not in GM_M3_S2:
        raise ValueError(f"no Keplerian broadcast model for system {system!r} ({sat})")
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    out = np.full(t.shape[0], np.nan)
    sel = select_records(eph, sat, t)
    ok = sel >= 0
    if not np.any(ok):
        return out
    idx = sel[ok]
    dt = _wrap_tk(t[ok] - eph.toc_gps_s[idx])
    tk = _wrap_tk(t[ok] - eph.toe_gps_s[idx])
    _, big_e = _eccentric_anomaly(eph, idx, tk, system)
    rel = _F_REL[system] * eph.e[idx] * eph.sqrt_a[idx] * np.sin(big_e)
    out[ok] = eph.af0_s[idx] + eph.af1[idx] * dt + eph.af2[idx] * dt * dt + rel
    return out
