"""Vectorised scan of a regular RINEX 3 data section (the common case).

:func:`scan_v3` does in a few numpy passes what the line-by-line scan of
:func:`psdbound.io._body.parse_v3` does with a Python loop over every line:
find the epoch records, read their dates, flags and satellite counts, and
collect the satellite records per system as a space-padded character array.
It only accepts a data section that is *regular*: every epoch record in the
strict layout with flag 0 or 1, exactly the announced number of satellite
records after each, every record starting with a system letter, no repeated
epoch and nothing but blanks beyond the header's observation types. For
anything else it returns None and the caller runs the line-by-line scan,
which reports the exact problem (file, line, what was expected) or handles
the rare valid irregularities (events, repeated epochs). On a regular
section both scans give identical arrays.
"""

from __future__ import annotations

from collections.abc import Collection

import numpy as np
from numpy.typing import NDArray

__all__ = ["Scan", "scan_v3"]

_SPACE, _ZERO, _NL = 32, 48, 10
#: characters ``bytes.strip()`` removes (blanks beyond the observation types)
_WHITE = np.zeros(256, dtype=bool)
_WHITE[[9, 10, 11, 12, 13, 32]] = True
_IS_DIGIT = np.zeros(256, dtype=bool)
_IS_DIGIT[_ZERO : _ZERO + 10] = True
_IS_DIGIT_OR_SPACE = _IS_DIGIT.copy()
_IS_DIGIT_OR_SPACE[_SPACE] = True
_LETTERS = np.zeros(256, dtype=bool)
_LETTERS[np.frombuffer(b"GRECJSI", dtype=np.uint8)] = True
#: rows per chunk when gathering characters (bounds the index arrays to ~32 MB)
_CHUNK_CHARS = 4_000_000
#: epoch record ``> yyyy mm dd hh mm ss.sssssss  f nnn``: fixed characters and digit columns
_EPOCH_LEN = 35
_FIXED = {0: ord(">"), 1: _SPACE, 6: _SPACE, 9: _SPACE, 12: _SPACE, 15: _SPACE, 21: ord(".")}
_DIGITS = [2, 3, 4, 5, 8, 11, 14, 17, 20, *range(22, 29)]
_DIGIT_OR_SPACE = [7, 10, 13, 16, 18, 19]


class Scan:
    """What :func:`scan_v3` found (the fields of the line-by-line collector).

    Attributes
    ----------
    dates : ndarray of float64, shape (n_epoch, 6)
        Year, month, day, hour, minute, second of every epoch.
    lines : ndarray of int64, shape (n_epoch,)
        0-based line index of every epoch record in the data section.
    flags : ndarray of int8, shape (n_epoch,)
        Epoch flags (0 or 1).
    chars : dict of str to ndarray of uint8, shape (n_record, width)
        Satellite records per system, cut to ``width`` and space-padded.
    line_of, epoch_of : dict of str to ndarray of int64
        Line and epoch index of every record.
    sat_of : dict of str to list of str
        Satellite id of every record (blanks in the number read as zeros).
    sat_key : dict of str to ndarray of int64
        The id's three characters as one integer (same order as the ids).
    seen : set of str
        Systems of every record, kept or not.
    """

    def __init__(self) -> None:
        self.dates = np.zeros((0, 6))
        self.lines = np.zeros(0, dtype=np.int64)
        self.flags = np.zeros(0, dtype=np.int8)
        self.chars: dict[str, NDArray[np.uint8]] = {}
        self.line_of: dict[str, NDArray[np.int64]] = {}
        self.epoch_of: dict[str, NDArray[np.int64]] = {}
        self.sat_of: dict[str, list[str]] = {}
        self.sat_key: dict[str, NDArray[np.int64]] = {}
        self.seen: set[str] = set()


