"""Record layout and column collection shared by the RINEX 2, 3 and 4 navigation parsers.

A Keplerian navigation record is an epoch line (satellite, time of clock,
three clock terms) and seven orbit lines of four 19-character Fortran reals.
:class:`RecordParser` reads the numbers of one record into per-system
columns and builds :class:`~psdbound.io.kepler.KeplerEphemerides` from them
(times in GPS seconds, BeiDou converted from BDT). The version-specific
parts -- column offsets, the epoch line and the record boundaries -- are in
:mod:`psdbound.io._nav_rinex2` and :mod:`psdbound.io._nav_rinex3`.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from psdbound.errors import InputError
from psdbound.io.kepler import PRN_RANGE, KeplerEphemerides
from psdbound.io.timescales import SECONDS_PER_WEEK, calendar_to_gps_s

__all__ = [
    "ATTRS",
    "BDT_MINUS_GPST_S",
    "BDT_WEEK0_IN_GPS_WEEKS",
    "DESCRIPTION",
    "FIELD_TABLE",
    "FIELD_WIDTH",
    "KEPLER_LINES",
    "OPTIONAL",
    "REQUIRED",
    "Epoch",
    "RecordParser",
    "valid_calendar",
]

# BDT = GPST - 14 s; BDT week 0 starts 2006-01-01 = GPS week 1356.
BDT_MINUS_GPST_S = -14.0
BDT_WEEK0_IN_GPS_WEEKS = 1356
FIELD_WIDTH = 19

# (orbit line, field index) -> attribute; orbit line 0 is the epoch line.
REQUIRED = {
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
OPTIONAL = {
    (1, 0): "iode",
    (5, 1): "data_source",
    (6, 1): "health",
}
DESCRIPTION = {
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
ATTRS = [v for v in REQUIRED.values()] + [v for v in OPTIONAL.values()]
FIELD_TABLE = sorted(
    [(k, v, True) for k, v in REQUIRED.items()] + [(k, v, False) for k, v in OPTIONAL.items()]
)
KEPLER_LINES = 8

#: Calendar fields of a time of clock: year, month, day, hour, minute, second.
Epoch = tuple[int, int, int, int, int, float]

#: Plausible Keplerian elements; a record outside them cannot be a GNSS orbit.
_PLAUSIBLE = {
    "sqrt_a": (2000.0, 10000.0, "sqrt(A) of 2000-10000 m^0.5"),
    "e": (0.0, 0.5, "eccentricity from 0 to 0.5"),
    "toe_sow_s": (0.0, 604800.0, "Toe within the week (0-604800 s)"),
    "_week": (0.0, 10000.0, "a week number from 0 to 10000"),
}


def valid_calendar(ep: Epoch, two_digit_year: bool = False) -> bool:
    """True when the calendar fields are a real date and time (year 1980-2099)."""
    y, mo, d, h, mi, s = ep
    if two_digit_year:
        if not 0 <= y <= 99:
            return False
        y = y + 2000 if y < 80 else y + 1900
    if not (1980 <= y <= 2099 and 1 <= mo <= 12 and 0 <= h <= 23 and 0 <= mi <= 59):
        return False
    if not 0.0 <= s < 60.0:  # also False for NaN
        return False
    days = [
        31,
        29 if (y % 4 == 0 and y % 100 != 0) or y % 400 == 0 else 28,
        31,
        30,
        31,
        30,
        31,
        31,
        30,
        31,
        30,
        31,
    ]
    return 1 <= d <= days[mo - 1]


class RecordParser:
    """Collect the Keplerian records of a navigation file body into columns.

    Subclasses set the column offsets, read the epoch line and walk the
    records (``parse``); this class reads the numbers and builds the output.
    """

    #: 0-based column of the first field of the epoch line.
    FIRST_COLUMN = 0
    #: 0-based column of the first field of an orbit line.
    CONTINUATION_COLUMN = 0
    #: Columns of the epoch, for messages.
    EPOCH_COLUMNS = ""

    def __init__(self, path: Path, lines: list[str]) -> None:
        self.path = path
        self.lines = lines
        self.cols: dict[str, dict[str, list[float]]] = {}
        self.sats: dict[str, list[str]] = {}
        self.epochs: dict[str, list[Epoch]] = {}
        self.skipped: dict[str, int] = {}
        self.last_nonblank = len(lines) - 1
        #: records left out because they are damaged: (line index, satellite, reason)
        self.damaged: list[tuple[int, str, str]] = []

    #: RINEX 2 epochs carry two-digit years
    TWO_DIGIT_YEAR = False

    def check_sat(self, sat: str, idx: int, columns: str) -> None:
        """Raise InputError unless ``sat`` is a satellite id within its system's range."""
        lo, hi = PRN_RANGE.get(sat[:1], (1, 99))
        num = sat[1:]
        if not (len(sat) == 3 and num.isdigit() and lo <= int(num) <= hi):
            raise self.error(
                f"satellite id {sat!r} in {columns} is not valid: expected a system letter and "
                f"a number from {lo:02d} to {hi:02d}",
                idx,
            )

    def error(self, message: str, line_index: int) -> InputError:
        return InputError(message, path=self.path, line=line_index + 1)

    def last_line(self, start: int) -> int:
        """Index of the last non-blank line at or after ``start`` (``start - 1`` if none)."""
        last = len(self.lines) - 1
        while last >= start and not self.lines[last].strip():
            last -= 1
        self.last_nonblank = last
        return last

    def epoch(self, line0: str) -> Epoch:
        """Calendar fields of the epoch line; ValueError when they do not parse."""
        raise NotImplementedError

    def describe(self, attr: str) -> str:
        """Name of a record field for messages (e.g. ``'sqrt(A)'``)."""
        return DESCRIPTION.get(attr, attr)

    # -- numbers ------------------------------------------------------------
    def number(self, rec: list[int], k: int, j: int, sat: str, attr: str, required: bool) -> float:
        idx = rec[k]
        text = self.lines[idx]
        if k == 0:
            start = self.FIRST_COLUMN + (j - 1) * FIELD_WIDTH
        else:
            start = self.CONTINUATION_COLUMN + j * FIELD_WIDTH
        s = text[start : start + FIELD_WIDTH]
        col = f"columns {start + 1}-{start + FIELD_WIDTH}"
        what = f"{self.describe(attr)} of {sat}"
        if len(s) < FIELD_WIDTH and s.strip() and idx == self.last_nonblank:
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
            ep = self.epoch(line0)
        except ValueError:
            raise self.error(
                f"cannot parse the epoch (time of clock) of {sat} in {self.EPOCH_COLUMNS}: "
                f"{line0[:23].rstrip()!r}; expected 'yyyy mm dd hh mm ss'",
                rec[0],
            ) from None
        cols = self.cols.get(system)
        if cols is None:
            cols = self.cols[system] = {a: [] for a in ATTRS}
            self.sats[system] = []
            self.epochs[system] = []
        values = {
            attr: self.number(rec, k, j, sat, attr, required)
            for (k, j), attr, required in FIELD_TABLE
        }
        reason = self.damage(ep, values)
        if reason:
            self.damaged.append((rec[0], sat, reason))
            return
        for attr, v in values.items():
            cols[attr].append(v)
        self.sats[system].append(sat)
        self.epochs[system].append(ep)

    def damage(self, ep: Epoch, values: dict[str, float]) -> str:
        """Why a record cannot be used (empty when it can)."""
        if not valid_calendar(ep, self.TWO_DIGIT_YEAR):
            return f"impossible time of clock {' '.join(f'{v:g}' for v in ep)}"
        bad = [DESCRIPTION[a] for a, v in values.items() if not math.isfinite(v)]
        if bad:
            return f"non-finite {bad[0]}"
        for attr, (lo, hi, what) in _PLAUSIBLE.items():
            if not lo <= values[attr] <= hi:
                return f"{DESCRIPTION[attr]} {values[attr]:g} (expected {what})"
        return ""

    def damage_note(self) -> str:
        """One line about the damaged records left out (empty when none)."""
        if not self.damaged:
            return ""
        idx, sat, reason = self.damaged[0]
        return (
            f"{len(self.damaged)} navigation record(s) left out because they cannot be a "
            f"valid ephemeris (first: {sat} on line {idx + 1}, {reason})"
        )

    def truncated(self, sat: str, have: int, need: int, idx: int) -> InputError:
        return self.error(
            f"truncated navigation record: the file ends in the middle of the record of {sat} "
            f"(it has {have} of its {need} lines)",
            idx,
        )

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
                toc = toc - BDT_MINUS_GPST_S
                toe = toe + BDT_WEEK0_IN_GPS_WEEKS * SECONDS_PER_WEEK - BDT_MINUS_GPST_S
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
