"""Reader for RINEX broadcast navigation files (Keplerian ephemerides).

Supported inputs
----------------
* RINEX 2.x GPS navigation files (file type ``N``). RINEX 2 GLONASS (``G``)
  and GEO/SBAS (``H``) navigation files are read too, but their records are
  only counted (in :attr:`Navigation.skipped`), not parsed.
* RINEX 3.0x navigation files, single-system or mixed. Keplerian records of
  GPS (``G``), Galileo (``E``), BeiDou (``C``) and QZSS (``J``) are parsed;
  GLONASS (``R``), SBAS (``S``) and NavIC/IRNSS (``I``) records are skipped
  and counted per system.

RINEX 4 navigation files (``> EPH`` record headers) are not supported.

Every epoch is converted to GPS seconds (see :mod:`psdbound.io.timescales`):
GPS, QZSS and Galileo labels are used directly (GST and QZSST are labelled
like GPS time in RINEX), BeiDou labels are BDT and get +14 s. The week number
of each record (GPS week, GST week aligned with GPS, or BDT week + 1356) gives
the full time of ephemeris ``toe_gps_s``; it is moved by whole weeks to the one
nearest to ``toc_gps_s`` so that week-rollover or "week of transmission"
conventions of some writers cannot put it in the wrong week.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.io._source import read_bytes
from psdbound.io.timescales import SECONDS_PER_WEEK, calendar_to_gps_s

__all__ = [
    "KeplerEphemerides",
    "Navigation",
    "read_nav",
    "KEPLER_SYSTEMS",
    "SKIPPED_SYSTEMS",
]

#: Systems whose RINEX records are Keplerian broadcast ephemerides parsed here.
KEPLER_SYSTEMS: tuple[str, ...] = ("G", "E", "C", "J")
#: Systems whose records are recognised but skipped (only counted).
SKIPPED_SYSTEMS: tuple[str, ...] = ("R", "S", "I")

_SYSTEM_NAMES = {
    "G": "GPS",
    "E": "Galileo",
    "C": "BeiDou",
    "J": "QZSS",
    "R": "GLONASS",
    "S": "SBAS",
    "I": "NavIC/IRNSS",
}
# BDT = GPST - 14 s; BDT week 0 starts 2006-01-01 = GPS week 1356.
_BDT_MINUS_GPST_S = -14.0
_BDT_WEEK0_IN_GPS_WEEKS = 1356
_FIELD_WIDTH = 19
_SAT_RE = re.compile(r"^[A-Z][ 0-9]\d$")


@dataclass(frozen=True, eq=False)
class KeplerEphemerides:
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

    def select(self, mask: ArrayLike) -> KeplerEphemerides:
        """Return the records selected by a boolean mask or index array.

        Parameters
        ----------
        mask : array_like of bool or int
            Row selection applied to every attribute.

        Returns
        -------
        KeplerEphemerides
            A new object holding only the selected rows.

        """
        sel = np.asarray(mask)
        return KeplerEphemerides(**{f.name: getattr(self, f.name)[sel] for f in fields(self)})


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

    """

    path: Path
    version: float
    leap_seconds: int | None
    ephemerides: dict[str, KeplerEphemerides] = field(default_factory=dict)
    skipped: dict[str, int] = field(default_factory=dict)

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
        from psdbound.io.ephemeris import kepler_positions_ecef_m, nan_positions

        sat = _check_sat(sat)
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
        from psdbound.io.ephemeris import satellite_clock_s

        sat = _check_sat(sat)
        eph = self.ephemerides.get(sat[0])
        if eph is None:
            return np.full(np.atleast_1d(np.asarray(t_gps_s)).shape, np.nan)
        return satellite_clock_s(eph, sat, t_gps_s)


def _check_sat(sat: str) -> str:
    s = str(sat)
    if len(s) == 3 and s[1] == " ":
        s = s[0] + "0" + s[2]
    if not _SAT_RE.match(s):
        raise ValueError(f"satellite id must look like 'G05', got {sat!r}")
    return s


