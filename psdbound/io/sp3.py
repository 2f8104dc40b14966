"""Reader for SP3-c and SP3-d precise orbit files.

Only the position (``P``) records are used; velocity (``V``) and correlation
(``EP``/``EV``) records are ignored. Positions are converted from km to m,
clocks from microseconds to seconds. Missing values (position 0.000000 or
999999.999999 in any coordinate, clock 999999.999999) become NaN.

The epochs are converted to GPS seconds according to the ``%c`` time-system
field: GPS, GAL and QZS labels are used directly, TAI labels minus 19 s, BDT
labels plus 14 s, UTC labels through the leap-second table and GLO (UTC + 3 h)
likewise. A blank or ``ccc`` field (an unfilled SP3-c template) is taken as
GPS, the SP3 default.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import TAI_MINUS_GPS_S
from psdbound.errors import InputError
from psdbound.io._nav_records import valid_calendar
from psdbound.io._source import read_bytes
from psdbound.io.kepler import PRN_RANGE
from psdbound.io.timescales import calendar_to_gps_s, utc_to_gps_s

__all__ = ["PreciseOrbit", "read_sp3", "merge_precise", "INTERPOLATION_NODES"]

#: Number of consecutive epochs used by the Lagrange interpolation.
INTERPOLATION_NODES = 11
_MISSING_KM = 999999.0
_MISSING_CLOCK_US = 999999.0
_TIME_SYSTEMS = ("GPS", "GAL", "QZS", "TAI", "BDT", "UTC", "GLO")
# a window is refused when one of its node spacings exceeds this times the
# nominal spacing (a data gap inside the window)
_GAP_FACTOR = 1.5


@dataclass(frozen=True, eq=False)
class PreciseOrbit:
    """Satellite positions and clocks from an SP3 file.

    Attributes
    ----------
    path : pathlib.Path
        The file read.
    t_gps_s : ndarray of float64, shape (n_epoch,)
        Epochs, GPS seconds.
    sats : tuple of str
        Satellite ids in header order, e.g. ``('G01', 'E05')``.
    xyz_m : ndarray of float64, shape (n_epoch, n_sat, 3)
        ECEF positions in metres (NaN where missing).
    clock_s : ndarray of float64, shape (n_epoch, n_sat)
        Satellite clock offsets in seconds (NaN where missing).
    time_system : str
        Time system of the file's epoch labels (``'GPS'``, ``'GAL'``,
        ``'UTC'``, ...).

    """

    path: Path
    t_gps_s: NDArray[np.float64]
    sats: tuple[str, ...]
    xyz_m: NDArray[np.float64]
    clock_s: NDArray[np.float64]
    time_system: str

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of the satellites listed in the file."""
        return tuple(sorted(self.sats))

    @property
    def systems(self) -> tuple[str, ...]:
        """Sorted letters of the systems with at least one listed satellite."""
        return tuple(sorted({s[0] for s in self.sats}))

    def positions_ecef_m(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """Interpolated ECEF positions of one satellite.

        A Lagrange polynomial through :data:`INTERPOLATION_NODES` (11)
        consecutive epochs, centred on each time where the data allow (the
        window is shifted inwards near the ends of the file), evaluated with
        :func:`scipy.interpolate.barycentric_interpolate`.

        Parameters
        ----------
        sat : str
            Satellite id such as ``'G05'``.
        t_gps_s : array_like of float
            Times, GPS seconds (scalar or 1-D).

        Returns
        -------
        ndarray of float64, shape (n, 3)
            ECEF coordinates in metres (Earth-fixed frame at each time). NaN
            rows outside the span of the file's epochs, where a node of the
            window is missing or the window spans a data gap, and for a
            satellite not in the file.

        """
        t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
        out = np.full((t.shape[0], 3), np.nan)
        try:
            j = self.sats.index(sat)
        except ValueError:
            return out
        nodes = self.t_gps_s
        n_ep = nodes.shape[0]
        n_nodes = min(INTERPOLATION_NODES, n_ep)
        if n_nodes < 2:
            return out
        inside = (t >= nodes[0]) & (t <= nodes[-1])
        if not np.any(inside):
            return out
        steps = np.diff(nodes)
        nominal = float(np.median(steps))
        ti = t[inside]
        # interval k holds t in [nodes[k], nodes[k+1]); centre the window on it
        k = np.clip(np.searchsorted(nodes, ti, side="right") - 1, 0, n_ep - 2)
        start = np.clip(k - (n_nodes // 2 - 1), 0, n_ep - n_nodes)
        out[inside] = _lagrange(nodes, self.xyz_m[:, j, :], ti, start, n_nodes, nominal)
        return out


def _lagrange(
    nodes: NDArray[np.float64],
    pos: NDArray[np.float64],
    ti: NDArray[np.float64],
    start: NDArray[np.intp],
    n_nodes: int,
    nominal: float,
) -> NDArray[np.float64]:
    """Evaluate the window polynomials; windows starting at ``start`` per time.

    Node times are scaled to units of the nominal step around the window's
    middle node. For windows with the regular pattern (nearly all) the
    Lagrange basis values at each time come from one
    :class:`scipy.interpolate.BarycentricInterpolator` of the identity matrix
    and are applied to each time's window; irregular windows are evaluated
    one by one with :func:`scipy.interpolate.barycentric_interpolate`.
    """
    from scipy.interpolate import BarycentricInterpolator, barycentric_interpolate

    res = np.full((ti.shape[0], 3), np.nan)
    wins, inv = np.unique(start, return_inverse=True)
    take = wins[:, None] + np.arange(n_nodes)  # (n_win, n_nodes)
    xw = nodes[take]
    yw = pos[take]  # (n_win, n_nodes, 3)
    mid = n_nodes // 2
    centre = xw[:, mid]
    pattern = (xw - centre[:, None]) / nominal
    usable = np.isfinite(yw).all(axis=(1, 2)) & np.all(
        np.diff(xw, axis=1) <= _GAP_FACTOR * nominal, axis=1
    )
    ref = np.arange(n_nodes, dtype=np.float64) - mid
    regular = usable & np.all(np.abs(pattern - ref) < 1e-9, axis=1)
    s = (ti - centre[inv]) / nominal
    ids = np.flatnonzero(regular[inv])
    if ids.size:
        # Lagrange basis values L_j(s) of the regular pattern: the interpolant
        # of the identity matrix; the position is then sum_j L_j(s) y_j.
        basis = BarycentricInterpolator(ref, np.eye(n_nodes))(s[ids])  # (n, n_nodes)
        res[ids] = np.einsum("nj,njk->nk", basis, yw[inv[ids]])
    for w in np.flatnonzero(usable & ~regular):
        sel = inv == w
        res[sel] = barycentric_interpolate(pattern[w], yw[w], s[sel], axis=0)
    return res


def _fail(path: Path, message: str, line: int | None = None) -> InputError:
    return InputError(message, path=path, line=line)


def _float(path: Path, text: str, lineno: int, c0: int, c1: int, what: str) -> float:
    s = text[c0:c1]
    if not s.strip():
        raise _fail(path, f"{what} (columns {c0 + 1}-{c1}) is blank; expected a number", lineno)
    try:
        x = float(s)
    except ValueError:
        raise _fail(
            path,
            f"cannot parse number {s.strip()!r} in columns {c0 + 1}-{c1} ({what})",
            lineno,
        ) from None
    if not math.isfinite(x):
        raise _fail(
            path,
            f"{what} (columns {c0 + 1}-{c1}) is {s.strip()!r}; expected a finite number",
            lineno,
        )
    return x


def _epoch_fields(path: Path, line: str, lineno: int) -> tuple[int, int, int, int, int, float]:
    try:
        ints = [line[a:b] for a, b in ((3, 7), (8, 10), (11, 13), (14, 16), (17, 19))]
        if not all(x.strip().isdigit() for x in ints):
            raise ValueError
        ep = tuple(int(x) for x in ints) + (float(line[20:31]),)
    except ValueError:
        raise _fail(
            path,
            f"cannot read the epoch {line.rstrip()!r}; expected '*  yyyy mm dd hh mm ss.ssssssss'",
            lineno,
        ) from None
    if not valid_calendar(ep):
        raise _fail(
            path,
            f"impossible epoch {line[3:31].strip()!r} (month 1-12, day in the month, hour 0-23, "
            "minute 0-59, seconds 0-60, year 1980-2099)",
            lineno,
        )
    return ep


def _lines(p: Path) -> list[str]:
    """Return the file's lines (Latin-1 text), without the empty one after the last newline."""
    lines = read_bytes(p).decode("latin-1").split("\n")
    if lines and not lines[-1]:
        lines.pop()  # the newline ending the last line does not start a new one
    return lines


def _first_line(p: Path, first: str) -> int:
    """Check line 1 (SP3-c/d, position/velocity flag); return the number of epochs it announces."""
    if first[:1] != "#" or first[1:2] not in ("a", "b", "c", "d"):
        what = "a RINEX file" if first[60:80].strip() == "RINEX VERSION / TYPE" else "not SP3"
        raise _fail(
            p,
            f"not an SP3 file ({what}): line 1 starts with {first[:3]!r}; expected an SP3-c "
            "or SP3-d header starting with '#c' or '#d'",
            1,
        )
    version = first[1]
    if version not in ("c", "d"):
        raise _fail(p, f"SP3-{version} is not supported; expected SP3-c or SP3-d ('#c' / '#d')", 1)
    if first[2:3] not in ("P", "V"):
        raise _fail(
            p,
            f"line 1 column 3 is {first[2:3]!r}; expected the position/velocity flag 'P' or 'V'",
            1,
        )
    try:
        return int(first[32:39])
    except ValueError:
        raise _fail(
            p, f"cannot read the number of epochs {first[32:39]!r} in columns 33-39", 1
        ) from None


@dataclass
class _Header:
    """What the SP3 header lines after line 1 hold, and where the data section starts."""

    n_sat: int | None = None
    sat_line: int = 0
    sat_ids: list[str] = field(default_factory=list)
    time_system: str | None = None
    start: int = 1


def _sat_count(p: Path, line: str, lineno: int) -> int:
    """Read the number of satellites in columns 2-6 of the first '+' line."""
    try:
        return int(line[1:6])
    except ValueError:
        raise _fail(
            p,
            f"cannot read the number of satellites {line[1:6].strip()!r} in columns 2-6",
            lineno,
        ) from None


def _read_header(p: Path, lines: list[str]) -> _Header:
    """Read the satellite list and time system up to the first epoch line ('*')."""
    h = _Header()
    i = 1
    n = len(lines)
    while i < n and not lines[i].startswith("*"):
        line = lines[i]
        if line.startswith("+ "):
            h.sat_line = h.sat_line or i + 1
            if h.n_sat is None:
                h.n_sat = _sat_count(p, line, i + 1)
            body = line[9:60]
            h.sat_ids.extend(body[c : c + 3] for c in range(0, len(body), 3))
        elif line.startswith("%c") and h.time_system is None:
            h.time_system = line[9:12].strip()
        elif line.startswith("EOF"):
            break
        i += 1
    if i >= n or not lines[i].startswith("*"):
        raise _fail(
            p,
            "truncated SP3 file: no epoch line ('*  yyyy ...') after the header",
            i + 1 if i < n else n,
        )
    if h.n_sat is None:
        raise _fail(p, "no satellite list ('+' lines) in the SP3 header", i + 1)
    h.start = i
    return h


def _satellites(p: Path, h: _Header) -> list[str]:
    """Return the header's satellite ids (blanks read as zeros), checked against their count."""
    sats = [s.replace(" ", "0") for s in h.sat_ids if s.strip() and s.strip() != "0"][: h.n_sat]
    for s in sats:
        lo, hi = PRN_RANGE.get(s[:1], (1, 99))
        if not (s[1:].isdigit() and lo <= int(s[1:]) <= hi):
            raise _fail(
                p,
                f"satellite id {s!r} in the header's satellite list is not valid: expected a "
                f"system letter and a number from {lo:02d} to {hi:02d}",
                h.sat_line,
            )
    if len(sats) != h.n_sat:
        raise _fail(
            p,
            f"the header announces {h.n_sat} satellites but its '+' lines list {len(sats)}",
            2,
        )
    return sats


def _time_system(p: Path, time_system: str | None) -> str:
    """Return the '%c' time system (GPS when blank or 'ccc'); refuse an unknown one."""
    if time_system in (None, "", "ccc"):
        time_system = "GPS"
    if time_system not in _TIME_SYSTEMS:
        raise _fail(
            p,
            f"unknown time system {time_system!r} in the '%c' line; expected one of "
            + ", ".join(_TIME_SYSTEMS),
        )
    return time_system


_ORIGIN = [0.0, 0.0, 0.0]


def _position_values(p: Path, line: str, lineno: int, sat: str) -> tuple[list[float], float]:
    """Return x, y, z (km) and the clock (us, NaN when blank) of a position record line."""
    has_clock = bool(line[46:60].strip())
    try:
        v = [float(line[4:18]), float(line[18:32]), float(line[32:46])]
        ck = float(line[46:60]) if has_clock else math.nan
        ok = math.isfinite(v[0] + v[1] + v[2] + (ck if has_clock else 0.0))
    except ValueError:
        ok = False
    if ok:
        return v, ck
    # a blank, unreadable or non-finite number: read field by field, naming the first one
    v = [
        _float(p, line, lineno, 4 + 14 * q, 18 + 14 * q, f"{ax} of {sat}")
        for q, ax in enumerate(("x", "y", "z"))
    ]
    ck = _float(p, line, lineno, 46, 60, f"clock of {sat}") if has_clock else math.nan
    return v, ck


class _Records:
    """Epochs, positions (m) and clocks (s) of an SP3 data section, filled line by line."""

    def __init__(self, p: Path, sats: list[str], n_epochs_header: int, start: int) -> None:
        self.p, self.n_sat, self.n_epochs_header = p, len(sats), n_epochs_header
        self.col = {s: k for k, s in enumerate(sats)}
        self.epochs: list[tuple[int, int, int, int, int, float]] = []
        self.epoch_lines: list[int] = []
        self.xyz = np.full((max(n_epochs_header, 1), self.n_sat, 3), np.nan)
        self.clk = np.full((max(n_epochs_header, 1), self.n_sat), np.nan)
        self.seen = 0  # P records in the current epoch
        self.saw_eof = False
        self.last_epoch_line = start
        self.end = start  # index of the line where reading stopped (the EOF line, or n)

    def epoch(self, line: str, i: int) -> int:
        """Start an epoch at line index ``i`` (the one before must be complete); its index."""
        if self.epochs and self.seen < self.n_sat:
            raise _fail(
                self.p,
                f"incomplete epoch: {self.seen} of {self.n_sat} position records before the next "
                "epoch line",
                i + 1,
            )
        self.epochs.append(_epoch_fields(self.p, line, i + 1))
        self.epoch_lines.append(i + 1)
        self.last_epoch_line = i
        self.seen = 0
        e = len(self.epochs) - 1
        if e >= self.xyz.shape[0]:
            self.xyz = np.concatenate([self.xyz, np.full_like(self.xyz, np.nan)])
            self.clk = np.concatenate([self.clk, np.full_like(self.clk, np.nan)])
        return e

    def position(self, line: str, i: int, e: int) -> None:
        """Read the position (km -> m) and clock (us -> s) record on line index ``i``."""
        if e < 0:
            raise _fail(self.p, "position record before the first epoch line", i + 1)
        sat = line[1:4].replace(" ", "0")
        k = self.col.get(sat)
        if k is None:
            raise _fail(self.p, f"satellite {sat} is not in the header's satellite list", i + 1)
        v, ck = _position_values(self.p, line, i + 1, sat)
        # neither coordinate 999999.999999 nor all three 0.000000: a position
        if max(abs(v[0]), abs(v[1]), abs(v[2])) < _MISSING_KM and v != _ORIGIN:
            self.xyz[e, k] = np.multiply(v, 1000.0)
        if abs(ck) < _MISSING_CLOCK_US:  # (NaN: a blank clock)
            self.clk[e, k] = ck * 1e-6
        self.seen += 1

    def check_complete(self, n_lines: int) -> None:
        """Refuse an incomplete last epoch, and fewer epochs than the header announces."""
        n_ep = len(self.epochs)
        end_line = self.end + 1 if self.saw_eof else n_lines  # the EOF line, or the last line
        if self.seen < self.n_sat and n_ep:
            raise _fail(
                self.p,
                f"truncated SP3 file: the last epoch (line {self.last_epoch_line + 1}) has "
                f"{self.seen} of {self.n_sat} position records"
                + ("" if self.saw_eof else " and there is no EOF line"),
                end_line,
            )
        if n_ep < self.n_epochs_header:
            raise _fail(
                self.p,
                f"truncated SP3 file: the header announces {self.n_epochs_header} epochs but the "
                f"file holds {n_ep}" + ("" if self.saw_eof else " and ends without the EOF line"),
                end_line,
            )


#: first characters of the lines the reader skips (velocities, correlations, comments)
_SKIPPED = ("V", "E", "/", "%", "+", "#")


def _read_records(rec: _Records, lines: list[str]) -> None:
    """Read epoch and position lines from the first epoch line to 'EOF' or the file's end."""
    i = rec.end
    n = len(lines)
    e = -1
    while i < n:
        line = lines[i]
        c = line[:1]
        if c == "*":
            e = rec.epoch(line, i)
        elif c == "P":
            rec.position(line, i, e)
        elif line.startswith("EOF"):
            rec.saw_eof = True
            break
        elif c not in _SKIPPED and line.strip():
            raise _fail(
                rec.p,
                f"unexpected line {line[:20]!r}; expected an epoch ('*'), position ('P'), "
                "velocity ('V') or 'EOF' line",
                i + 1,
            )
        i += 1
    rec.end = i


def _epoch_times(rec: _Records, time_system: str) -> NDArray[np.float64]:
    """Return the epochs in GPS seconds; refuse epochs that do not increase."""
    ep = np.asarray(rec.epochs, dtype=np.float64)
    labels = calendar_to_gps_s(
        ep[:, 0].astype(np.int64),
        ep[:, 1].astype(np.int64),
        ep[:, 2].astype(np.int64),
        ep[:, 3].astype(np.int64),
        ep[:, 4].astype(np.int64),
        ep[:, 5],
    )
    t = _labels_to_gps_s(labels, time_system)
    if np.any(np.diff(t) <= 0):
        bad = int(np.flatnonzero(np.diff(t) <= 0)[0]) + 1
        raise _fail(
            rec.p,
            f"epoch {bad + 1} is not later than the previous epoch (line "
            f"{rec.epoch_lines[bad - 1]}); expected increasing epochs",
            rec.epoch_lines[bad],
        )
    return t


def read_sp3(path: str | os.PathLike[str]) -> PreciseOrbit:
    """Read an SP3-c or SP3-d precise orbit file.

    Parameters
    ----------
    path : str or path-like
        SP3 file, plain or compressed (gzip, Z, bz2, zip).

    Returns
    -------
    PreciseOrbit
        Epochs (GPS seconds), satellite list, positions (m) and clocks (s).

    Raises
    ------
    InputError
        If the file is not SP3-c/d, has an unknown time system, a malformed
        line or number, or is truncated (fewer epochs than the header
        announces, or an incomplete last epoch). The message names the file
        and the 1-based line.

    """
    p = Path(path)
    lines = _lines(p)
    n_epochs_header = _first_line(p, lines[0])
    head = _read_header(p, lines)
    sats = _satellites(p, head)
    time_system = _time_system(p, head.time_system)
    rec = _Records(p, sats, n_epochs_header, head.start)
    _read_records(rec, lines)
    rec.check_complete(len(lines))
    t = _epoch_times(rec, time_system)
    n_ep = len(rec.epochs)
    return PreciseOrbit(
        path=p,
        t_gps_s=t,
        sats=tuple(sats),
        xyz_m=rec.xyz[:n_ep],
        clock_s=rec.clk[:n_ep],
        time_system=time_system,
    )


def _labels_to_gps_s(labels: NDArray[np.float64], time_system: str) -> NDArray[np.float64]:
    if time_system in ("GPS", "GAL", "QZS"):
        return labels
    if time_system == "TAI":
        return labels - TAI_MINUS_GPS_S
    if time_system == "BDT":
        return labels + 14.0
    if time_system == "GLO":
        return utc_to_gps_s(labels - 3 * 3600.0)
    return utc_to_gps_s(labels)


def merge_precise(orbits: Sequence[PreciseOrbit], path: str | Path) -> PreciseOrbit:
    """Join SP3 files of consecutive periods (one epoch interval) into one orbit.

    Parameters
    ----------
    orbits : sequence of PreciseOrbit
        The files read.
    path : str or Path
        The name of the joined set (for messages).

    Returns
    -------
    PreciseOrbit
        The union of the satellites (in order of appearance) and of the
        epochs in time order; an epoch in two files is taken from the first
        given; NaN where a file lacks a satellite.

    Raises
    ------
    InputError
        When the files have different epoch intervals (the interpolation
        windows need one step).
    """
    steps = {round(float(np.median(np.diff(o.t_gps_s))), 3) for o in orbits if o.t_gps_s.size > 1}
    if len(steps) > 1:
        names = ", ".join(
            f"{Path(o.path).name} ({float(np.median(np.diff(o.t_gps_s))):g} s)"
            for o in orbits
            if o.t_gps_s.size > 1
        )
        raise InputError(
            f"SP3 files with different epoch intervals: {names}; give files of "
            "one interval (one product)",
            path=path,
        )
    sats = tuple(dict.fromkeys(s for o in orbits for s in o.sats))
    t_all = np.concatenate([o.t_gps_s for o in orbits])
    t, first = np.unique(t_all, return_index=True)  # the first file's epoch where repeated
    xyz = np.full((t.size, len(sats), 3), np.nan)
    clk = np.full((t.size, len(sats)), np.nan)
    offset = 0
    for o in orbits:
        rows = np.arange(offset, offset + o.t_gps_s.size)
        keep = np.isin(rows, first)
        at = np.searchsorted(t, o.t_gps_s[keep])
        cols = [sats.index(s) for s in o.sats]
        xyz[at[:, None], cols] = o.xyz_m[keep]
        clk[at[:, None], cols] = o.clock_s[keep]
        offset += o.t_gps_s.size
    return PreciseOrbit(
        path=Path(path),
        t_gps_s=t,
        sats=sats,
        xyz_m=xyz,
        clock_s=clk,
        time_system=orbits[0].time_system,
    )
