"""Nominal GNSS constellations as circular Keplerian orbits.

Used when the user gives no navigation, SP3 or almanac file. Two systems:

* **GPS 24-slot** (``"G"``): the baseline 24-slot reference constellation of
  the GPS SPS Performance Standard (4th ed., 2008, table 3.2-1): six planes
  A-F, right ascension of the ascending node (RAAN) and argument of latitude
  per slot at the reference epoch 1993-07-01 00:00:00 UTC, when the Greenwich
  hour angle was 18 h 36 min 14.4 s; circular orbits, inclination 55 deg,
  radius 26 559.7 km. Slot ``A1`` .. ``F4`` becomes satellite ``G01`` ..
  ``G24`` in that order.
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
and all perturbations are ignored (nominal geometry); for geometry studies
such as the ionosphere cutoff this is what matters, not metre-level orbits.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.io.geometry import OMEGA_E_RAD_S
from psdbound.io.nominal import GPS_SLOTS as _GPS_SLOTS
from psdbound.io.timescales import calendar_to_gps_s

__all__ = [
    "SIDEREAL_DAY_S",
    "GPS_SLOTS",
    "NominalConstellation",
    "nominal_constellation",
]

#: Sidereal day (Earth rotation period relative to the stars), s: 2 pi / omega_E.
SIDEREAL_DAY_S = 2.0 * np.pi / OMEGA_E_RAD_S

#: GPS SPS PS (2008) table 3.2-1 (shared with the broadcast-record constellation).
GPS_SLOTS = _GPS_SLOTS

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


@dataclass(frozen=True, eq=False)
class NominalConstellation:
    """Circular-orbit constellation with ``positions_ecef_m`` and ``satellites``.

    Implements :class:`psdbound.io.geometry.OrbitSource`, so
    :func:`psdbound.io.geometry.satellite_azel` and
    :func:`~psdbound.io.geometry.signal_path` work with it.

    Attributes
    ----------
    sats : tuple of str
        Satellite ids, e.g. ``('G01', ..., 'G24')``.
    radius_m : ndarray of float64
        Orbit radius per satellite, m.
    inclination_rad : ndarray of float64
        Inclination per satellite, rad.
    node_lon0_rad : ndarray of float64
        Earth-fixed longitude of the ascending node at ``epoch_gps_s``, rad.
    arg_lat0_rad : ndarray of float64
        Argument of latitude at ``epoch_gps_s``, rad.
    mean_motion_rad_s : ndarray of float64
        Mean motion, rad/s.
    epoch_gps_s : ndarray of float64
        Reference epoch per satellite, GPS seconds.
    description : str
        What this constellation is (recorded with results).
    """

    sats: tuple[str, ...]
    radius_m: NDArray[np.float64]
    inclination_rad: NDArray[np.float64]
    node_lon0_rad: NDArray[np.float64]
    arg_lat0_rad: NDArray[np.float64]
    mean_motion_rad_s: NDArray[np.float64]
    epoch_gps_s: NDArray[np.float64]
    description: str = ""
    _index: dict[str, int] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self._index.update({s: i for i, s in enumerate(self.sats)})

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted satellite ids."""
        return tuple(sorted(self.sats))

    @property
    def source_id(self) -> str:
        """Short identifier of the orbit source, used in cache keys and results."""
        systems = "".join(sorted({s[0] for s in self.sats}))
        return f"nominal:{systems}:{len(self.sats)}"

    def period_s(self, sat: str) -> float:
        """Orbital period of ``sat``, s."""
        return float(2.0 * np.pi / self.mean_motion_rad_s[self._index[sat]])

    def positions_ecef_m(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """ECEF positions of one satellite.

        Parameters
        ----------
        sat : str
            Satellite id such as ``'G05'``.
        t_gps_s : array_like of float
            Times, GPS seconds (scalar or 1-D).

        Returns
        -------
        ndarray of float64, shape (n, 3)
            ECEF coordinates, m, in the Earth-fixed frame at each time; all
            NaN for a satellite not in the constellation.
        """
        t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
        j = self._index.get(str(sat))
        if j is None:
            return np.full((t.shape[0], 3), np.nan)
        dt = t - self.epoch_gps_s[j]
        u = self.arg_lat0_rad[j] + self.mean_motion_rad_s[j] * dt
        lon_node = self.node_lon0_rad[j] - OMEGA_E_RAD_S * dt
        cu, su = np.cos(u), np.sin(u)
        cl, sl = np.cos(lon_node), np.sin(lon_node)
        ci, si = np.cos(self.inclination_rad[j]), np.sin(self.inclination_rad[j])
        r = self.radius_m[j]
        return np.stack(
            [r * (cu * cl - su * ci * sl), r * (cu * sl + su * ci * cl), r * su * si], axis=-1
        )


def _system_elements(system: str) -> dict[str, np.ndarray | list[str]]:
    if system == "G":
        sats = [f"G{k + 1:02d}" for k in range(len(GPS_SLOTS))]
        raan = np.radians([s[1] for s in GPS_SLOTS])
        u0 = np.radians([s[2] for s in GPS_SLOTS])
        n = len(sats)
        return {
            "sats": sats,
            "radius_m": np.full(n, _GPS_RADIUS_M),
            "inclination_rad": np.full(n, np.radians(_GPS_INCLINATION_DEG)),
            "node_lon0_rad": raan - np.radians(_GPS_GHA_DEG),
            "arg_lat0_rad": u0,
            "mean_motion_rad_s": np.full(n, _GPS_REVS_PER_SIDEREAL_DAY * OMEGA_E_RAD_S),
            "epoch_gps_s": np.full(n, _GPS_EPOCH_GPS_S),
        }
    if system == "E":
        sats, lan, u0 = [], [], []
        for p in range(3):
            for k in range(8):
                sats.append(f"E{8 * p + k + 1:02d}")
                lan.append(np.radians(120.0 * p))
                u0.append(np.radians(45.0 * k + 15.0 * p))
        n = len(sats)
        return {
            "sats": sats,
            "radius_m": np.full(n, _GAL_RADIUS_M),
            "inclination_rad": np.full(n, np.radians(_GAL_INCLINATION_DEG)),
            "node_lon0_rad": np.array(lan),
            "arg_lat0_rad": np.array(u0),
            "mean_motion_rad_s": np.full(n, _GAL_REVS_PER_SIDEREAL_DAY * OMEGA_E_RAD_S),
            "epoch_gps_s": np.full(n, _GAL_EPOCH_GPS_S),
        }
    raise ValueError(f"no nominal constellation for system {system!r}; use 'G' and/or 'E'")


def nominal_constellation(systems: str = "G") -> NominalConstellation:
    """Build the nominal constellation of one or more systems.

    Parameters
    ----------
    systems : str, default "G"
        System letters: ``"G"`` (GPS 24-slot), ``"E"`` (Galileo Walker
        24/3/1) or ``"GE"``.

    Returns
    -------
    NominalConstellation

    Raises
    ------
    ValueError
        For a system letter other than G or E.
    """
    letters = list(dict.fromkeys(systems.upper()))
    if not letters:
        raise ValueError("systems must name at least one of 'G', 'E'")
    parts = [_system_elements(s) for s in letters]
    keys = [k for k in parts[0] if k != "sats"]
    return NominalConstellation(
        sats=tuple(s for p in parts for s in p["sats"]),
        **{k: np.concatenate([np.asarray(p[k], dtype=np.float64) for p in parts]) for k in keys},
        description="; ".join(_DESCRIPTIONS[s] for s in letters),
    )