# --------------------------------------------------------------------------- parsing

# (orbit line, field index) -> attribute; orbit line 0 is the epoch line.
_REQUIRED = {
    (0, 1): "af0_s",
    (0, 2): "af1",
    (0, 3): "af2",
    (1, 1): "crs_m",
    (1, 2): "delta_n_rad_s",
    (1, 3): "m0_rad",
    (2, 0): "cuc_rad",
    (2, 1): "e",
    (2, 2): "cus_rad",
    (2, 3): "sqrt_a",
    (3, 0): "toe_sow_s",
    (3, 1): "cic_rad",
    (3, 2): "omega0_rad",
    (3, 3): "cis_rad",
    (4, 0): "i0_rad",
    (4, 1): "crc_m",
    (4, 2): "omega_rad",
    (4, 3): "omega_dot_rad_s",
    (5, 0): "idot_rad_s",
    (5, 2): "_week",
}
# Fields that may legitimately be blank in some files (read as 0).
_OPTIONAL = {
    (1, 0): "iode",
    (5, 1): "data_source",
    (6, 1): "health",
}
_DESCRIPTION = {
    "af0_s": "clock bias af0",
    "af1": "clock drift af1",
    "af2": "clock drift rate af2",
    "crs_m": "Crs",
    "delta_n_rad_s": "Delta n",
    "m0_rad": "M0",
    "cuc_rad": "Cuc",
    "e": "eccentricity",
    "cus_rad": "Cus",
    "sqrt_a": "sqrt(A)",
    "toe_sow_s": "Toe",
    "cic_rad": "Cic",
    "omega0_rad": "OMEGA0",
    "cis_rad": "Cis",
    "i0_rad": "i0",
    "crc_m": "Crc",
    "omega_rad": "omega",
    "omega_dot_rad_s": "OMEGA DOT",
    "idot_rad_s": "IDOT",
    "_week": "week number",
    "iode": "IODE",
    "data_source": "data source / L2 codes",
    "health": "SV health",
}
_ATTRS = [v for v in _REQUIRED.values()] + [v for v in _OPTIONAL.values()]
_FIELD_TABLE = sorted(
    [(k, v, True) for k, v in _REQUIRED.items()] + [(k, v, False) for k, v in _OPTIONAL.items()]
)
_KEPLER_LINES = 8
# Minimum number of lines of the records that are only counted.
_SKIPPED_LINES = {"R": 4, "S": 4, "I": 8}


