"""RINEX 4 navigation records: the legacy ephemerides read as in RINEX 3, the rest counted.

Layout (RINEX 4.00-4.02): every record starts with a record header line
``> EPH G01 LNAV`` -- ``>`` in column 1, the record type in columns 3-5
(``EPH`` ephemeris, ``STO`` system time offset, ``EOP`` Earth orientation,
``ION`` ionosphere), the transmitting satellite in columns 7-9 and the
message type in columns 11-14 -- and runs to the next record header. The
lines of an ephemeris record of a legacy message follow the RINEX 3.05 layout
(the satellite, time of clock and clock terms, then orbit lines of four
19-character fields), so they are read by the RINEX 3 record code:

* GPS and QZSS ``LNAV``, Galileo ``INAV`` and ``FNAV``, BeiDou ``D1`` and
  ``D2``: eight lines, Keplerian (:data:`READ_MESSAGES`);
* GLONASS ``FDMA``: five lines, of which the first four are read;
* SBAS ``SBAS`` and NavIC ``LNAV``: counted per system, as in RINEX 3
  (:data:`COUNTED_MESSAGES`).

Every other record -- ``STO``, ``EOP``, ``ION``, and the ephemerides of the
modernised messages (``CNAV``, ``CNV1``-``CNV3``, ``L1OC``, ``L3OC``,
``L1NV``...), whose parameters the Keplerian propagation does not use -- is
skipped and counted per type (:attr:`Rinex4Parser.unused`); the reader says
so in one warning. An ephemeris record whose number of lines does not fit
its message is left out as damaged (the record headers make its end
certain); one that the end of the file cuts short is an error.
"""

from __future__ import annotations

import re
from collections import Counter
from pathlib import Path

from psdbound.io._nav_glonass import GLONASS_LINES
from psdbound.io._nav_records import KEPLER_LINES
from psdbound.io._nav_rinex3 import SKIPPED_LINES, Rinex3Parser
from psdbound.io.kepler import PRN_RANGE

__all__ = ["COUNTED_MESSAGES", "READ_MESSAGES", "RECORD_TYPES", "Rinex4Parser", "unused_note"]

#: Record types of RINEX 4 navigation files.
RECORD_TYPES: tuple[str, ...] = ("EPH", "STO", "EOP", "ION")
#: Ephemeris messages read, per system letter (the RINEX 3 records of the system).
READ_MESSAGES: dict[str, tuple[str, ...]] = {
    "G": ("LNAV",),
    "J": ("LNAV",),
    "E": ("INAV", "FNAV"),
    "C": ("D1", "D2"),
    "R": ("FDMA",),
}
#: Ephemeris messages only counted per system (as the RINEX 3 records of the system).
COUNTED_MESSAGES: dict[str, tuple[str, ...]] = {"S": ("SBAS",), "I": ("LNAV",)}
#: Lines (after the record header) of the ephemeris messages read: (fewest, most).
_LINES = {"R": (GLONASS_LINES, GLONASS_LINES + 1)}
# the satellite number may be blank in STO/EOP/ION records ('> STO E   IFNV')
_RECORD_HEADER = re.compile(r"> ([A-Z]{3}) ([A-Z][ \d]{2}) ([A-Z0-9]{1,4}) *")


