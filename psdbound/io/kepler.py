"""Keplerian broadcast-ephemeris records: the container shared by readers and propagation.

:class:`KeplerEphemerides` holds the records of one satellite system as
columns (one row per navigation record). It is filled by the RINEX
navigation reader (:func:`psdbound.io.nav.read_nav`) and the nominal
constellations (:func:`psdbound.io.nominal.nominal_navigation`), and
propagated by :mod:`psdbound.io.ephemeris`.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["KeplerEphemerides", "PRN_RANGE", "RecordTable", "SAT_ID_RE", "check_sat_id"]

#: Satellite numbers per system letter (RINEX 3.05 ids; SBAS ids are PRN - 100), in
#: observation, navigation and SP3 files alike.
PRN_RANGE = {
    "G": (1, 63),
    "R": (1, 36),
    "E": (1, 50),
    "C": (1, 63),
    "J": (1, 10),
    "S": (20, 59),
    "I": (1, 14),
}

#: A satellite id: system letter and two digits (the first may be blank), e.g. ``'G05'``.
SAT_ID_RE = re.compile(r"^[A-Z][ 0-9]\d$")


def check_sat_id(sat: str) -> str:
    """Return a satellite id in the ``'G05'`` form (``'G 5'`` becomes ``'G05'``).

    Parameters
    ----------
    sat : str
        Satellite id.

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If ``sat`` is not a satellite id like ``'G05'``.
    """
    s = str(sat)
    if len(s) == 3 and s[1] == " ":
        s = s[0] + "0" + s[2]
    if not SAT_ID_RE.match(s):
        raise ValueError(f"satellite id must look like 'G05', got {sat!r}")
    return s


class RecordTable:
    """Mixin of broadcast-record dataclasses: each attribute a 1-D array, one row per record."""

    def select(self, mask: ArrayLike) -> Any:
        """Return the records selected by a boolean mask or index array.

        Parameters
        ----------
        mask : array_like of bool or int
            Row selection applied to every attribute.

        Returns
        -------
        same type as ``self``
            A new object holding only the selected rows.
        """
        sel = np.asarray(mask)
        return type(self)(**{f.name: getattr(self, f.name)[sel] for f in fields(self)})  # type: ignore[arg-type]

    def concatenate(self, *others: Any) -> Any:
        """Return these records followed by those of ``others`` (same type), in that order.

        Parameters
        ----------
        *others : same type as ``self``
            Further records (e.g. of the next day's navigation file).

        Returns
        -------
        same type as ``self``
        """
        tables = (self, *others)
        return type(self)(  # type: ignore[call-arg]
            **{f.name: np.concatenate([getattr(t, f.name) for t in tables]) for f in fields(self)}
        )


@dataclass(frozen=True, eq=False)
class KeplerEphemerides(RecordTable):
    """Keplerian broadcast ephemerides of one satellite system.

    One row per navigation record, in file order. All attributes are 1-D numpy
    arrays of equal length.

    Attributes
    ----------
    sat : ndarray of str
        Satellite id, e.g. ``'G01'``.
    toc_gps_s : ndarray of float64
        Time of clock, GPS seconds (BeiDou: converted from BDT).
    toe_gps_s : ndarray of float64
        Time of ephemeris, GPS seconds (week number of the record + toe).
    toe_sow_s : ndarray of float64
        Time of ephemeris as broadcast, seconds of the system's own week
        (GPS/GST/BDT), needed by the user algorithm for the node longitude.
    af0_s, af1, af2 : ndarray of float64
        Clock bias (s), drift (s/s) and drift rate (s/s^2).
    crs_m, crc_m : ndarray of float64
        Orbit radius harmonic corrections, m.
    delta_n_rad_s : ndarray of float64
        Mean motion difference, rad/s.
    m0_rad : ndarray of float64
        Mean anomaly at toe, rad.
    cuc_rad, cus_rad : ndarray of float64
        Argument of latitude harmonic corrections, rad.
    e : ndarray of float64
        Eccentricity (dimensionless).
    sqrt_a : ndarray of float64
        Square root of the semi-major axis, m^0.5.
    cic_rad, cis_rad : ndarray of float64
        Inclination harmonic corrections, rad.
    omega0_rad : ndarray of float64
        Longitude of the ascending node at the start of the week, rad.
    i0_rad : ndarray of float64
        Inclination at toe, rad.
    omega_rad : ndarray of float64
        Argument of perigee, rad.
    omega_dot_rad_s : ndarray of float64
        Rate of right ascension, rad/s.
    idot_rad_s : ndarray of float64
        Rate of inclination, rad/s.
    health : ndarray of int64
        SV health field (0 = healthy; Galileo: bit-coded signal health).
    iode : ndarray of int64
        Issue of data (GPS/QZSS IODE, Galileo IODnav, BeiDou AODE).
    data_source : ndarray of int64
        Galileo data-source bit field (bit 0/2/9: I/NAV, bit 1/8: F/NAV);
        0 for the other systems.

    """

    sat: NDArray[np.str_]
    toc_gps_s: NDArray[np.float64]
    toe_gps_s: NDArray[np.float64]
    toe_sow_s: NDArray[np.float64]
    af0_s: NDArray[np.float64]
    af1: NDArray[np.float64]
    af2: NDArray[np.float64]
    crs_m: NDArray[np.float64]
    delta_n_rad_s: NDArray[np.float64]
    m0_rad: NDArray[np.float64]
    cuc_rad: NDArray[np.float64]
    e: NDArray[np.float64]
    cus_rad: NDArray[np.float64]
    sqrt_a: NDArray[np.float64]
    cic_rad: NDArray[np.float64]
    omega0_rad: NDArray[np.float64]
    cis_rad: NDArray[np.float64]
    i0_rad: NDArray[np.float64]
    crc_m: NDArray[np.float64]
    omega_rad: NDArray[np.float64]
    omega_dot_rad_s: NDArray[np.float64]
    idot_rad_s: NDArray[np.float64]
    health: NDArray[np.int64]
    iode: NDArray[np.int64]
    data_source: NDArray[np.int64]

    def __len__(self) -> int:
        return int(self.sat.shape[0])

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of the satellites with at least one record."""
        return tuple(sorted({str(s) for s in self.sat}))