class _Parser:
    """Parse the body of a navigation file into column lists."""

    def __init__(self, path: Path, lines: list[str], version: float) -> None:
        self.path = path
        self.lines = lines
        self.version = version
        self.rinex2 = version < 3.0
        # RINEX 2: epoch-line fields start at column 23 (1-based), orbit-line
        # fields at 4; RINEX 3: 24 and 5.
        self.first = 22 if self.rinex2 else 23
        self.cont = 3 if self.rinex2 else 4
        self.cols: dict[str, dict[str, list[float]]] = {}
        self.sats: dict[str, list[str]] = {}
        self.epochs: dict[str, list[tuple[int, int, int, int, int, float]]] = {}
        self.skipped: dict[str, int] = {}
        self.last_nonblank = len(lines) - 1

    def error(self, message: str, line_index: int) -> InputError:
        return InputError(message, path=self.path, line=line_index + 1)

    # -- numbers ------------------------------------------------------------
    def number(self, rec: list[int], k: int, j: int, sat: str, attr: str, required: bool) -> float:
        idx = rec[k]
        text = self.lines[idx]
        start = (self.first + (j - 1) * _FIELD_WIDTH) if k == 0 else (self.cont + j * _FIELD_WIDTH)
        s = text[start : start + _FIELD_WIDTH]
        col = f"columns {start + 1}-{start + _FIELD_WIDTH}"
        what = f"{_DESCRIPTION[attr]} of {sat}"
        if len(s) < _FIELD_WIDTH and s.strip() and idx == self.last_nonblank:
            raise self.error(
                f"truncated navigation record: {what} ({col}) is cut short at the end of the "
                f"file; the file ends in the middle of the record of {sat}",
                idx,
            )
        try:
            return float(s)
        except ValueError:
            pass
        if not s.strip():
            if not required:
                return 0.0
            if idx == self.last_nonblank:
                raise self.error(
                    f"truncated navigation record: {what} ({col}) is missing at the end of "
                    f"the file; the file ends in the middle of the record of {sat}",
                    idx,
                )
            raise self.error(f"missing value: {what} ({col}) is blank; expected a number", idx)
        try:
            return float(s.replace("D", "E").replace("d", "e"))
        except ValueError:
            raise self.error(
                f"cannot parse number {s.strip()!r} in {col} ({what}); expected a "
                "Fortran real such as 1.234567890123E-05 (D exponents allowed)",
                idx,
            ) from None

    # -- records ------------------------------------------------------------
    def add_kepler(self, system: str, sat: str, rec: list[int]) -> None:
        line0 = self.lines[rec[0]]
        try:
            if self.rinex2:
                ep = (
                    int(line0[2:5]),
                    int(line0[5:8]),
                    int(line0[8:11]),
                    int(line0[11:14]),
                    int(line0[14:17]),
                    float(line0[17:22]),
                )
            else:
                ep = (
                    int(line0[3:8]),
                    int(line0[8:11]),
                    int(line0[11:14]),
                    int(line0[14:17]),
                    int(line0[17:20]),
                    float(line0[20:23]),
                )
        except ValueError:
            span = "columns 3-22" if self.rinex2 else "columns 5-23"
            raise self.error(
                f"cannot parse the epoch (time of clock) of {sat} in {span}: "
                f"{line0[:23].rstrip()!r}; expected 'yyyy mm dd hh mm ss'",
                rec[0],
            ) from None
        cols = self.cols.get(system)
        if cols is None:
            cols = self.cols[system] = {a: [] for a in _ATTRS}
            self.sats[system] = []
            self.epochs[system] = []
        for (k, j), attr, required in _FIELD_TABLE:
            cols[attr].append(self.number(rec, k, j, sat, attr, required))
        self.sats[system].append(sat)
        self.epochs[system].append(ep)

    def truncated(self, sat: str, have: int, need: int, idx: int) -> InputError:
        return self.error(
            f"truncated navigation record: the file ends in the middle of the record of {sat} "
            f"(it has {have} of its {need} lines)",
            idx,
        )

    def parse(self, start: int) -> None:
        lines = self.lines
        n = len(lines)
        last = n - 1
        while last >= start and not lines[last].strip():
            last -= 1
        self.last_nonblank = last
        if self.rinex2:
            self.parse_rinex2(start, last)
        else:
            self.parse_rinex3(start, last)

    def parse_rinex3(self, i: int, last: int) -> None:
        lines = self.lines
        while i <= last:
            line = lines[i]
            if not line.strip():
                i += 1
                continue
            system = line[0]
            if system == " " or not line[:3].strip():
                raise self.error(
                    "unexpected continuation line; expected the first line of a navigation "
                    "record starting with a satellite id such as 'G01' in columns 1-3",
                    i,
                )
            if system == ">":
                raise self.error(
                    "RINEX 4 record header ('> EPH ...') found; only RINEX 2 and 3 "
                    "navigation files are supported",
                    i,
                )
            sat = line[:3].replace(" ", "0")
            if not _SAT_RE.match(sat):
                raise self.error(
                    f"cannot read the satellite id {line[:3]!r} in columns 1-3; expected "
                    "a system letter and a 2-digit number such as 'G01'",
                    i,
                )
            # collect continuation lines (those starting with a blank)
            j = i + 1
            while j <= last and lines[j][:1] == " " and lines[j].strip():
                j += 1
            rec = list(range(i, j))
            if system in KEPLER_SYSTEMS:
                if len(rec) < _KEPLER_LINES:
                    if j > last:
                        raise self.truncated(sat, len(rec), _KEPLER_LINES, j - 1)
                    raise self.error(
                        f"incomplete navigation record of {sat}: {len(rec)} lines found "
                        f"before the next record; expected {_KEPLER_LINES} lines",
                        j - 1,
                    )
                if len(rec) > _KEPLER_LINES:
                    raise self.error(
                        f"navigation record of {sat} has more than {_KEPLER_LINES} lines; "
                        "expected the next record to start with a satellite id",
                        rec[_KEPLER_LINES],
                    )
                self.add_kepler(system, sat, rec)
            elif system in SKIPPED_SYSTEMS:
                need = _SKIPPED_LINES[system]
                if len(rec) < need and j > last:
                    raise self.truncated(sat, len(rec), need, j - 1)
                self.skipped[system] = self.skipped.get(system, 0) + 1
            else:
                raise self.error(
                    f"unknown satellite system letter {system!r} in satellite id {sat!r}; "
                    "expected one of G, E, C, J, R, S, I",
                    i,
                )
            i = j

    def parse_rinex2(self, i: int, last: int, system: str = "G") -> None:
        lines = self.lines
        need = _KEPLER_LINES if system == "G" else 4
        while i <= last:
            if not lines[i].strip():
                i += 1
                continue
            prn_text = lines[i][:2]
            try:
                prn = int(prn_text)
            except ValueError:
                raise self.error(
                    f"cannot read the PRN {prn_text!r} in columns 1-2; expected the first "
                    "line of a RINEX 2 navigation record",
                    i,
                ) from None
            sat = f"{system}{prn:02d}"
            if last - i + 1 < need:
                raise self.truncated(sat, last - i + 1, need, last)
            rec = list(range(i, i + need))
            for k in rec[1:]:
                if lines[k][:3].strip():
                    raise self.error(
                        f"incomplete navigation record of {sat}: line {k + 1} starts a new "
                        f"record; expected {need} lines per record",
                        k,
                    )
            if system == "G":
                self.add_kepler(system, sat, rec)
            else:
                self.skipped[system] = self.skipped.get(system, 0) + 1
            i += need

    # -- output ---------------------------------------------------------------
    def build(self) -> dict[str, KeplerEphemerides]:
        out: dict[str, KeplerEphemerides] = {}
        for system, cols in self.cols.items():
            arr = {a: np.asarray(v, dtype=np.float64) for a, v in cols.items()}
            ep = np.asarray(self.epochs[system], dtype=np.float64)
            toc = calendar_to_gps_s(
                ep[:, 0].astype(np.int64),
                ep[:, 1].astype(np.int64),
                ep[:, 2].astype(np.int64),
                ep[:, 3].astype(np.int64),
                ep[:, 4].astype(np.int64),
                ep[:, 5],
            )
            week = arr.pop("_week")
            toe = week * SECONDS_PER_WEEK + arr["toe_sow_s"]
            if system == "C":
                toc = toc - _BDT_MINUS_GPST_S
                toe = toe + _BDT_WEEK0_IN_GPS_WEEKS * SECONDS_PER_WEEK - _BDT_MINUS_GPST_S
            # put toe in the week nearest to toc (rollover / writer conventions)
            toe = toe + np.round((toc - toe) / SECONDS_PER_WEEK) * SECONDS_PER_WEEK
            ints = {
                a: np.round(arr.pop(a)).astype(np.int64) for a in ("health", "iode", "data_source")
            }
            if system != "E":
                ints["data_source"] = np.zeros_like(ints["data_source"])
            out[system] = KeplerEphemerides(
                sat=np.asarray(self.sats[system], dtype="<U3"),
                toc_gps_s=toc,
                toe_gps_s=toe,
                **arr,
                **ints,
            )
        return dict(sorted(out.items()))


