"""Reader for RINEX broadcast navigation files (Keplerian ephemerides).

Supported inputs
----------------
* RINEX 2.x GPS (file type ``N``) and GLONASS (``G``) navigation files.
  GEO/SBAS (``H``) navigation files are read too, but their records are
  only counted (in :attr:`Navigation.skipped`), not parsed.
* RINEX 3.0x navigation files, single-system or mixed. Keplerian records of
  GPS (``G``), Galileo (``E``), BeiDou (``C``) and QZSS (``J``) and the
  state-vector records of GLONASS (``R``) are parsed; SBAS (``S``) and
  NavIC/IRNSS (``I``) records are skipped and counted per system.
* RINEX 4.00-4.02 navigation files (records headed ``> EPH G01 LNAV``): the
  ephemerides of the legacy messages (GPS and QZSS LNAV, Galileo INAV and
  FNAV, BeiDou D1 and D2, GLONASS FDMA) are read into the same records as
  from RINEX 3; SBAS and NavIC ephemerides are counted per system as in
  RINEX 3; the other records (``STO``, ``EOP``, ``ION``, the CNAV/CNV1-3 and
  other modernised messages) are skipped, counted per type in
  :attr:`Navigation.unused` and in one warning. A version from 4.03 on is
  read with the 4.02 layout, with a warning; from 5 on it is refused.

Every epoch is converted to GPS seconds (see :mod:`psdbound.io.timescales`):
GPS, QZSS and Galileo labels are used directly (GST and QZSST are labelled
like GPS time in RINEX), BeiDou labels are BDT and get +14 s. The week number
of each record (GPS week, GST week aligned with GPS, or BDT week + 1356) gives
the full time of ephemeris ``toe_gps_s``; it is moved by whole weeks to the one
nearest to ``toc_gps_s`` so that week-rollover or "week of transmission"
conventions of some writers cannot put it in the wrong week. GLONASS epochs
are UTC labels and are converted with the leap-second table.

Layout: this module is the front (:func:`read_nav` and the header); the
containers are :class:`~psdbound.io.navigation.Navigation`,
:class:`~psdbound.io.kepler.KeplerEphemerides` (propagated by
:mod:`psdbound.io.ephemeris`) and
:class:`~psdbound.io.glonass.GlonassEphemerides` (integrated by
:mod:`psdbound.io.glonass`); the record parsers are in
``psdbound.io._nav_records`` (shared layout), ``psdbound.io._nav_glonass``,
``psdbound.io._nav_rinex2``, ``psdbound.io._nav_rinex3`` and
``psdbound.io._nav_rinex4``.
"""

from __future__ import annotations

import os
from pathlib import Path

from psdbound.common.notices import warn
from psdbound.errors import InputError
from psdbound.io._nav_rinex2 import Rinex2Parser
from psdbound.io._nav_rinex3 import KEPLER_SYSTEMS, SKIPPED_SYSTEMS, Rinex3Parser
from psdbound.io._nav_rinex4 import Rinex4Parser, unused_note
from psdbound.io._source import read_bytes
from psdbound.io.glonass import GlonassEphemerides
from psdbound.io.kepler import KeplerEphemerides
from psdbound.io.navigation import Navigation

#: The newest RINEX navigation version whose layout the reader knows.
NEWEST_VERSION = 4.02

__all__ = [
    "GlonassEphemerides",
    "KeplerEphemerides",
    "Navigation",
    "read_nav",
    "KEPLER_SYSTEMS",
    "SKIPPED_SYSTEMS",
]


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
            "file (RINEX VERSION / TYPE type 'N', e.g. 'NAVIGATION DATA')"
            + ("; observation files go before --nav" if ftype == "O" else ""),
            path=path,
            line=1,
        )
    if not 2.0 <= version < 5.0:
        raise InputError(
            f"RINEX {version:.2f} navigation files are not supported; expected RINEX 2, 3 "
            f"or 4 (up to {NEWEST_VERSION:.2f}) navigation data; convert the file (e.g. with "
            "gfzrnx) and read it again",
            path=path,
            line=1,
        )
    return _end_of_header(path, lines, version, ftype)


def _end_of_header(
    path: Path, lines: list[str], version: float, ftype: str
) -> tuple[float, str, int | None, int]:
    """Find END OF HEADER, reading LEAP SECONDS on the way."""
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
    """Read a RINEX 2, 3 or 4 broadcast navigation file.

    Parameters
    ----------
    path : str or path-like
        Navigation file, plain or compressed (gzip, Z, bz2, zip).

    Returns
    -------
    Navigation
        Keplerian ephemerides per system (GPS, Galileo, BeiDou, QZSS), the
        GLONASS ephemerides and the counts of skipped SBAS/NavIC records.

    Raises
    ------
    InputError
        If the file is not a RINEX 2/3/4 navigation file (e.g. an observation or
        SP3 file), has no END OF HEADER, ends in the middle of a record,
        holds a number that cannot be parsed or a satellite id outside its
        system's range. The message names the file, the 1-based line and,
        where relevant, the satellite and columns.

    Warns
    -----
    PsdboundWarning
        Records with non-finite values, an impossible time of clock,
        elements no GNSS orbit has or (GLONASS) an implausible position or
        frequency number are left out (counted in one warning,
        also in :attr:`Navigation.warnings`); so are RINEX 4 ephemeris
        records whose number of lines does not fit their message. The
        RINEX 4 records not used (``STO``, ``EOP``, ``ION``, modernised
        messages) are counted per type in one warning.

    """
    p = Path(path)
    text = read_bytes(p).decode("latin-1")
    lines = text.split("\n")
    if lines and not lines[-1]:
        lines.pop()  # the newline ending the last line does not start a new one
    version, ftype, leap, end = _header(p, lines)
    parser: Rinex2Parser | Rinex3Parser | Rinex4Parser
    if version < 3.0:
        parser = Rinex2Parser(p, lines)
        parser.parse(end + 1, {"N": "G", "G": "R"}.get(ftype, "S"))
    else:
        parser = Rinex4Parser(p, lines) if version >= 4.0 else Rinex3Parser(p, lines)
        parser.parse(end + 1)
    unused = dict(sorted(parser.unused.items())) if isinstance(parser, Rinex4Parser) else {}
    notes = [_newer_note(version), parser.damage_note(), unused_note(unused)]
    return Navigation(
        path=p,
        version=version,
        leap_seconds=leap,
        ephemerides=parser.build(),
        skipped=dict(sorted(parser.skipped.items())),
        warnings=tuple(warn(n, path=p) for n in notes if n),
        glonass=parser.build_glonass(),
        unused=unused,
    )


def _newer_note(version: float) -> str:
    """Return a note when the file is newer than the newest RINEX version known (or "")."""
    if version <= NEWEST_VERSION + 1e-9:
        return ""
    return (
        f"RINEX {version:.2f} is newer than the {NEWEST_VERSION:.2f} this reader knows; read "
        f"with the RINEX {NEWEST_VERSION:.2f} layout (records of unknown types are counted)"
    )
