"""The content of a broadcast navigation file: :class:`Navigation`.

A :class:`Navigation` holds the Keplerian records of each system
(:class:`~psdbound.io.kepler.KeplerEphemerides`) and gives satellite
positions and clocks through the propagation of :mod:`psdbound.io.ephemeris`.
It is what :func:`psdbound.io.nav.read_nav` returns and what
:func:`psdbound.io.nominal.nominal_navigation` builds.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.io.ephemeris import kepler_positions_ecef_m, nan_positions
from psdbound.io.ephemeris import satellite_clock_s as kepler_clock_s
from psdbound.io.kepler import KeplerEphemerides, check_sat_id

__all__ = ["Navigation"]


@dataclass(frozen=True, eq=False)
class Navigation:
    """Content of a broadcast navigation file.

    Attributes
    ----------
    path : pathlib.Path
        The file read.
    version : float
        RINEX format version from the header (e.g. 2.0, 3.05).
    leap_seconds : int or None
        GPS-UTC leap seconds from the ``LEAP SECONDS`` header line, if present.
    ephemerides : dict of str to KeplerEphemerides
        Parsed Keplerian records per system letter (``'G'``, ``'E'``, ...);
        only systems with at least one record are present.
    skipped : dict of str to int
        Number of records per system letter that were recognised but not
        parsed (GLONASS, SBAS, NavIC).
    warnings : tuple of str
        Records left out because they are damaged (non-finite values,
        impossible dates or elements), one line per file; also issued as
        :class:`~psdbound.common.notices.PsdboundWarning`.

    """

    path: Path
    version: float
    leap_seconds: int | None
    ephemerides: dict[str, KeplerEphemerides] = field(default_factory=dict)
    skipped: dict[str, int] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of all satellites with Keplerian ephemerides, e.g. ``('E01', 'G01')``."""
        out: set[str] = set()
        for eph in self.ephemerides.values():
            out.update(eph.satellites)
        return tuple(sorted(out))

    def positions_ecef_m(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """Broadcast ECEF positions of one satellite.

        Parameters
        ----------
        sat : str
            Satellite id such as ``'G05'``.
        t_gps_s : array_like of float
            Times, GPS seconds (scalar or 1-D).

        Returns
        -------
        ndarray of float64, shape (n, 3)
            ECEF coordinates in metres, in the Earth-fixed frame at each time.
            Rows are NaN where no healthy ephemeris is valid, and all rows are
            NaN for a satellite (or system) absent from the file.

        Raises
        ------
        ValueError
            If ``sat`` is not a satellite id like ``'G05'``.

        See Also
        --------
        psdbound.io.ephemeris.kepler_positions_ecef_m : the propagation.

        """
        sat = check_sat_id(sat)
        eph = self.ephemerides.get(sat[0])
        if eph is None:
            return nan_positions(t_gps_s)
        return kepler_positions_ecef_m(eph, sat, t_gps_s)

    def satellite_clock_s(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """Broadcast satellite clock offset of one satellite.

        Parameters
        ----------
        sat : str
            Satellite id such as ``'E11'``.
        t_gps_s : array_like of float
            Times, GPS seconds.

        Returns
        -------
        ndarray of float64, shape (n,)
            Clock offset in seconds (polynomial + relativistic correction, no
            group delay); NaN where no healthy ephemeris is valid.

        """
        sat = check_sat_id(sat)
        eph = self.ephemerides.get(sat[0])
        if eph is None:
            return np.full(np.atleast_1d(np.asarray(t_gps_s)).shape, np.nan)
        return kepler_clock_s(eph, sat, t_gps_s)