def _header(path: Path, lines: list[str]) -> tuple[float, str, int | None, int]:
    """Return (version, file type, leap seconds, index of END OF HEADER)."""
    first = lines[0] if lines else ""
    if first.startswith(("#a", "#b", "#c", "#d")):
        raise InputError(
            "this is an SP3 precise orbit file, not a RINEX navigation file; "
            "expected a RINEX navigation file (use read_sp3 for SP3)",
            path=path,
            line=1,
        )
    if first[60:80].strip() != "RINEX VERSION / TYPE":
        raise InputError(
            "not a RINEX file: line 1 has no 'RINEX VERSION / TYPE' label in columns "
            "61-80; expected a RINEX navigation file",
            path=path,
            line=1,
        )
    try:
        version = float(first[:9])
    except ValueError:
        raise InputError(
            f"cannot read the RINEX version {first[:9].strip()!r} in columns 1-9",
            path=path,
            line=1,
        ) from None
    ftype = first[20:21].upper()
    described = first[20:40].strip()
    if ftype not in ("N", "G", "H"):
        raise InputError(
            f"header says file type {ftype!r} ({described!r}); expected a navigation "
            "file (RINEX VERSION / TYPE type 'N', e.g. 'NAVIGATION DATA')",
            path=path,
            line=1,
        )
    if version >= 4.0:
        raise InputError(
            f"RINEX {version:.2f} navigation files are not supported; expected RINEX 2 "
            "or 3 navigation data",
            path=path,
            line=1,
        )
    leap: int | None = None
    for i, line in enumerate(lines):
        label = line[60:80].strip()
        if label == "END OF HEADER":
            return version, ftype, leap, i
        if label == "LEAP SECONDS":
            try:
                leap = int(line[:6])
            except ValueError:
                raise InputError(
                    f"cannot read the leap seconds {line[:6].strip()!r} in columns 1-6",
                    path=path,
                    line=i + 1,
                ) from None
    raise InputError(
        f"no 'END OF HEADER' line found (the file has {len(lines)} lines); the header of a "
        "RINEX navigation file must end with END OF HEADER",
        path=path,
        line=len(lines),
    )


