"""RINEX observation header records: the observation-type lists and every other record.

:class:`HeaderRecords` reads the header line by line: the records psdbound
uses are checked and kept, the records of the RINEX 2.11, 3.05 and 4.00-4.02
layouts that it does not use are passed over (:data:`KNOWN_LABELS`), and any
other record is skipped and counted, so that the reader can say so in one
warning (:meth:`HeaderRecords.unknown_notes`) instead of ignoring it
silently. :class:`TypeLists` reads the observation-type lists slot by slot.
"""

from __future__ import annotations

import math
import re
from collections import Counter
from pathlib import Path

import numpy as np

from psdbound.errors import InputError

__all__ = [
    "KNOWN_LABELS",
    "SYSTEM_LETTERS",
    "TIME_SYSTEMS",
    "HeaderRecords",
    "TypeLists",
    "parse_float",
    "parse_int",
    "three_numbers",
    "time_record",
]

#: Satellite system letters of RINEX 3 (and RINEX 2 observation files).
SYSTEM_LETTERS = "GRECJSI"
_V3_CODE = re.compile(r"[CLDSX][1-9][A-Z]")
_V3_IONO = re.compile(r"I[1-9][A-Z ]")  # RINEX 3.01 ionosphere phase delay
_V2_CODE = re.compile(r"[A-Z][0-9A-Z]")
_V3_PER_LINE, _V2_PER_LINE = 13, 9
_GLONASS_PAIR = re.compile(r"(R\d\d) *([+-]?\d{1,2})(?!\d)")
#: Time systems an observation file may use.
TIME_SYSTEMS = ("GPS", "GLO", "GAL", "BDT", "QZS", "IRN", "UTC")


def parse_float(text: str, what: str) -> float:
    """A finite number; ValueError naming ``what`` otherwise."""
    try:
        x = float(text)
    except ValueError:
        raise ValueError(f"{what} {text.strip()!r} is not a number") from None
    if not math.isfinite(x):
        raise ValueError(f"{what} {text.strip()!r} is not a finite number")
    return x


def parse_int(text: str, what: str) -> int:
    """An integer; ValueError naming ``what`` otherwise."""
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"{what} {text.strip()!r} is not an integer") from None


def time_record(body: str) -> tuple[tuple, str, bool]:
    """Date, time system and shift of a TIME OF ... record.

    The fields are read in their columns (``5I6, F13.7, 5X, A3``). A record whose
    fields are shifted from them (some writers use other widths) is read as the
    numbers and the system separated by blanks when that gives a whole record.

    Returns
    -------
    tuple
        (year, month, day, hour, minute, second), the time system (``""`` if
        blank) and whether the record was read from blank-separated fields.
    """
    try:
        date, system = _fixed_time_record(body)
    except ValueError:
        shifted = _blank_separated_time(body)
        if shifted is None:
            raise
        return *shifted, True
    if system and system not in TIME_SYSTEMS:
        shifted = _blank_separated_time(body)
        if shifted is not None:
            return *shifted, True
    return date, system, False


def _fixed_time_record(body: str) -> tuple[tuple, str]:
    date = tuple(parse_int(body[k : k + 6], "date field") for k in (0, 6, 12, 18, 24)) + (
        parse_float(body[30:43], "seconds"),
    )
    return date, body[48:51].strip()


def _blank_separated_time(body: str) -> tuple[tuple, str] | None:
    """Five integers, the seconds and an optional known time system, or None."""
    tokens = body.split()
    if len(tokens) not in (6, 7) or (len(tokens) == 7 and tokens[6] not in TIME_SYSTEMS):
        return None
    try:
        date = tuple(int(t) for t in tokens[:5]) + (parse_float(tokens[5], "seconds"),)
    except ValueError:
        return None
    return date, tokens[6] if len(tokens) == 7 else ""


def three_numbers(body: str, what: str) -> tuple[np.ndarray, bool]:
    """Three ``F14.4`` fields of a header record, and whether they were shifted.

    Read in their columns; when that fails, as three blank-separated numbers
    (some writers use 15-wide fields), and the second value says so.
    """
    try:
        return np.array([parse_float(body[k : k + 14], what) for k in (0, 14, 28)]), False
    except ValueError:
        tokens = body.split()
        if len(tokens) != 3:
            raise
        return np.array([parse_float(t, what) for t in tokens]), True


