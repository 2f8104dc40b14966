"""RINEX 3 navigation records: Keplerian (GPS, Galileo, BeiDou, QZSS) and GLONASS; others counted.

Layout (RINEX 3.0x): the epoch line holds the satellite id in columns 1-3,
the time of clock ``yyyy mm dd hh mm ss`` in columns 5-23 and three fields
from column 24; the orbit lines start with a blank and hold four fields from
column 5. A record runs to the next line that starts with a satellite id.
Keplerian records (:data:`KEPLER_SYSTEMS`) have eight lines, GLONASS records
four (five from RINEX 3.05; see :mod:`psdbound.io._nav_glonass`); SBAS and
NavIC records (:data:`SKIPPED_SYSTEMS`) are only counted.
"""

from __future__ import annotations

from psdbound.io._nav_glonass import GLONASS_LINES, GlonassParser
from psdbound.io._nav_records import KEPLER_LINES, Epoch
from psdbound.io.kepler import SAT_ID_RE

__all__ = ["KEPLER_SYSTEMS", "SKIPPED_SYSTEMS", "SKIPPED_LINES", "Rinex3Parser"]

#: Systems whose RINEX records are Keplerian broadcast ephemerides parsed here.
KEPLER_SYSTEMS: tuple[str, ...] = ("G", "E", "C", "J")
#: Systems whose records are recognised but skipped (only counted).
SKIPPED_SYSTEMS: tuple[str, ...] = ("S", "I")
#: Minimum number of lines of the records that are only counted.
SKIPPED_LINES = {"S": 4, "I": 8}


class Rinex3Parser(GlonassParser):
    """Parser of the body of a RINEX 3 navigation file (single-system or mixed)."""

    FIRST_COLUMN = 23
    CONTINUATION_COLUMN = 4
    EPOCH_COLUMNS = "columns 5-23"

    def epoch(self, line0: str) -> Epoch:
        """Calendar fields of the epoch line."""
        return (
            int(line0[3:8]),
            int(line0[8:11]),
            int(line0[11:14]),
            int(line0[14:17]),
            int(line0[17:20]),
            float(line0[20:23]),
        )

    def parse(self, start: int) -> None:
        """Read every record from line index ``start`` (the line after END OF HEADER) on."""
        lines = self.lines
        i = start
        last = self.last_line(start)
        while i <= last:
            line = lines[i]
            if not line.strip():
                i += 1
                continue
            sat = self._record_sat(line, i)
            # collect continuation lines (those starting with a blank)
            j = i + 1
            while j <= last and lines[j][:1] == " " and lines[j].strip():
                j += 1
            self._read_record(line[0], sat, list(range(i, j)), j > last)
            i = j

    def _record_sat(self, line: str, i: int) -> str:
        """Return the satellite id of the record's first line (index ``i``), checked."""
        system = line[0]
        if system == " " or not line[:3].strip():
            raise self.error(
                "unexpected continuation line; expected the first line of a navigation "
                "record starting with a satellite id such as 'G01' in columns 1-3",
                i,
            )
        if system == ">":
            raise self.error(
                "a RINEX 4 record header ('> EPH ...') in a file whose line 1 gives a "
                "RINEX 3 version; expected a satellite id such as 'G01' in columns 1-3 "
                "(if the file is RINEX 4, its line 1 should say 4.00-4.02)",
                i,
            )
        sat = line[:3].replace(" ", "0")
        if not SAT_ID_RE.match(sat):
            raise self.error(
                f"cannot read the satellite id {line[:3]!r} in columns 1-3; expected "
                "a system letter and a 2-digit number such as 'G01'",
                i,
            )
        if system in KEPLER_SYSTEMS or system in SKIPPED_SYSTEMS or system == "R":
            self.check_sat(sat, i, "columns 1-3")
        return sat

    def _read_record(self, system: str, sat: str, rec: list[int], at_end: bool) -> None:
        """Read, or count, the record on line indices ``rec`` (``at_end``: the file ends there)."""
        if system in KEPLER_SYSTEMS:
            self._kepler_record(system, sat, rec, at_end)
        elif system == "R":
            self._glonass_record(sat, rec, at_end)
        elif system in SKIPPED_SYSTEMS:
            need = SKIPPED_LINES[system]
            if len(rec) < need and at_end:
                raise self.truncated(sat, len(rec), need, rec[-1])
            self.skipped[system] = self.skipped.get(system, 0) + 1
        else:
            raise self.error(
                f"unknown satellite system letter {system!r} in satellite id {sat!r}; "
                "expected one of G, E, C, J, R, S, I",
                rec[0],
            )

    def _kepler_record(self, system: str, sat: str, rec: list[int], at_end: bool) -> None:
        """Read a Keplerian record, refusing one with fewer or more lines than its layout."""
        if len(rec) < KEPLER_LINES:
            if at_end:
                raise self.truncated(sat, len(rec), KEPLER_LINES, rec[-1])
            raise self.error(
                f"incomplete navigation record of {sat}: {len(rec)} lines found "
                f"before the next record; expected {KEPLER_LINES} lines",
                rec[-1],
            )
        if len(rec) > KEPLER_LINES:
            raise self.error(
                f"navigation record of {sat} has more than {KEPLER_LINES} lines; "
                "expected the next record to start with a satellite id",
                rec[KEPLER_LINES],
            )
        self.add_kepler(system, sat, rec)

    def _glonass_record(self, sat: str, rec: list[int], at_end: bool) -> None:
        """Read a GLONASS record, refusing one with fewer lines than its layout."""
        if len(rec) < GLONASS_LINES:
            if at_end:
                raise self.truncated(sat, len(rec), GLONASS_LINES, rec[-1])
            raise self.error(
                f"incomplete navigation record of {sat}: {len(rec)} lines found "
                f"before the next record; expected {GLONASS_LINES} lines (5 from "
                "RINEX 3.05)",
                rec[-1],
            )
        self.add_glonass(sat, rec[:GLONASS_LINES])
