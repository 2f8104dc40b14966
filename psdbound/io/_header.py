"""RINEX observation header parsing (versions 2.1x and 3.0x), strict.

Every record psdbound uses is checked against the format: the observation
type lists are read slot by slot (a blank code inside the declared count,
a count that does not match the codes listed, an invalid or repeated code
are errors naming the line), numbers must be finite, the time system must
be known. Records that only inform (``INTERVAL``, ``APPROX POSITION XYZ``)
are checked too, but a bad value there is reported as a warning and not
used: the sampling interval is taken from the epochs.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from psdbound.errors import InputError, NoDataError


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

#: Satellite system letters of RINEX 3 (and RINEX 2 observation files).
SYSTEM_LETTERS = "GRECJSI"
#: Name of each system letter.
SYSTEM_NAMES = {"G": "GPS", "E": "Galileo", "R": "GLONASS", "C": "BeiDou", "J": "QZSS",
                "S": "SBAS", "I": "NavIC"}  # fmt: skip
#: Time systems an observation file may use.
TIME_SYSTEMS = ("GPS", "GLO", "GAL", "BDT", "QZS", "IRN", "UTC")
_V3_CODE = re.compile(r"[CLDSX][1-9][A-Z]")
_V3_IONO = re.compile(r"I[1-9][A-Z ]")  # RINEX 3.01 ionosphere phase delay
_V2_CODE = re.compile(r"[A-Z][0-9A-Z]")
_V3_PER_LINE, _V2_PER_LINE = 13, 9


def _float(text: str, what: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise ValueError(f"{what} {text.strip()!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} {text.strip()!r} is not a finite number")
    return x


def _int(text: str, what: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"{what} {text.strip()!r} is not an integer") from None


def _time_record(body: str) -> tuple[tuple, str]:
    """(year, month, day, hour, minute, second) and the time system of a TIME OF ... record."""
    date = tuple(_int(body[k : k + 6], "date field") for k in (0, 6, 12, 18, 24)) + (
        _float(body[30:43], "seconds"),
    )
    return date, body[48:51].strip()


class _TypeLists:
    """Observation-type records read slot by slot, checked against the declared counts."""

    def __init__(self, version: float) -> None:
        self.v3 = version >= 3
        self.types: dict[str, list[str]] = {}
        self.count: dict[str, int] = {}
        self.first_line: dict[str, int] = {}
        self.cur = ""

    def add(self, body: str, line: int) -> None:
        if self.v3:
            head, slot0, per, width, sys_ = body[:6], 7, _V3_PER_LINE, 4, body[0]
        else:
            head, slot0, per, width, sys_ = body[:6], 10, _V2_PER_LINE, 6, "*"
        if head.strip():
            if self.v3:
                if sys_ not in SYSTEM_LETTERS:
                    raise ValueError(
                        f"unknown satellite system {sys_!r} in column 1; expected one of "
                        f"{', '.join(SYSTEM_LETTERS)}"
                    )
                n = _int(body[3:6], "the number of observation types")
            else:
                n = _int(body[:6], "the number of observation types")
            if sys_ in self.types:
                raise ValueError(
                    f"the observation types of {'system ' + sys_ if self.v3 else 'the file'} "
                    f"are declared twice (first on line {self.first_line[sys_]})"
                )
            if not 1 <= n <= 999:
                raise ValueError(f"{n} observation types declared; expected 1 to 999")
            self.cur = sys_
            self.types[sys_], self.count[sys_], self.first_line[sys_] = [], n, line
        elif not self.cur or len(self.types[self.cur]) >= self.count[self.cur]:
            what = f"system {self.cur}" if self.v3 and self.cur else "the file"
            raise ValueError(
                "continuation line without a declaration to continue"
                + (f" ({what} already has its {self.count[self.cur]} types)" if self.cur else "")
            )
        have = self.types[self.cur]
        before = len(have)
        n_here = min(per, self.count[self.cur] - before)
        for k in range(per):
            a = slot0 + width * k
            code = body[a : a + (3 if self.v3 else 2)]
            if k >= n_here:
                if body[a - (1 if self.v3 else 4) : a + width].strip():
                    raise ValueError(
                        f"more observation types than the {self.count[self.cur]} declared "
                        f"(extra code {body[a : a + width].strip()!r} in columns {a + 1}-"
                        f"{a + len(code)})"
                    )
                continue
            sep = body[a - 1 : a] if self.v3 else body[a - 4 : a]
            if sep.strip():
                raise ValueError(
                    f"observation code {k + 1 + before} is not in its columns "
                    f"{a + 1}-{a + len(code)} (found {body[a - len(sep) : a + len(code)]!r})"
                )
            if not code.strip():
                raise ValueError(
                    f"observation code {k + 1 + before} of {self.count[self.cur]} is blank "
                    f"(columns {a + 1}-{a + len(code)}): the type list is damaged and every "
                    "later column would be misread"
                )
            ok = (_V3_CODE.fullmatch(code) or _V3_IONO.fullmatch(code)) if self.v3 else (
                _V2_CODE.fullmatch(code)
            )  # fmt: skip
            if not ok:
                raise ValueError(
                    f"{code!r} in columns {a + 1}-{a + len(code)} is not an observation code"
                )
            if code in have:
                raise ValueError(f"observation code {code} is listed twice")
            have.append(code)

    def result(self, path: Path, n_lines: int) -> dict[str, list[str]]:
        for s, codes in self.types.items():
            if len(codes) != self.count[s]:
                what = f"system {s}" if self.v3 else "the file"
                raise InputError(
                    f"the observation types of {what} declare {self.count[s]} codes but list "
                    f"{len(codes)} (a line of the list is missing or damaged)",
                    path=path,
                    line=self.first_line[s],
                )
        return self.types


def parse_header(text: bytes, path: Path) -> tuple[ObsHeader, int]:
    """Parse the header; return it and the byte offset of the first data line."""
    end = text.find(b"END OF HEADER")
    first = text[: text.find(b"\n")] if b"\n" in text else text
    first_s = first.decode("ascii", "replace")
    if first_s.startswith(("#a", "#b", "#c", "#d")):
        raise InputError("this is an SP3 orbit file, expected a RINEX observation file", path=path)
    if "RINEX VERSION / TYPE" not in first_s:
        raise InputError(
            "not a RINEX file: line 1 should end with 'RINEX VERSION / TYPE', "
            f"found {first_s[:60].strip()!r}",
            path=path,
            line=1,
        )
    try:
        version = _float(first_s[:9], "RINEX version")
    except ValueError:
        raise InputError(f"bad RINEX version {first_s[:9]!r}", path=path, line=1) from None
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
    if not 2.0 <= version < 4.0:
        raise InputError(
            f"RINEX version {version} is not supported (2.1x and 3.0x are)", path=path, line=1
        )
    if end < 0:
        raise InputError("header has no 'END OF HEADER' record (truncated file?)", path=path)
    stop = text.find(b"\n", end)
    stop = len(text) if stop < 0 else stop + 1
    lines = text[:stop].decode("ascii", "replace").split("\n")
    if lines and lines[-1] == "":
        lines.pop()

    marker = receiver = antenna = ""
    approx = None
    delta = np.zeros(3)
    interval = None
    time_system = ""
    leap = None
    first_obs = last_obs = None
    notes: list[str] = []
    glo: dict[str, int] = {}
    type_lists = _TypeLists(version)
    file_system = first_s[40:41].strip() or "G"
    if file_system not in SYSTEM_LETTERS + "M":
        raise InputError(
            f"unknown satellite system {file_system!r} in RINEX VERSION / TYPE (column 41); "
            f"expected one of {SYSTEM_LETTERS} or M",
            path=path,
            line=1,
        )

    for i, ln in enumerate(lines, start=1):
        label = ln[60:].strip()
        body = ln[:60]
        try:
            if label == "MARKER NAME":
                marker = body.strip()
            elif label == "REC # / TYPE / VERS":
                receiver = body[20:40].strip()
            elif label == "ANT # / TYPE":
                antenna = body[20:40].strip()
            elif label == "APPROX POSITION XYZ":
                xyz = np.array([_float(body[k : k + 14], "coordinate") for k in (0, 14, 28)])
                r = float(np.linalg.norm(xyz))
                approx = None if not np.any(xyz) else xyz
                if approx is not None and not 6.2e6 <= r <= 6.5e6:
                    notes.append(
                        f"line {i}: APPROX POSITION XYZ is {r / 1000:.6g} km from the Earth's "
                        "centre, not near its surface; ignored"
                    )
                    approx = None
            elif label == "ANTENNA: DELTA H/E/N":
                delta = np.array([_float(body[k : k + 14], "eccentricity") for k in (0, 14, 28)])
                if np.any(np.abs(delta) > 1000.0):
                    raise ValueError(
                        f"antenna eccentricities {delta.tolist()} m are not plausible (at most "
                        "1000 m)"
                    )
            elif label == "INTERVAL":
                try:
                    value = _float(body[:10], "INTERVAL")
                    if value < 0:
                        raise ValueError(f"INTERVAL {value:g} s is negative")
                    interval = value or None
                except ValueError as exc:
                    notes.append(f"line {i}: {exc}; the interval is taken from the epochs")
            elif label == "TIME OF FIRST OBS":
                first_obs, time_system = _time_record(body)
            elif label == "TIME OF LAST OBS":
                last_obs, _ = _time_record(body)
            elif label == "LEAP SECONDS":
                leap = _int(body[:6], "leap seconds")
            elif label in ("# / TYPES OF OBSERV", "SYS / # / OBS TYPES"):
                if (label == "SYS / # / OBS TYPES") != (version >= 3):
                    raise ValueError(f"this record does not belong in a RINEX {version:g} header")
                type_lists.add(body, i)
            elif label == "GLONASS SLOT / FRQ #":
                parts = body[4:].split()
                if len(parts) % 2:
                    raise ValueError("expected pairs of slot and channel")
                for k in range(0, len(parts), 2):
                    slot, ch = parts[k], _int(parts[k + 1], "channel")
                    if not re.fullmatch(r"R\d\d", slot) or not -7 <= ch <= 6:
                        raise ValueError(
                            f"{slot} {ch}: expected a slot such as R01 and a channel from -7 to 6"
                        )
                    glo[slot] = ch
        except ValueError as exc:
            raise InputError(
                f"cannot parse header record {label!r}: {exc}", path=path, line=i
            ) from None

    types_raw = type_lists.result(path, len(lines))
    if version < 3:
        if not types_raw:
            raise InputError("header has no '# / TYPES OF OBSERV' record", path=path)
        systems = "GRES" if file_system == "M" else file_system
        types = {s: tuple(types_raw["*"]) for s in systems}
        type_lines = {s: type_lists.first_line["*"] for s in systems}
    else:
        if not types_raw:
            raise InputError("header has no 'SYS / # / OBS TYPES' record", path=path)
        types = {s: tuple(v) for s, v in types_raw.items()}
        type_lines = dict(type_lists.first_line)
    if not time_system:
        time_system = {"R": "GLO", "E": "GAL", "C": "BDT", "J": "QZS", "I": "IRN"}.get(
            file_system, "GPS"
        )
    elif time_system not in TIME_SYSTEMS:
        line = next(k for k, ln in enumerate(lines, 1) if ln[60:].strip() == "TIME OF FIRST OBS")
        raise InputError(
            f"unknown time system {time_system!r} in TIME OF FIRST OBS (columns 49-51); expected "
            f"one of {', '.join(TIME_SYSTEMS)}",
            path=path,
            line=line,
        )
    header = ObsHeader(
        version=version,
        file_system=file_system,
        marker_name=marker,
        receiver_type=receiver,
        antenna_type=antenna,
        approx_position_m=approx,
        antenna_delta_hen_m=delta,
        interval_s=interval,
        time_system=time_system,
        obs_types=types,
        glonass_channels=glo,
        leap_seconds=leap,
        n_lines=len(lines),
        first_obs=first_obs,
        last_obs=last_obs,
        notes=tuple(notes),
        type_lines=type_lines,
    )
    return header, stop


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
        return NoDataError(f"no {want} observations: the file holds none of any system",
                           path=path)  # fmt: skip
    first = sorted(held, key=lambda s: SYSTEM_LETTERS.find(s) % 99)[0]
    return NoDataError(
        f"no {want} observations: the file holds {system_list(held)} only ({where}); choose "
        f"one of those systems (--system {first}) or give a file with {want} observations",
        path=path,
    )