class TypeLists:
    """Observation-type records read slot by slot, checked against the declared counts."""

    def __init__(self, version: float) -> None:
        self.v3 = version >= 3
        self.types: dict[str, list[str]] = {}
        self.count: dict[str, int] = {}
        self.first_line: dict[str, int] = {}
        self.cur = ""

    def add(self, body: str, line: int) -> None:
        """Read one type-list line (a declaration or its continuation)."""
        slot0, per, width = (7, _V3_PER_LINE, 4) if self.v3 else (10, _V2_PER_LINE, 6)
        if body[:6].strip():
            self._declare(body, line)
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
            if k < n_here:
                have.append(self._code(body, a, k + 1 + before))
            else:
                self._no_extra(body, a, width)

    def _declare(self, body: str, line: int) -> None:
        """Start a system's list (RINEX 3) or the file's list (RINEX 2)."""
        if self.v3:
            sys_ = body[0]
            if sys_ not in SYSTEM_LETTERS:
                raise ValueError(
                    f"unknown satellite system {sys_!r} in column 1; expected one of "
                    f"{', '.join(SYSTEM_LETTERS)}"
                )
            n = parse_int(body[3:6], "the number of observation types")
        else:
            sys_, n = "*", parse_int(body[:6], "the number of observation types")
        if sys_ in self.types:
            raise ValueError(
                f"the observation types of {'system ' + sys_ if self.v3 else 'the file'} "
                f"are declared twice (first on line {self.first_line[sys_]})"
            )
        if not 1 <= n <= 999:
            raise ValueError(f"{n} observation types declared; expected 1 to 999")
        self.cur = sys_
        self.types[sys_], self.count[sys_], self.first_line[sys_] = [], n, line

    def _no_extra(self, body: str, a: int, width: int) -> None:
        """Refuse a code in a slot beyond the declared count."""
        size = 3 if self.v3 else 2
        if body[a - (1 if self.v3 else 4) : a + width].strip():
            raise ValueError(
                f"more observation types than the {self.count[self.cur]} declared "
                f"(extra code {body[a : a + width].strip()!r} in columns {a + 1}-"
                f"{a + len(body[a : a + size])})"
            )

    def _code(self, body: str, a: int, number: int) -> str:
        """The code in the slot starting at column ``a`` (0-based), checked."""
        code = body[a : a + (3 if self.v3 else 2)]
        sep = body[a - 1 : a] if self.v3 else body[a - 4 : a]
        cols = f"{a + 1}-{a + len(code)}"
        if sep.strip():
            raise ValueError(
                f"observation code {number} is not in its columns {cols} (found "
                f"{body[a - len(sep) : a + len(code)]!r})"
            )
        if not code.strip():
            raise ValueError(
                f"observation code {number} of {self.count[self.cur]} is blank (columns "
                f"{cols}): the type list is damaged and every later column would be misread"
            )
        ok = (
            (_V3_CODE.fullmatch(code) or _V3_IONO.fullmatch(code))
            if self.v3
            else (_V2_CODE.fullmatch(code))
        )
        if not ok:
            raise ValueError(f"{code!r} in columns {cols} is not an observation code")
        if code in self.types[self.cur]:
            raise ValueError(f"observation code {code} is listed twice")
        return code

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


#: Labels (columns 61-80) of the observation header records of RINEX 2.11, 3.05 and
#: 4.00-4.02 that the reader knows: those it uses and those it passes over.
KNOWN_LABELS = frozenset(
    {
        # RINEX 2.11
        "RINEX VERSION / TYPE",
        "PGM / RUN BY / DATE",
        "COMMENT",
        "MARKER NAME",
        "MARKER NUMBER",
        "OBSERVER / AGENCY",
        "REC # / TYPE / VERS",
        "ANT # / TYPE",
        "APPROX POSITION XYZ",
        "ANTENNA: DELTA H/E/N",
        "WAVELENGTH FACT L1/2",
        "# / TYPES OF OBSERV",
        "INTERVAL",
        "TIME OF FIRST OBS",
        "TIME OF LAST OBS",
        "RCV CLOCK OFFS APPL",
        "LEAP SECONDS",
        "# OF SATELLITES",
        "PRN / # OF OBS",
        "END OF HEADER",
        # RINEX 3.0x
        "MARKER TYPE",
        "ANTENNA: DELTA X/Y/Z",
        "ANTENNA: PHASECENTER",
        "ANTENNA: B.SIGHT XYZ",
        "ANTENNA: ZERODIR AZI",
        "ANTENNA: ZERODIR XYZ",
        "CENTER OF MASS: XYZ",
        "SYS / # / OBS TYPES",
        "SIGNAL STRENGTH UNIT",
        "SYS / DCBS APPLIED",
        "SYS / PCVS APPLIED",
        "SYS / SCALE FACTOR",
        "SYS / PHASE SHIFT",
        "GLONASS SLOT / FRQ #",
        "GLONASS COD/PHS/BIS",
        # RINEX 4.0x
        "DOI",
        "LICENSE OF USE",
        "STATION INFORMATION",
    }
)


