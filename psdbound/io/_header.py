"""RINEX observation header parsing (versions 2.1x, 3.0x and 4.00-4.02), strict.

Every record psdbound uses is checked against the format: the observation
type lists are read slot by slot (a blank code inside the declared count,
a count that does not match the codes listed, an invalid or repeated code
are errors naming the line), numbers must be finite, the time system must
be known. Records that only inform (``INTERVAL``, ``APPROX POSITION XYZ``)
are checked too, but a bad value there is reported as a warning and not
used: the sampling interval is taken from the epochs.

RINEX 4.00-4.02 observation files have the RINEX 3.05 layout; their header
may hold new records (``DOI``, ``LICENSE OF USE``, ``STATION INFORMATION``)
that psdbound passes over. A record of a type no RINEX version defines is
skipped and counted in one warning (:mod:`psdbound.io._header_records`).
A version from 4.03 on is read with the 4.02 layout, with a warning; a
version before 2 or from 5 on is refused.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from psdbound.errors import InputError, NoDataError
from psdbound.io._header_records import (
    SYSTEM_LETTERS,
    TIME_SYSTEMS,
    HeaderRecords,
    TypeLists,
    parse_float,
)


@dataclass(frozen=True)
class ObsHeader:
    """What psdbound uses from a RINEX observation header.

    Attributes
    ----------
    version : float
        RINEX version, e.g. 2.11 or 3.04.
    file_system : str
        Satellite system letter of the file (``M`` for mixed).
    marker_name, receiver_type, antenna_type : str
        Station and hardware identification.
    approx_position_m : ndarray of shape (3,) or None
        Approximate marker position, ECEF metres (None when absent, zero,
        or not near the Earth's surface).
    antenna_delta_hen_m : ndarray of shape (3,)
        Antenna height, east, north eccentricities, metres.
    interval_s : float or None
        Nominal sampling interval in seconds (``INTERVAL`` record; None when
        absent, zero or not a positive number). The interval psdbound uses
        comes from the epochs (:attr:`Observations.interval_s`).
    time_system : str
        Time system of the epochs (``GPS``, ``GAL``, ``GLO``, ``UTC``...).
    obs_types : dict of str to tuple of str
        Observation codes per system letter, in file order.
    glonass_channels : dict of str to int
        GLONASS frequency channel per slot (``R01`` -> 1).
    leap_seconds : int or None
        ``LEAP SECONDS`` record, when present.
    n_lines : int
        Number of header lines including ``END OF HEADER``.
    first_obs, last_obs : tuple or None
        ``TIME OF FIRST OBS`` / ``TIME OF LAST OBS`` as (year, month, day,
        hour, minute, second) in the file's time system, when present.
    notes : tuple of str
        Problems found in informative records (values not used); the reader
        reports them as warnings.
    type_lines : dict of str to int
        Header line (1-based) of each system's observation-type list.
    """

    version: float
    file_system: str
    marker_name: str
    receiver_type: str
    antenna_type: str
    approx_position_m: np.ndarray | None
    antenna_delta_hen_m: np.ndarray
    interval_s: float | None
    time_system: str
    obs_types: dict[str, tuple[str, ...]]
    glonass_channels: dict[str, int] = field(default_factory=dict)
    leap_seconds: int | None = None
    n_lines: int = 0
    first_obs: tuple | None = None
    last_obs: tuple | None = None
    notes: tuple[str, ...] = ()
    type_lines: dict[str, int] = field(default_factory=dict)


_TYPE_NAMES = {
    "N": "a GPS navigation file",
    "G": "a GLONASS navigation file",
    "H": "a GEO/SBAS navigation file",
    "M": "a meteorological file",
    "C": "a clock file",
}

#: Name of each system letter.
SYSTEM_NAMES = {
    "G": "GPS",
    "E": "Galileo",
    "R": "GLONASS",
    "C": "BeiDou",
    "J": "QZSS",
    "S": "SBAS",
    "I": "NavIC",
}
#: The RINEX observation versions read, for messages.
SUPPORTED_VERSIONS = "2.1x, 3.0x and 4.00-4.02"
#: The newest RINEX version whose layout the reader knows.
NEWEST_VERSION = 4.02


def _first_line(text: bytes) -> str:
    """Line 1 of the file as text."""
    first = text[: text.find(b"\n")] if b"\n" in text else text
    return first.decode("ascii", "replace")


def _check_kind(first_s: str, path: Path) -> None:
    """Refuse anything but a RINEX observation file, saying what the file is."""
    if first_s.startswith(("#a", "#b", "#c", "#d")):
        raise InputError("this is an SP3 orbit file, expected a RINEX observation file", path=path)
    if "RINEX VERSION / TYPE" not in first_s:
        raise InputError(
            "not a RINEX file: line 1 should end with 'RINEX VERSION / TYPE', "
            f"found {first_s[:60].strip()!r}",
            path=path,
            line=1,
        )
    ftype = first_s[20:21].upper()
    if ftype != "O":
        what = _TYPE_NAMES.get(ftype, f"a RINEX file of type {ftype!r}")
        if "NAV" in first_s[20:60].upper():
            what = "a navigation file"
        raise InputError(
            f"this is {what} (RINEX VERSION / TYPE says {first_s[20:40].strip()!r}); "
            "expected an observation file",
            path=path,
            line=1,
        )


def _version(first_s: str, path: Path) -> tuple[float, list[str]]:
    """The RINEX version of line 1 and a note when it is newer than the reader knows."""
    try:
        version = parse_float(first_s[:9], "RINEX version")
    except ValueError:
        raise InputError(
            f"bad RINEX version {first_s[:9]!r} in columns 1-9; expected a number such as "
            "3.05 or 4.01",
            path=path,
            line=1,
        ) from None
    if not 2.0 <= version < 5.0:
        raise InputError(
            f"RINEX version {version:g} is not supported ({SUPPORTED_VERSIONS} are); convert "
            "the file to RINEX 3 or 4 (e.g. with gfzrnx) and read it again",
            path=path,
            line=1,
        )
    notes = []
    if version > NEWEST_VERSION + 1e-9:
        notes.append(
            f"line 1: RINEX {version:.2f} is newer than the {NEWEST_VERSION:.2f} this reader "
            f"knows; read with the RINEX {NEWEST_VERSION:.2f} layout (unknown header records "
            "are counted)"
        )
    return version, notes


def _file_system(first_s: str, path: Path) -> str:
    """The satellite system letter of line 1 (column 41; ``M`` mixed, blank GPS)."""
    file_system = first_s[40:41].strip() or "G"
    if file_system not in SYSTEM_LETTERS + "M":
        raise InputError(
            f"unknown satellite system {file_system!r} in RINEX VERSION / TYPE (column 41); "
            f"expected one of {SYSTEM_LETTERS} or M",
            path=path,
            line=1,
        )
    return file_system


def _header_lines(text: bytes, path: Path) -> tuple[list[str], int]:
    """The header's lines (to END OF HEADER) and the byte offset of the first data line."""
    end = text.find(b"END OF HEADER")
    if end < 0:
        raise InputError("header has no 'END OF HEADER' record (truncated file?)", path=path)
    stop = text.find(b"\n", end)
    stop = len(text) if stop < 0 else stop + 1
    lines = text[:stop].decode("ascii", "replace").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines, stop


def parse_header(text: bytes, path: Path) -> tuple[ObsHeader, int]:
    """Parse the header; return it and the byte offset of the first data line."""
    first_s = _first_line(text)
    _check_kind(first_s, path)
    version, notes = _version(first_s, path)
    lines, stop = _header_lines(text, path)
    file_system = _file_system(first_s, path)
    rec = HeaderRecords(version, path)
    for i, ln in enumerate(lines, start=1):
        rec.read(ln, i)
    types, type_lines = _obs_types(rec.type_lists, version, file_system, path, len(lines))
    time_system = _time_system(rec.time_system, file_system, lines, path)
    header = ObsHeader(
        version=version,
        file_system=file_system,
        marker_name=rec.marker,
        receiver_type=rec.receiver,
        antenna_type=rec.antenna,
        approx_position_m=rec.approx,
        antenna_delta_hen_m=rec.delta,
        interval_s=rec.interval,
        time_system=time_system,
        obs_types=types,
        glonass_channels=rec.glo,
        leap_seconds=rec.leap,
        n_lines=len(lines),
        first_obs=rec.first_obs,
        last_obs=rec.last_obs,
        notes=tuple(notes + rec.notes + rec.unknown_notes()),
        type_lines=type_lines,
    )
    return header, stop


def _obs_types(
    type_lists: TypeLists, version: float, file_system: str, path: Path, n_lines: int
) -> tuple[dict[str, tuple[str, ...]], dict[str, int]]:
    """Observation codes per system and the header line of each list."""
    types_raw = type_lists.result(path, n_lines)
    if version < 3:
        if not types_raw:
            raise InputError("header has no '# / TYPES OF OBSERV' record", path=path)
        systems = "GRES" if file_system == "M" else file_system
        types = {s: tuple(types_raw["*"]) for s in systems}
        return types, {s: type_lists.first_line["*"] for s in systems}
    if not types_raw:
        raise InputError("header has no 'SYS / # / OBS TYPES' record", path=path)
    return {s: tuple(v) for s, v in types_raw.items()}, dict(type_lists.first_line)


def _time_system(time_system: str, file_system: str, lines: list[str], path: Path) -> str:
    """The epochs' time system: TIME OF FIRST OBS's, else the file system's own."""
    if not time_system:
        return {"R": "GLO", "E": "GAL", "C": "BDT", "J": "QZS", "I": "IRN"}.get(file_system, "GPS")
    if time_system not in TIME_SYSTEMS:
        line = next(k for k, ln in enumerate(lines, 1) if ln[60:].strip() == "TIME OF FIRST OBS")
        raise InputError(
            f"unknown time system {time_system!r} in TIME OF FIRST OBS (columns 49-51); expected "
            f"one of {', '.join(TIME_SYSTEMS)}",
            path=path,
            line=line,
        )
    return time_system


def system_list(systems) -> str:
    """``GPS (G), Galileo (E)`` for system letters (sorted as RINEX lists them)."""
    order = sorted(systems, key=lambda s: SYSTEM_LETTERS.find(s) % 99)
    return ", ".join(f"{SYSTEM_NAMES.get(s, s)} ({s})" for s in order)


def missing_systems(path: Path, missing, held, where: str) -> NoDataError:
    """The error for requested systems a file has no observations of.

    ``held``: the systems the file does hold, ``where``: where they were
    found (the header's observation types, the observed satellites).
    """
    want = system_list(missing)
    if not held:
        return NoDataError(f"no {want} observations: the file holds none of any system", path=path)
    first = sorted(held, key=lambda s: SYSTEM_LETTERS.find(s) % 99)[0]
    return NoDataError(
        f"no {want} observations: the file holds {system_list(held)} only ({where}); choose "
        f"one of those systems (--system {first}) or give a file with {want} observations",
        path=path,
    )