def read_nav(path: str | os.PathLike[str]) -> Navigation:
    """Read a RINEX 2 or 3 broadcast navigation file.

    Parameters
    ----------
    path : str or path-like
        Navigation file, plain or compressed (gzip, Z, bz2, zip).

    Returns
    -------
    Navigation
        Keplerian ephemerides per system (GPS, Galileo, BeiDou, QZSS) and the
        counts of skipped GLONASS/SBAS/NavIC records.

    Raises
    ------
    InputError
        If the file is not a RINEX 2/3 navigation file (e.g. an observation or
        SP3 file), has no END OF HEADER, ends in the middle of a record, or
        holds a number that cannot be parsed. The message names the file, the
        1-based line and, where relevant, the satellite and columns.

    """
    p = Path(path)
    text = read_bytes(p).decode("latin-1")
    lines = text.split("\n")
    if lines and not lines[-1]:
        lines.pop()  # the newline ending the last line does not start a new one
    version, ftype, leap, end = _header(p, lines)
    parser = _Parser(p, lines, version)
    if version < 3.0 and ftype != "N":
        parser.last_nonblank = len(lines) - 1
        while parser.last_nonblank > end and not lines[parser.last_nonblank].strip():
            parser.last_nonblank -= 1
        parser.parse_rinex2(end + 1, parser.last_nonblank, "R" if ftype == "G" else "S")
    else:
        parser.parse(end + 1)
    return Navigation(
        path=p,
        version=version,
        leap_seconds=leap,
        ephemerides=parser.build(),
        skipped=dict(sorted(parser.skipped.items())),
    )
