"""Nominal constellations as broadcast ephemerides.

* GPS: the 24-slot reference constellation of the GPS SPS Performance
  Standard (table 3-1: six planes A-F, RAAN and argument of latitude per slot
  at 1993-07-01 00:00, Greenwich hour angle 18 h 36 min 14.4 s, circular
  orbits, i = 55 deg, a = 26559.7 km, two revolutions per sidereal day so the
  ground track repeats every sidereal day). Slot ``A1`` .. ``F4`` is given PRN
  ``G01`` .. ``G24`` in that order.
* Galileo: a Walker 24/3/1 constellation (i = 56 deg, a = 29600 km, planes
  at RAAN 0/120/240 deg, eight slots per plane 45 deg apart, phasing 15 deg
  between planes) referenced to the Greenwich meridian at 2000-01-01 12:00
  (an arbitrary but fixed phasing).

The orbits are turned into Keplerian broadcast records (one every two hours,
valid four hours) so the result is a :class:`~psdbound.io.nav.Navigation`:
the same propagation code as for real navigation files computes positions,
and :func:`psdbound.io.write.write_nav_v3` writes it as a RINEX 3 file.
Nodal regression and perturbations are ignored (nominal geometry).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from psdbound.io.nav import KeplerEphemerides, Navigation
from psdbound.io.timescales import SECONDS_PER_WEEK, calendar_to_gps_s

__all__ = ["nominal_navigation", "GPS_SLOTS", "OMEGA_E_RAD_S"]

OMEGA_E_RAD_S = 7.2921151467e-5
_MU = {"G": 3.986005e14, "E": 3.986004418e14}

#: (slot, RAAN deg, argument of latitude deg) at the GPS reference epoch.
GPS_SLOTS = (
    ("A1", 272.847, 268.126), ("A2", 272.847, 161.786), ("A3", 272.847, 11.676),
    ("A4", 272.847, 41.806), ("B1", 332.847, 80.956), ("B2", 332.847, 173.336),
    ("B3", 332.847, 309.976), ("B4", 332.847, 204.376), ("C1", 32.847, 111.876),
    ("C2", 32.847, 11.796), ("C3", 32.847, 339.666), ("C4", 32.847, 241.556),
    ("D1", 92.847, 135.226), ("D2", 92.847, 265.446), ("D3", 92.847, 35.156),
    ("D4", 92.847, 167.356), ("E1", 152.847, 197.046), ("E2", 152.847, 302.596),
    ("E3", 152.847, 66.066), ("E4", 152.847, 333.686), ("F1", 212.847, 238.886),
    ("F2", 212.847, 345.226), ("F3", 212.847, 105.206), ("F4", 212.847, 135.346),
)  # fmt: skip
# 1993-07-01 00:00:00 UTC = 00:00:09 GPS (GPS - UTC became 9 s at that instant)
_GPS_EPOCH_GPS_S = float(calendar_to_gps_s(1993, 7, 1, 0, 0, 9.0))
_SIDEREAL_DAY_S = 2.0 * np.pi / 7.2921151467e-5
#: Revolutions per sidereal day (GPS: exact repeat of the ground track).
_REVS = {"G": 2.0, "E": 1.7}
_GPS_GHA_DEG = (18 + 36 / 60 + 14.4 / 3600) * 15.0
_GPS_A_M = 26559.7e3
_GAL_EPOCH_GPS_S = float(calendar_to_gps_s(2000, 1, 1, 12, 0, 0.0)) + 13.0
_GAL_A_M = 29600.0e3


def _elements(system: str) -> tuple[list[str], np.ndarray, np.ndarray, float, float, float]:
    """Satellites, LAN at epoch (rad, Earth-fixed), arg. of latitude (rad), a, i, epoch."""
    if system == "G":
        sats = [f"G{k + 1:02d}" for k in range(len(GPS_SLOTS))]
        raan = np.radians([s[1] for s in GPS_SLOTS])
        u0 = np.radians([s[2] for s in GPS_SLOTS])
        lan = raan - np.radians(_GPS_GHA_DEG)
        return sats, lan, u0, _GPS_A_M, np.radians(55.0), _GPS_EPOCH_GPS_S
    if system == "E":
        sats, lan, u0 = [], [], []
        for p in range(3):
            for k in range(8):
                sats.append(f"E{p * 8 + k + 1:02d}")
                lan.append(np.radians(120.0 * p))
                u0.append(np.radians(45.0 * k + 15.0 * p))
        return sats, np.array(lan), np.array(u0), _GAL_A_M, np.radians(56.0), _GAL_EPOCH_GPS_S
    raise ValueError(f"no nominal constellation for system {system!r} (G or E)")


def nominal_navigation(
    t_start_gps_s: float,
    t_stop_gps_s: float,
    *,
    systems: str = "G",
    record_interval_s: float = 7200.0,
    clock_seed: int | None = 0,
) -> Navigation:
    """Broadcast-ephemeris records of nominal constellations over a time span.

    Parameters
    ----------
    t_start_gps_s, t_stop_gps_s : float
        Span to cover, GPS seconds; records every ``record_interval_s`` from
        one interval before the start to one after the stop.
    systems : str, default "G"
        ``"G"``, ``"E"`` or ``"GE"``.
    record_interval_s : float, default 7200
        Spacing of the records' reference times, seconds.
    clock_seed : int or None, default 0
        Seed of the satellite clock offsets written in the records
        (``af0`` up to 0.5 ms, ``af1`` up to 1e-11); None for zero clocks.

    Returns
    -------
    Navigation
        With ``path`` ``<nominal>`` and circular Keplerian records.
    """
    rng = None if clock_seed is None else np.random.default_rng(clock_seed)
    t0 = np.floor(t_start_gps_s / record_interval_s) * record_interval_s - record_interval_s
    toes = np.arange(t0, t_stop_gps_s + 2 * record_interval_s, record_interval_s)
    ephs = {}
    for system in systems:
        sats, lan0, u0, a, inc, epoch = _elements(system)
        n0 = np.sqrt(_MU[system] / a**3)  # Keplerian mean motion of the records
        n = 2.0 * np.pi * _REVS[system] / _SIDEREAL_DAY_S  # nominal mean motion
        ns = len(sats)
        af0 = np.zeros(ns) if rng is None else rng.uniform(-5e-4, 5e-4, ns)
        af1 = np.zeros(ns) if rng is None else rng.uniform(-1e-11, 1e-11, ns)
        rows: dict[str, list] = {k: [] for k in ("sat", "toe", "m0", "omega0", "af0", "af1")}
        for toe in toes:
            dt = toe - epoch
            sow = toe - np.floor(toe / SECONDS_PER_WEEK) * SECONDS_PER_WEEK
            lan = lan0 - OMEGA_E_RAD_S * dt  # Earth-fixed longitude of the node at toe
            rows["sat"] += sats
            rows["toe"] += [toe] * ns
            rows["m0"] += list(np.mod(u0 + n * dt + np.pi, 2 * np.pi) - np.pi)
            rows["omega0"] += list(np.mod(lan + OMEGA_E_RAD_S * sow + np.pi, 2 * np.pi) - np.pi)
            rows["af0"] += list(af0 + af1 * (toe - toes[0]))
            rows["af1"] += list(af1)
        m = len(rows["sat"])
        toe_arr = np.array(rows["toe"])
        z = np.zeros(m)
        ephs[system] = KeplerEphemerides(
            sat=np.array(rows["sat"]),
            toc_gps_s=toe_arr,
            toe_gps_s=toe_arr,
            toe_sow_s=toe_arr - np.floor(toe_arr / SECONDS_PER_WEEK) * SECONDS_PER_WEEK,
            af0_s=np.array(rows["af0"]),
            af1=np.array(rows["af1"]),
            af2=z.copy(),
            crs_m=z.copy(),
            delta_n_rad_s=np.full(m, n - n0),
            m0_rad=np.array(rows["m0"]),
            cuc_rad=z.copy(),
            e=z.copy(),
            cus_rad=z.copy(),
            sqrt_a=np.full(m, np.sqrt(a)),
            cic_rad=z.copy(),
            omega0_rad=np.array(rows["omega0"]),
            cis_rad=z.copy(),
            i0_rad=np.full(m, inc),
            crc_m=z.copy(),
            omega_rad=z.copy(),
            omega_dot_rad_s=z.copy(),
            idot_rad_s=z.copy(),
            health=np.zeros(m, dtype=np.int64),
            iode=np.arange(m, dtype=np.int64) % 256,
            data_source=np.full(m, 517 if system == "E" else 0, dtype=np.int64),
        )
    return Navigation(path=Path("<nominal>"), version=3.04, leap_seconds=None, ephemerides=ephs)