def _gather(
    buf: NDArray[np.uint8], starts: NDArray[np.int64], lengths: NDArray[np.int64], width: int
) -> NDArray[np.uint8]:
    """Rows ``buf[start:start + length]`` cut to ``width`` and space-padded, in chunks."""
    n = starts.size
    out = np.full((n, width), _SPACE, dtype=np.uint8)
    if n == 0 or width == 0:
        return out
    cols = np.arange(width, dtype=np.int64)
    step = max(1, _CHUNK_CHARS // width)
    last = buf.size - 1
    for lo in range(0, n, step):
        hi = min(n, lo + step)
        idx = starts[lo:hi, None] + cols
        inside = cols < lengths[lo:hi, None]
        np.minimum(idx, last, out=idx)
        out[lo:hi] = np.where(inside, buf[idx], _SPACE)
    return out


def _is_strict_epoch(chars: NDArray[np.uint8]) -> bool:
    """Whether every epoch record has the fixed characters and digits of the strict layout."""
    for k, c in _FIXED.items():
        if np.any(chars[:, k] != c):
            return False
    if (
        not _IS_DIGIT[chars[:, _DIGITS]].all()
        or not _IS_DIGIT_OR_SPACE[chars[:, _DIGIT_OR_SPACE]].all()
    ):
        return False
    # a blank inside a number ("1 2") is not what int() reads: only leading blanks
    for a, b in ((7, 8), (10, 11), (13, 14), (16, 17), (18, 19)):
        if np.any((chars[:, a] != _SPACE) & (chars[:, b] == _SPACE)):
            return False
    return True


def _number(digits: NDArray[np.int64], cols: list[int]) -> NDArray[np.int64]:
    """The decimal number written in columns ``cols`` of rows of digit values."""
    v = np.zeros(digits.shape[0], dtype=np.int64)
    for c in cols:
        v = v * 10 + digits[:, c]
    return v


def _dates(chars: NDArray[np.uint8]) -> NDArray[np.float64]:
    """Year, month, day, hour, minute, second (s) of strict epoch records."""
    d = chars.astype(np.int64) - _ZERO
    dsp = np.where(chars == _SPACE, 0, d)  # "[ \d]" columns: a blank is a leading zero
    year = _number(d, [2, 3, 4, 5])
    sec = _number(dsp, [18, 19, 20, *range(22, 29)]).astype(np.float64) / 1e7
    fields = [year, *(_number(dsp, [c, c + 1]) for c in (7, 10, 13, 16))]
    return np.column_stack([np.column_stack(fields).astype(np.float64), sec])


def _sat_counts(n_c: NDArray[np.uint8]) -> NDArray[np.int64] | None:
    """The satellite counts (3 columns, leading blanks); None if one is not in that layout."""
    if not _IS_DIGIT[n_c[:, 2]].all() or not _IS_DIGIT_OR_SPACE[n_c[:, :2]].all():
        return None
    if np.any((n_c[:, 0] != _SPACE) & (n_c[:, 1] == _SPACE)):
        return None
    return _number(np.where(n_c == _SPACE, 0, n_c.astype(np.int64) - _ZERO), [0, 1, 2])


def _epoch_fields(
    chars: NDArray[np.uint8],
) -> tuple[NDArray[np.float64], NDArray[np.int64], NDArray[np.int64]] | None:
    """Dates, flags and satellite counts of strict epoch records; None if any is not."""
    if not _is_strict_epoch(chars):
        return None
    dates = _dates(chars)
    flag_c = chars[:, 31]
    if not np.all((flag_c == _SPACE) | (flag_c == _ZERO) | (flag_c == _ZERO + 1)):
        return None  # events (2-5), cycle-slip records (6) and bad flags: line by line
    flags = np.where(flag_c == _SPACE, 0, flag_c.astype(np.int64) - _ZERO)
    nsat = _sat_counts(chars[:, 32:35])
    if nsat is None:
        return None
    return dates, flags, nsat


def _line_bounds(buf: NDArray[np.uint8]) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Start and length (bytes) of every line, blank lines at the end dropped."""
    nl = np.flatnonzero(buf == _NL)
    starts = np.concatenate([[0], nl + 1]).astype(np.int64)
    ends = np.concatenate([nl, [buf.size]]).astype(np.int64)
    lengths = ends - starts
    n_lines = lengths.size
    while n_lines and (
        lengths[n_lines - 1] == 0 or _WHITE[buf[starts[n_lines - 1] : ends[n_lines - 1]]].all()
    ):
        n_lines -= 1
    return starts[:n_lines], lengths[:n_lines]


def _epochs(
    buf: NDArray[np.uint8],
    starts: NDArray[np.int64],
    lengths: NDArray[np.int64],
    is_epoch: NDArray[np.bool_],
    scan: Scan,
) -> bool:
    """Read the epoch records into ``scan``; False if they are not regular."""
    ep_lines = np.flatnonzero(is_epoch)
    ep_chars = _gather(buf, starts[ep_lines], lengths[ep_lines], _EPOCH_LEN)
    if np.any(lengths[ep_lines] < _EPOCH_LEN):
        return False
    fields = _epoch_fields(ep_chars)
    if fields is None:
        return False
    dates, flags, nsat = fields
    if not np.array_equal(np.diff(np.append(ep_lines, lengths.size)) - 1, nsat):
        return False
    if dates.shape[0] > 1 and np.any((np.diff(dates, axis=0) == 0).all(axis=1)):
        return False  # repeated epochs: compared record by record, line by line
    scan.dates, scan.lines, scan.flags = dates, ep_lines.astype(np.int64), flags.astype(np.int8)
    return True


def _system_records(
    buf: NDArray[np.uint8],
    starts: NDArray[np.int64],
    lengths: NDArray[np.int64],
    sel: NDArray[np.int64],
    s: str,
    width: int,
    scan: Scan,
) -> bool:
    """Put the records ``sel`` of system ``s`` into ``scan``; False if one is not regular."""
    longest = int(lengths[sel].max())
    chars = _gather(buf, starts[sel], lengths[sel], max(width, longest))
    if longest > width:
        if not _WHITE[chars[:, width:]].all():
            return False
        chars = np.ascontiguousarray(chars[:, :width])
    ids = chars[:, :3].copy()
    if np.any(ids >= 128):
        return False
    ids[ids == _SPACE] = _ZERO
    scan.chars[s] = chars
    scan.line_of[s] = sel.astype(np.int64)
    scan.sat_of[s] = ids.view("S3").ravel().astype("U3").tolist()
    scan.sat_key[s] = (ids.astype(np.int64) << np.array([16, 8, 0])).sum(axis=1)
    return True


def scan_v3(body: bytes, systems: Collection[str] | None, widths: dict[str, int]) -> Scan | None:
    """Scan a regular RINEX 3 data section at once.

    Parameters
    ----------
    body : bytes
        The data section (after ``END OF HEADER``).
    systems : collection of str or None
        System letters to keep (None: all).
    widths : dict of str to int
        Record width per system (3 + 16 x number of observation types).

    Returns
    -------
    Scan or None
        None when the section is not regular (see the module docstring).
    """
    buf = np.frombuffer(body, dtype=np.uint8)
    # blank lines at the end are dropped; any other blank or short line: line by line
    starts, lengths = _line_bounds(buf)
    if lengths.size == 0 or np.any(lengths < 3):
        return None
    first = buf[starts]
    is_epoch = first == ord(">")
    if not is_epoch[0] or not np.all(is_epoch | _LETTERS[first]):
        return None
    scan = Scan()
    if not _epochs(buf, starts, lengths, is_epoch, scan):
        return None
    rec = np.flatnonzero(~is_epoch)
    epoch_idx = np.cumsum(is_epoch)[rec] - 1
    sys_of = first[rec]
    letters, first_rec = np.unique(sys_of, return_index=True)
    scan.seen = {chr(int(c)) for c in letters}
    for letter in letters[np.argsort(first_rec)]:  # systems in order of appearance
        s = chr(int(letter))
        if systems is not None and s not in systems:
            continue
        width = widths.get(s)
        if width is None:
            return None  # no observation types: the line-by-line scan names the record
        if not _system_records(buf, starts, lengths, rec[sys_of == letter], s, width, scan):
            return None
        scan.epoch_of[s] = epoch_idx[sys_of == letter].astype(np.int64)
    return scan
