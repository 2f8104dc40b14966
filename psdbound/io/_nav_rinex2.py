"""RINEX 2 navigation records: GPS Keplerian and GLONASS records; GEO/SBAS records counted.

Layout (RINEX 2.11, table A4): the epoch line holds the PRN in columns 1-2,
the time of clock ``yy mm dd hh mm ss.s`` in columns 3-22 and three fields
from column 23; the orbit lines hold four fields from column 4. A GPS record
has eight lines; GLONASS (file type ``G``, read by
:mod:`psdbound.io._nav_glonass`) and GEO/SBAS (``H``, only counted) records
have four.
"""

from __future__ import annotations

from psdbound.io._nav_glonass import GlonassParser
from psdbound.io._nav_records import KEPLER_LINES, Epoch

__all__ = ["Rinex2Parser"]


class Rinex2Parser(GlonassParser):
    """Parser of the body of a RINEX 2 navigation file (one system per file)."""

    FIRST_COLUMN = 22
    CONTINUATION_COLUMN = 3
    EPOCH_COLUMNS = "columns 3-22"
    TWO_DIGIT_YEAR = True

    def epoch(self, line0: str) -> Epoch:
        """Calendar fields of the epoch line (two-digit year as written)."""
        return (
            int(line0[2:5]),
            int(line0[5:8]),
            int(line0[8:11]),
            int(line0[11:14]),
            int(line0[14:17]),
            float(line0[17:22]),
        )

    def parse(self, start: int, system: str = "G") -> None:
        """Read every record from line index ``start`` on; ``system`` from the file type.

        ``"G"`` (GPS, file type N) and ``"R"`` (GLONASS, file type G)
        records are parsed; SBAS (``"S"``, file type H) records are counted.
        """
        lines = self.lines
        i = start
        last = self.last_line(start)
        need = KEPLER_LINES if system == "G" else 4
        while i <= last:
            if not lines[i].strip():
                i += 1
                continue
            prn_text = lines[i][:2]
            if not prn_text.strip().isdigit():
                raise self.error(
                    f"cannot read the PRN {prn_text!r} in columns 1-2; expected the first "
                    "line of a RINEX 2 navigation record",
                    i,
                )
            sat = f"{system}{int(prn_text):02d}"
            self.check_sat(sat, i, "columns 1-2")
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
            elif system == "R":
                self.add_glonass(sat, rec)
            else:
                self.skipped[system] = self.skipped.get(system, 0) + 1
            i += need