class HeaderRecords:
    """The header records of one observation file, read line by line.

    Attributes hold what psdbound uses (marker, receiver, antenna, positions,
    interval, time records, leap seconds, GLONASS channels, the type lists);
    ``notes`` the problems of informative records (values not used).
    """

    def __init__(self, version: float, path: Path) -> None:
        self.version, self.path = version, path
        self.marker = self.receiver = self.antenna = self.time_system = ""
        self.approx: np.ndarray | None = None
        self.delta = np.zeros(3)
        self.interval: float | None = None
        self.leap: int | None = None
        self.first_obs: tuple | None = None
        self.last_obs: tuple | None = None
        self.notes: list[str] = []
        self.glo: dict[str, int] = {}
        self.type_lists = TypeLists(version)
        self.unknown: Counter[str] = Counter()
        self.first_unknown = 0
        self._handlers = {
            "MARKER NAME": self._marker,
            "REC # / TYPE / VERS": self._receiver,
            "ANT # / TYPE": self._antenna,
            "APPROX POSITION XYZ": self._approx,
            "ANTENNA: DELTA H/E/N": self._delta,
            "INTERVAL": self._interval,
            "TIME OF FIRST OBS": self._first,
            "TIME OF LAST OBS": self._last,
            "LEAP SECONDS": self._leap,
            "# / TYPES OF OBSERV": self._types,
            "SYS / # / OBS TYPES": self._types,
            "GLONASS SLOT / FRQ #": self._glonass,
        }

    def read(self, ln: str, i: int) -> None:
        """Read header line ``ln`` (1-based line ``i``); InputError naming the line if damaged."""
        label, body = ln[60:].strip(), ln[:60]
        handler = self._handlers.get(label)
        if handler is None:
            if label not in KNOWN_LABELS:
                self.unknown[label] += 1
                self.first_unknown = self.first_unknown or i
            return
        try:
            handler(body, i, label)
        except ValueError as exc:
            raise InputError(
                f"cannot parse header record {label!r}: {exc}", path=self.path, line=i
            ) from None

    def unknown_notes(self) -> list[str]:
        """One note counting the header records of unknown type that were skipped."""
        if not self.unknown:
            return []
        n = sum(self.unknown.values())
        kinds = ", ".join(
            (f"'{k}'" if k else "(no label in columns 61-80)") + (f" x{c}" if c > 1 else "")
            for k, c in self.unknown.most_common()
        )
        return [
            f"line {self.first_unknown}: {n} header record(s) of a type not in RINEX 2.11, "
            f"3.05 or 4.00-4.02 skipped: {kinds} (their content is not used)"
        ]

    def _marker(self, body: str, i: int, label: str) -> None:
        self.marker = body.strip()

    def _receiver(self, body: str, i: int, label: str) -> None:
        self.receiver = body[20:40].strip()

    def _antenna(self, body: str, i: int, label: str) -> None:
        self.antenna = body[20:40].strip()

    def _approx(self, body: str, i: int, label: str) -> None:
        xyz, shifted = three_numbers(body, "coordinate")
        self._note_shifted(shifted, i, label)
        r = float(np.linalg.norm(xyz))
        self.approx = None if not np.any(xyz) else xyz
        if self.approx is not None and not 6.2e6 <= r <= 6.5e6:
            self.notes.append(
                f"line {i}: APPROX POSITION XYZ is {r / 1000:.6g} km from the Earth's "
                "centre, not near its surface; ignored"
            )
            self.approx = None

    def _delta(self, body: str, i: int, label: str) -> None:
        delta, shifted = three_numbers(body, "eccentricity")
        self._note_shifted(shifted, i, label)
        if np.any(np.abs(delta) > 1000.0):
            raise ValueError(
                f"antenna eccentricities {delta.tolist()} m are not plausible (at most 1000 m)"
            )
        self.delta = delta

    def _interval(self, body: str, i: int, label: str) -> None:
        try:
            value = parse_float(body[:10], "INTERVAL")
            if value < 0:
                raise ValueError(f"INTERVAL {value:g} s is negative")
            self.interval = value or None
        except ValueError as exc:
            self.notes.append(f"line {i}: {exc}; the interval is taken from the epochs")

    def _first(self, body: str, i: int, label: str) -> None:
        self.first_obs, self.time_system, shifted = time_record(body)
        self._note_shifted(shifted, i, label)

    def _last(self, body: str, i: int, label: str) -> None:
        self.last_obs, _, shifted = time_record(body)
        self._note_shifted(shifted, i, label)

    def _note_shifted(self, shifted: bool, i: int, label: str) -> None:
        """Say that a record was read from blank-separated fields, not its columns."""
        if shifted:
            self.notes.append(
                f"line {i}: {label} is not in the columns RINEX gives it; its fields were "
                "read as separated by blanks"
            )

    def _leap(self, body: str, i: int, label: str) -> None:
        self.leap = parse_int(body[:6], "leap seconds")

    def _types(self, body: str, i: int, label: str) -> None:
        if (label == "SYS / # / OBS TYPES") != (self.version >= 3):
            raise ValueError(f"this record does not belong in a RINEX {self.version:g} header")
        self.type_lists.add(body, i)

    def _glonass(self, body: str, i: int, label: str) -> None:
        rest = body[4:].strip()
        pairs = _GLONASS_PAIR.findall(rest)
        if _GLONASS_PAIR.sub("", rest).strip():  # some writers leave out the blank after I2
            raise ValueError("expected pairs of slot and channel, such as 'R01  1 R02 -4'")
        for slot, text in pairs:
            ch = parse_int(text, "channel")
            if not -7 <= ch <= 6:
                raise ValueError(
                    f"{slot} {ch}: expected a slot such as R01 and a channel from -7 to 6"
                )
            self.glo[slot] = ch
