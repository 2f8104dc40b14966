"""RINEX observation header parsing (versions 2.1x and 3.0x)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from psdbound.errors import InputError


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
        Approximate marker position, ECEF metres (None when absent or zero).
    antenna_delta_hen_m : ndarray of shape (3,)
        Antenna height, east, north eccentricities, metres.
    interval_s : float or None
        Nominal sampling interval in seconds (``INTERVAL`` record).
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


_TYPE_NAMES = {
    "N": "a GPS navigation file",
    "G": "a GLONASS navigation file",
    "H": "a GEO/SBAS navigation file",
    "M": "a meteorological file",
    "C": "a clock file",
}


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
        version = float(first_s[:9])
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
    obs_types: dict[str, list[str]] = {}
    glo: dict[str, int] = {}
    v2_types: list[str] = []
    v2_count = 0
    cur_sys = ""
    cur_count = 0
    file_system = first_s[40:41].strip() or "G"

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
                xyz = np.array([float(body[k : k + 14]) for k in (0, 14, 28)])
                approx = None if not np.any(xyz) else xyz
            elif label == "ANTENNA: DELTA H/E/N":
                delta = np.array([float(body[k : k + 14]) for k in (0, 14, 28)])
            elif label == "INTERVAL":
                interval = float(body[:10]) or None
            elif label == "TIME OF FIRST OBS":
                time_system = body[48:51].strip()
            elif label == "LEAP SECONDS":
                leap = int(body[:6])
            elif label == "# / TYPES OF OBSERV":
                if body[:6].strip():
                    v2_count = int(body[:6])
                v2_types += body[10:60].split()
            elif label == "SYS / # / OBS TYPES":
                if body[0] != " ":
                    cur_sys = body[0]
                    cur_count = int(body[3:6])
                    obs_types[cur_sys] = []
                obs_types[cur_sys] += body[7:60].split()
                if len(obs_types[cur_sys]) > cur_count:
                    raise ValueError(f"more than {cur_count} types for system {cur_sys}")
            elif label == "GLONASS SLOT / FRQ #":
                parts = body[4:].split()
                for k in range(0, len(parts) - 1, 2):
                    glo[parts[k]] = int(parts[k + 1])
        except ValueError as exc:
            raise InputError(
                f"cannot parse header record {label!r}: {exc}", path=path, line=i
            ) from None

    if version < 3:
        if not v2_types:
            raise InputError("header has no '# / TYPES OF OBSERV' record", path=path)
        if len(v2_types) != v2_count:
            raise InputError(
                f"'# / TYPES OF OBSERV' announces {v2_count} types, lists {len(v2_types)}",
                path=path,
            )
        systems = "GRES" if file_system == "M" else file_system
        types = {s: tuple(v2_types) for s in systems}
    else:
        if not obs_types:
            raise InputError("header has no 'SYS / # / OBS TYPES' record", path=path)
        types = {s: tuple(v) for s, v in obs_types.items()}
    if not time_system:
        time_system = {"R": "GLO", "E": "GAL", "C": "BDT", "J": "QZS"}.get(file_system, "GPS")
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
    )
    return header, stop
