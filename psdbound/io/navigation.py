"""The content of a broadcast navigation file: :class:`Navigation`.

A :class:`Navigation` holds the Keplerian records of each system
(:class:`~psdbound.io.kepler.KeplerEphemerides`) and the GLONASS records
(:class:`~psdbound.io.glonass.GlonassEphemerides`), and gives satellite
positions and clocks through the propagation of :mod:`psdbound.io.ephemeris`
and :mod:`psdbound.io.glonass`.
It is what :func:`psdbound.io.nav.read_nav` returns and what
:func:`psdbound.io.nominal.nominal_navigation` builds.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.io.ephemeris import MAX_AGE_S, kepler_positions_ecef_m, nan_positions
from psdbound.io.ephemeris import satellite_clock_s as kepler_clock_s
from psdbound.io.glonass import (
    GLONASS_MAX_AGE_S,
    GlonassEphemerides,
    glonass_clock_s,
    glonass_positions_ecef_m,
)
from psdbound.io.kepler import KeplerEphemerides, check_sat_id

__all__ = ["Navigation", "merge_navigation"]

# what makes a broadcast record the same record in two files
_KEPLER_KEY = ("sat", "toe_gps_s", "iode", "data_source")
_GLONASS_KEY = ("sat", "tb_gps_s")


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
        parsed (SBAS, NavIC).
    warnings : tuple of str
        Records left out because they are damaged (non-finite values,
        impossible dates or elements), one line per file; also issued as
        :class:`~psdbound.common.notices.PsdboundWarning`.
    glonass : GlonassEphemerides or None
        GLONASS records (state vectors in PZ-90), None when the file has none.
    unused : dict of str to int
        RINEX 4 records skipped because psdbound does not use them, per
        record type (``'STO'``, ``'EOP'``, ``'ION'``) or ephemeris message
        (``'EPH G CNAV'``, ``'EPH S SBAS'``); empty for RINEX 2 and 3.

    """

    path: Path
    version: float
    leap_seconds: int | None
    ephemerides: dict[str, KeplerEphemerides] = field(default_factory=dict)
    skipped: dict[str, int] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    glonass: GlonassEphemerides | None = None
    unused: dict[str, int] = field(default_factory=dict)

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of all satellites with ephemerides, e.g. ``('E01', 'G01', 'R03')``."""
        out: set[str] = set()
        for eph in self.ephemerides.values():
            out.update(eph.satellites)
        if self.glonass is not None:
            out.update(self.glonass.satellites)
        return tuple(sorted(out))

    @property
    def systems(self) -> tuple[str, ...]:
        """Sorted letters of the systems with at least one record, e.g. ``('E', 'G', 'R')``."""
        out = set(self.ephemerides)
        if self.glonass is not None and len(self.glonass):
            out.add("R")
        return tuple(sorted(out))

    @property
    def glonass_channels(self) -> dict[str, int]:
        """GLONASS FDMA frequency number per satellite, e.g. ``{'R01': 1}`` (empty without R)."""
        return {} if self.glonass is None else self.glonass.channels

    def reference_times_gps_s(self, system: str) -> NDArray[np.float64]:
        """Return the reference times of a system's healthy records (toe; GLONASS tb).

        Parameters
        ----------
        system : str
            System letter such as ``'G'`` or ``'R'``.

        Returns
        -------
        ndarray of float64
            Sorted reference times, GPS seconds; empty when the system has no
            healthy record.

        """
        if system == "R":
            g = self.glonass
            t = np.empty(0) if g is None else g.tb_gps_s[g.health == 0]
        else:
            eph = self.ephemerides.get(system)
            t = np.empty(0) if eph is None else eph.toe_gps_s[eph.health == 0]
        return np.sort(t)

    @staticmethod
    def validity_s(system: str) -> float:
        """Return how far from its reference time a record is used, s (4 h; GLONASS 30 min)."""
        return GLONASS_MAX_AGE_S if system == "R" else MAX_AGE_S.get(system, 4 * 3600.0)

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
        psdbound.io.ephemeris.kepler_positions_ecef_m : the Keplerian propagation.
        psdbound.io.glonass.glonass_positions_ecef_m : the GLONASS integration.

        """
        sat = check_sat_id(sat)
        if sat[0] == "R":
            if self.glonass is None:
                return nan_positions(t_gps_s)
            return glonass_positions_ecef_m(self.glonass, sat, t_gps_s)
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
            group delay; GLONASS: ``-tau_n + gamma_n (t - tb)``); NaN where no
            healthy ephemeris is valid.

        """
        sat = check_sat_id(sat)
        if sat[0] == "R":
            if self.glonass is None:
                return np.full(np.atleast_1d(np.asarray(t_gps_s)).shape, np.nan)
            return glonass_clock_s(self.glonass, sat, t_gps_s)
        eph = self.ephemerides.get(sat[0])
        if eph is None:
            return np.full(np.atleast_1d(np.asarray(t_gps_s)).shape, np.nan)
        return kepler_clock_s(eph, sat, t_gps_s)


def _unique_records(table: Any, *columns: str) -> Any:
    """Return the records without repeats (equal in every one of ``columns``), first kept."""
    keys = list(zip(*(getattr(table, c).tolist() for c in columns), strict=True))
    first = {k: n for n, k in reversed(list(enumerate(keys)))}
    return table.select(np.sort(np.fromiter(first.values(), dtype=np.intp, count=len(first))))


def merge_navigation(navs: Sequence[Navigation], path: str | Path) -> Navigation:
    """Join the records of several navigation files (e.g. consecutive days) into one.

    Parameters
    ----------
    navs : sequence of Navigation
        The files read, in the order given.
    path : str or Path
        The name of the joined set (for messages), e.g. ``a.rnx + b.rnx``.

    Returns
    -------
    Navigation
        Every system's records of every file, a record repeated in two files
        (same satellite, time of ephemeris, issue of data) once; the first
        file's version, the first leap seconds given, the skipped and unused
        records summed and the warnings of every file.
    """
    ephs: dict[str, KeplerEphemerides] = {}
    for system in sorted({s for n in navs for s in n.ephemerides}):
        parts = [n.ephemerides[system] for n in navs if system in n.ephemerides]
        ephs[system] = _unique_records(parts[0].concatenate(*parts[1:]), *_KEPLER_KEY)
    glo = [n.glonass for n in navs if n.glonass is not None]
    skipped: dict[str, int] = {}
    unused: dict[str, int] = {}
    for n in navs:
        for s, k in n.skipped.items():
            skipped[s] = skipped.get(s, 0) + k
        for s, k in n.unused.items():
            unused[s] = unused.get(s, 0) + k
    return Navigation(
        path=Path(path),
        version=navs[0].version,
        leap_seconds=next((n.leap_seconds for n in navs if n.leap_seconds is not None), None),
        ephemerides=ephs,
        skipped=dict(sorted(skipped.items())),
        warnings=tuple(w for n in navs for w in n.warnings),
        glonass=_unique_records(glo[0].concatenate(*glo[1:]), *_GLONASS_KEY) if glo else None,
        unused=dict(sorted(unused.items())),
    )