class Rinex4Parser(Rinex3Parser):
    """Parser of the body of a RINEX 4 navigation file."""

    def __init__(self, path: Path, lines: list[str]) -> None:
        super().__init__(path, lines)
        #: records skipped, per record type (``'STO'``) or ephemeris message (``'EPH G CNAV'``)
        self.unused: Counter[str] = Counter()

    def parse(self, start: int) -> None:
        """Read every record from line index ``start`` (the line after END OF HEADER) on."""
        last = self.last_line(start)
        i = start
        while i <= last:
            if not self.lines[i].strip():
                i += 1
                continue
            if not self.lines[i].startswith(">"):
                raise self.error(
                    f"expected a record header such as '> EPH G01 LNAV' (a RINEX 4 navigation "
                    f"record starts with '>'), found {self.lines[i][:40].rstrip()!r}",
                    i,
                )
            j = i + 1
            while j <= last and not self.lines[j].startswith(">"):
                j += 1
            self.record(i, j, last)
            i = j

    def record_header(self, i: int) -> tuple[str, str, str]:
        """Record type, satellite and message type of the record header on line index ``i``."""
        line = self.lines[i].rstrip()
        m = _RECORD_HEADER.fullmatch(line)
        if m is None:
            raise self.error(
                f"cannot read the record header {line[:40]!r}; expected '>', the record type "
                "in columns 3-5, the satellite in columns 7-9 and the message type in columns "
                "11-14, e.g. '> EPH G01 LNAV'",
                i,
            )
        kind, sat, message = m.groups()
        return kind, sat if kind != "EPH" else sat.replace(" ", "0"), message

    def record(self, i: int, j: int, last: int) -> None:
        """Read or count the record on line indices ``i`` (its header) to ``j - 1``."""
        kind, sat, message = self.record_header(i)
        system = sat[0]
        if kind not in RECORD_TYPES:
            self.unused[f"unknown record type {kind}"] += 1
            return
        if kind != "EPH":
            self.unused[kind] += 1
            return
        if system not in PRN_RANGE:
            raise self.error(
                f"unknown satellite system letter {system!r} in the record header (columns "
                f"7-9); expected one of {', '.join(PRN_RANGE)}",
                i,
            )
        self.check_sat(sat, i, "columns 7-9")
        rec = list(range(i + 1, j))
        while rec and not self.lines[rec[-1]].strip():
            rec.pop()
        if message in COUNTED_MESSAGES.get(system, ()):
            self.unused[f"EPH {system} {message}"] += 1
            self._count(system, sat, i, rec, j > last)
        elif message in READ_MESSAGES.get(system, ()):
            self._ephemeris(system, sat, message, i, rec, j > last)
        else:
            self.unused[f"EPH {system} {message}"] += 1

    def _count(self, system: str, sat: str, i: int, rec: list[int], at_end: bool) -> None:
        """Count an SBAS or NavIC record (as RINEX 3 does), refusing one cut by the file's end."""
        need = SKIPPED_LINES[system]
        if len(rec) < need and at_end:
            raise self.truncated(sat, len(rec), need, rec[-1] if rec else i)
        self.skipped[system] = self.skipped.get(system, 0) + 1

    def _ephemeris(
        self, system: str, sat: str, message: str, i: int, rec: list[int], at_end: bool
    ) -> None:
        """Read an ephemeris record of a legacy message (header on line index ``i``)."""
        fewest, most = _LINES.get(system, (KEPLER_LINES, KEPLER_LINES))
        if len(rec) < fewest and at_end:
            raise self.truncated(sat, len(rec), fewest, rec[-1] if rec else i)
        if not fewest <= len(rec) <= most:
            want = f"{fewest}" if fewest == most else f"{fewest} or {most}"
            self.damaged.append(
                (i, sat, f"{len(rec)} lines after the record header, {message} records have {want}")
            )
            return
        found = self.lines[rec[0]][:3].replace(" ", "0")
        if found != sat:
            raise self.error(
                f"the record header names {sat} but the record's first line holds "
                f"{found!r} in columns 1-3; expected the same satellite",
                rec[0],
            )
        if system == "R":
            self.add_glonass(sat, rec[:GLONASS_LINES])
        else:
            self.add_kepler(system, sat, rec)


def unused_note(unused: Counter[str] | dict[str, int]) -> str:
    """One line counting the RINEX 4 records skipped, per type (empty when none)."""
    if not unused:
        return ""
    n = sum(unused.values())
    kinds = ", ".join(f"{k} {c}" for k, c in sorted(unused.items(), key=lambda kc: -kc[1]))
    return (
        f"{n} RINEX 4 navigation record(s) skipped, not used by psdbound (per type: {kinds}); "
        "the legacy ephemerides (GPS/QZSS LNAV, Galileo INAV/FNAV, BeiDou D1/D2, GLONASS "
        "FDMA) are read"
    )
