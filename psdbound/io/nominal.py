"""Nominal GPS and Galileo constellations: the one definition, and as broadcast ephemerides.

The constellations (circular orbits, no perturbations) are defined here once,
by :func:`nominal_elements`, and used twice: as Keplerian broadcast records
(:func:`nominal_navigation`, for the simulator) and as a direct circular-orbit
propagator (:func:`psdbound.ionosphere.nominal_constellation`, for the
ionosphere geometry).

* **GPS 24-slot** (``"G"``): the baseline 24-slot reference constellation of
  the GPS SPS Performance Standard (4th ed., 2008, table 3.2-1): six planes
  A-F, right ascension of the ascending node (RAAN) and argument of latitude
  per slot at the reference epoch 1993-07-01 00:00:00 UTC (00:00:09 GPS),
  when the Greenwich hour angle was 18 h 36 min 14.4 s; circular orbits,
  inclination 55 deg, radius 26 559.7 km. Slot ``A1`` .. ``F4`` becomes
  satellite ``G01`` .. ``G24`` in that order.
* **Galileo Walker 24/3/1** (``"E"``): inclination 56 deg, radius
  29 600 km, three planes whose ascending nodes lie at Earth-fixed longitudes
  0, 120 and 240 deg at the reference epoch 2000-01-01 12:00:00 GPS time,
  eight satellites per plane 45 deg apart in argument of latitude, phasing
  15 deg between adjacent planes (Walker F = 1: 360 F / T). Plane ``p``
  (0-2), slot ``k`` (0-7) is ``E{8p + k + 1:02d}``. This phasing is a fixed,
  documented convention, not the real constellation's.

Mean motions are set so the ground tracks repeat exactly, as the real
constellations are maintained: GPS two revolutions per sidereal day (period
43 082.045 s), Galileo 17 revolutions in 10 sidereal days. Nodal regression
and all perturbations are ignored (nominal geometry).

The broadcast records (one every two hours, valid four hours) make a
:class:`~psdbound.io.navigation.Navigation`: the same propagation code as for
real navigation files computes positions, and
:func:`psdbound.io.write.write_nav_v3` writes it as a RINEX 3 file. The
records' Galileo node longitudes and arguments of latitude refer to
2000-01-01 12:00:00 **UTC** (12:00:13 GPS) instead of 12:00:00 GPS
(``_RECORD_EPOCH_SHIFT_S``), as the simulator has always written them: the
record Galileo constellation is the Walker pattern above shifted 13 s along
the orbits and in Earth rotation.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from psdbound.constants import OMEGA_E_RAD_S, SIDEREAL_DAY_S
from psdbound.io.ephemeris import GM_M3_S2
from psdbound.io.kepler import KeplerEphemerides
from psdbound.io.navigation import Navigation
from psdbound.io.timescales import SECONDS_PER_WEEK, calendar_to_gps_s

__all__ = [
    "GPS_SLOTS",
    "NominalElements",
    "nominal_elements",
    "nominal_navigation",
]


#: GPS SPS PS (2008) table 3.2-1: (slot, RAAN deg, argument of latitude deg) at the epoch.
GPS_SLOTS = (
    ("A1", 272.847, 268.126),
    ("A2", 272.847, 161.786),
    ("A3", 272.847, 11.676),
    ("A4", 272.847, 41.806),
    ("B1", 332.847, 80.956),
    ("B2", 332.847, 173.336),
    ("B3", 332.847, 309.976),
    ("B4", 332.847, 204.376),
    ("C1", 32.847, 111.876),
    ("C2", 32.847, 11.796),
    ("C3", 32.847, 339.666),
    ("C4", 32.847, 241.556),
    ("D1", 92.847, 135.226),
    ("D2", 92.847, 265.446),
    ("D3", 92.847, 35.156),
    ("D4", 92.847, 167.356),
    ("E1", 152.847, 197.046),
    ("E2", 152.847, 302.596),
    ("E3", 152.847, 66.066),
    ("E4", 152.847, 333.686),
    ("F1", 212.847, 238.886),
    ("F2", 212.847, 345.226),
    ("F3", 212.847, 105.206),
    ("F4", 212.847, 135.346),
)

_GPS_GHA_DEG = (18.0 + 36.0 / 60.0 + 14.4 / 3600.0) * 15.0
_GPS_RADIUS_M = 26_559.7e3
_GPS_INCLINATION_DEG = 55.0
_GPS_REVS_PER_SIDEREAL_DAY = 2.0
# 1993-07-01 00:00:00 UTC = 00:00:09 GPS (GPS - UTC = 9 s from that instant on)
_GPS_EPOCH_GPS_S = float(calendar_to_gps_s(1993, 7, 1, 0, 0, 9.0))

_GAL_RADIUS_M = 29_600.0e3
_GAL_INCLINATION_DEG = 56.0
_GAL_REVS_PER_SIDEREAL_DAY = 1.7
_GAL_EPOCH_GPS_S = float(calendar_to_gps_s(2000, 1, 1, 12, 0, 0.0))

_DESCRIPTIONS = {
    "G": "GPS 24-slot reference constellation (SPS PS 2008, epoch 1993-07-01)",
    "E": "Galileo Walker 24/3/1 (i=56 deg, nodes 0/120/240 deg E at 2000-01-01T12 GPS)",
}
# The broadcast records' reference epoch minus the constellation's, s: the
# simulator's Galileo records have always used 2000-01-01 12:00 UTC (GPS - UTC = 13 s).
_RECORD_EPOCH_SHIFT_S = {"G": 0.0, "E": 13.0}


@dataclass(frozen=True, eq=False)
class NominalElements:
    """Circular orbits of one system's nominal constellation at its reference epoch.

    Attributes
    ----------
    system : str
        System letter, ``"G"`` or ``"E"``.
    sats : tuple of str
        Satellite ids, e.g. ``('G01', ..., 'G24')``.
    node_lon0_rad : ndarray of float64
        Earth-fixed longitude of the ascending node per satellite at
        ``epoch_gps_s``, rad.
    arg_lat0_rad : ndarray of float64
        Argument of latitude per satellite at ``epoch_gps_s``, rad.
    radius_m : float
        Orbit radius, m.
    inclination_rad : float
        Inclination, rad.
    revs_per_sidereal_day : float
        Revolutions per sidereal day (exact ground-track repeat).
    epoch_gps_s : float
        Reference epoch, GPS seconds.
    description : str
        What this constellation is (recorded with results).
    """

    system: str
    sats: tuple[str, ...]
    node_lon0_rad: NDArray[np.float64]
    arg_lat0_rad: NDArray[np.float64]
    radius_m: float
    inclination_rad: float
    revs_per_sidereal_day: float
    epoch_gps_s: float
    description: str

    @property
    def mean_motion_rad_s(self) -> float:
        """Mean motion ``revs_per_sidereal_day * omega_E``, rad/s."""
        return self.revs_per_sidereal_day * OMEGA_E_RAD_S


def nominal_elements(system: str) -> NominalElements:
    """Return the nominal constellation of one system.

    Parameters
    ----------
    system : str
        ``"G"`` (GPS 24-slot) or ``"E"`` (Galileo Walker 24/3/1).

    Returns
    -------
    NominalElements

    Raises
    ------
    ValueError
        For another system letter.
    """
    if system == "G":
        sats = tuple(f"G{k + 1:02d}" for k in range(len(GPS_SLOTS)))
        raan = np.radians([s[1] for s in GPS_SLOTS])
        return NominalElements(
            system="G",
            sats=sats,
            node_lon0_rad=raan - np.radians(_GPS_GHA_DEG),
            arg_lat0_rad=np.radians([s[2] for s in GPS_SLOTS]),
            radius_m=_GPS_RADIUS_M,
            inclination_rad=float(np.radians(_GPS_INCLINATION_DEG)),
            revs_per_sidereal_day=_GPS_REVS_PER_SIDEREAL_DAY,
            epoch_gps_s=_GPS_EPOCH_GPS_S,
            description=_DESCRIPTIONS["G"],
        )
    if system == "E":
        sats_e, lan, u0 = [], [], []
        for p in range(3):
            for k in range(8):
                sats_e.append(f"E{8 * p + k + 1:02d}")
                lan.append(np.radians(120.0 * p))
                u0.append(np.radians(45.0 * k + 15.0 * p))
        return NominalElements(
            system="E",
            sats=tuple(sats_e),
            node_lon0_rad=np.array(lan),
            arg_lat0_rad=np.array(u0),
            radius_m=_GAL_RADIUS_M,
            inclination_rad=float(np.radians(_GAL_INCLINATION_DEG)),
            revs_per_sidereal_day=_GAL_REVS_PER_SIDEREAL_DAY,
            epoch_gps_s=_GAL_EPOCH_GPS_S,
            description=_DESCRIPTIONS["E"],
        )
    raise ValueError(f"no nominal constellation for system {system!r}; use 'G' and/or 'E'")


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

    Raises
    ------
    ValueError
        For a system letter other than G or E.
    """
    rng = None if clock_seed is None else np.random.default_rng(clock_seed)
    t0 = np.floor(t_start_gps_s / record_interval_s) * record_interval_s - record_interval_s
    toes = np.arange(t0, t_stop_gps_s + 2 * record_interval_s, record_interval_s)
    ephs = {}
    for system in systems:
        el = nominal_elements(system)
        sats, lan0, u0 = list(el.sats), el.node_lon0_rad, el.arg_lat0_rad
        a, inc = el.radius_m, el.inclination_rad
        epoch = el.epoch_gps_s + _RECORD_EPOCH_SHIFT_S[system]
        n0 = np.sqrt(GM_M3_S2[system] / a**3)  # Keplerian mean motion of the records
        n = 2.0 * np.pi * el.revs_per_sidereal_day / SIDEREAL_DAY_S  # nominal mean motion
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
