"""Nominal GNSS constellations as circular Keplerian orbits, for the ionosphere geometry.

Used when the user gives no navigation, SP3 or almanac file. The
constellations -- GPS 24-slot (``"G"``) and Galileo Walker 24/3/1 (``"E"``)
-- are defined once, in :mod:`psdbound.io.nominal` (:func:`~psdbound.io.nominal.nominal_elements`,
which the simulator's broadcast records use too); this module propagates
them directly: :func:`nominal_constellation` -> :class:`NominalConstellation`.

Mean motions are set so the ground tracks repeat exactly, as the real
constellations are maintained: GPS two revolutions per sidereal day (period
43 082.045 s), Galileo 17 revolutions in 10 sidereal days. Nodal regression
and all perturbations are ignored (nominal geometry); for geometry studies
such as the ionosphere cutoff this is what matters, not metre-level orbits.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import OMEGA_E_RAD_S
from psdbound.io.nominal import GPS_SLOTS, NominalElements, nominal_elements

__all__ = [
    "GPS_SLOTS",
    "NominalConstellation",
    "nominal_constellation",
]


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
    parts = [nominal_elements(s) for s in letters]

    def per_sat(value: Callable[[NominalElements], ArrayLike]) -> NDArray[np.float64]:
        return np.concatenate(
            [np.asarray(np.broadcast_to(value(p), len(p.sats)), dtype=np.float64) for p in parts]
        )

    return NominalConstellation(
        sats=tuple(s for p in parts for s in p.sats),
        radius_m=per_sat(lambda p: p.radius_m),
        inclination_rad=per_sat(lambda p: p.inclination_rad),
        node_lon0_rad=per_sat(lambda p: p.node_lon0_rad),
        arg_lat0_rad=per_sat(lambda p: p.arg_lat0_rad),
        mean_motion_rad_s=per_sat(lambda p: p.mean_motion_rad_s),
        epoch_gps_s=per_sat(lambda p: p.epoch_gps_s),
        description="; ".join(p.description for p in parts),
    )
