"""RINEX observation data sections (versions 2.1x, 3.0x and 4.0x) -> arrays, strict.

What is checked (every failure is an :class:`InputError` naming the file and
the line):

* epoch lines: the layout, the epoch flag (0-6), the number of records that
  follow (exactly that many lines up to the next epoch), calendar fields in
  range (month 13, day 32, hour 25, non-finite seconds, a year outside
  1980-2099 are refused), not before ``TIME OF FIRST OBS`` nor after
  ``TIME OF LAST OBS``; the seconds are rounded to the microsecond
  (``29.9999999`` is 30 s, ``59.9999999`` the next minute: :mod:`._epochs`);
* epoch order: an epoch earlier than the one before it is refused; an
  epoch repeated with the same records is dropped with a warning, repeated
  with different records refused;
* records: the satellite id (system letter, number within the system's
  range), one record per satellite and epoch, no characters beyond the
  columns of the declared observation types, every value in the strict
  F14.3 layout, and values within what their type can be (signal strength,
  Doppler, pseudorange), so that columns shifted against the header are
  refused instead of read as other observations;
* header records inside the data (event flag 4) that change the observation
  types are refused.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError
from psdbound.io._body_fast import Scan, scan_v3
from psdbound.io._epochs import YEAR_RANGE, check_dates, date_labels, fmt_date
from psdbound.io._fields import FIELD_WIDTH, FieldError, pad_lines, parse_fields
from psdbound.io._header import ObsHeader, missing_systems
from psdbound.io.kepler import PRN_RANGE
from psdbound.io.timescales import utc_to_gps_s

#: Plausible values per observation type (first letter), in RINEX units; outside them a
#: column is not what the header says it is.
VALUE_LIMITS = {
    "C": (-1e6, 1e9, "pseudorange, m"),
    "P": (-1e6, 1e9, "pseudorange, m"),
    "D": (-1e6, 1e6, "Doppler, Hz"),
    "S": (0.0, 1e4, "signal strength"),
}

_DATE_V3 = re.compile(rb"> (\d{4}) ([ \d]\d) ([ \d]\d) ([ \d]\d) ([ \d]\d)([ \d]{2}\d\.\d{7})")
_DATE_V2 = re.compile(rb" ([ \d]\d) ([ \d]\d) ([ \d]\d) ([ \d]\d) ([ \d]\d)([ \d]{2}\d\.\d{7})")
_LETTER = np.zeros(256, dtype=bool)
_LETTER[np.frombuffer(b"GRECJSI", dtype=np.uint8)] = True
#: records parsed at a time (bounds the temporary arrays of :func:`parse_fields`)
_PARSE_ROWS = 32768


@dataclass
class RawBlock:
    system: str
    sats: tuple[str, ...]
    codes: tuple[str, ...]
    values: np.ndarray
    lli: np.ndarray
    ssi: np.ndarray


#: What a data section's parser returns: epochs (GPS s), epoch flags, the blocks of the
#: systems read, warnings, and the system letters of every record of the file (read or not).
Parsed = tuple[
    NDArray[np.float64], NDArray[np.int8], dict[str, RawBlock], tuple[str, ...], tuple[str, ...]
]


def _error_line(header: ObsHeader, idx: int) -> int:
    return header.n_lines + idx + 1


def _to_gps_s(labels: np.ndarray, header: ObsHeader) -> np.ndarray:
    ts = header.time_system.upper()
    if ts in ("GPS", "GAL", "QZS", "IRN", ""):
        return labels
    if ts == "BDT":
        return labels + 14.0
    if ts == "GLO":
        return utc_to_gps_s(labels - 3 * 3600.0)
    return utc_to_gps_s(labels)


def _bad_date(date: tuple, time_system: str) -> bool:
    return check_dates(np.asarray([date], float), time_system, True) is not None


def _label(date: tuple) -> float:
    return float(date_labels(np.asarray([date], dtype=np.float64))[0])


class _Collector:
    """Gathers epochs and satellite records while a data section is scanned."""

    def __init__(self, header: ObsHeader, path: Path, systems: Collection[str] | None) -> None:
        self.header, self.path, self.systems = header, path, systems
        self.times: list[tuple] = []
        self.lines: list[int] = []
        self.flags: list[int] = []
        self.records: dict[str, list[bytes]] = {}
        self.line_of: dict[str, list[int]] = {}
        self.epoch_of: dict[str, list[int]] = {}
        self.sat_of: dict[str, list[str]] = {}
        self.warnings: list[str] = []
        self.sat_key: dict[str, np.ndarray] = {}
        self.seen: set[str] = set()  # systems of every record, wanted or not

    def load(self, scan: Scan) -> None:
        """Take the epochs and records of a vectorised scan (records as character arrays)."""
        self.times = scan.dates  # type: ignore[assignment]
        self.lines = scan.lines  # type: ignore[assignment]
        self.flags = scan.flags  # type: ignore[assignment]
        self.records = scan.chars  # type: ignore[assignment]
        self.line_of = scan.line_of  # type: ignore[assignment]
        self.epoch_of = scan.epoch_of  # type: ignore[assignment]
        self.sat_of = scan.sat_of
        self.sat_key = scan.sat_key
        self.seen = scan.seen

    def fail(self, message: str, idx: int) -> InputError:
        return InputError(message, path=self.path, line=_error_line(self.header, idx))

    def epoch(self, ln: bytes, i: int, flag: int, layout: re.Pattern[bytes]) -> int:
        """Record an epoch's date and flag; return its index."""
        m = layout.match(ln)
        if m is None:
            raise self.fail(
                f"bad epoch date {ln[:29].decode('ascii', 'replace')!r} (expected "
                + (
                    "'> yyyy mm dd hh mm ss.sssssss'"
                    if layout is _DATE_V3
                    else "' yy mm dd hh mm ss.sssssss'"
                )
                + ")",
                i,
            )
        g = m.groups()
        self.times.append((int(g[0]), int(g[1]), int(g[2]), int(g[3]), int(g[4]), float(g[5])))
        self.lines.append(i)
        self.flags.append(flag)
        return len(self.flags) - 1

    def record(self, sys_: str, rec: bytes, j: int, e: int, sat: str) -> None:
        """Keep one satellite record (line ``j``, epoch ``e``) if its system is wanted."""
        self.seen.add(sys_)
        if self.systems is not None and sys_ not in self.systems:
            return
        if sys_ not in self.records:
            self.records[sys_], self.line_of[sys_] = [], []
            self.epoch_of[sys_], self.sat_of[sys_] = [], []
        self.records[sys_].append(rec)
        self.line_of[sys_].append(j)
        self.epoch_of[sys_].append(e)
        self.sat_of[sys_].append(sat)

    # ----------------------------------------------------------------- epochs
    def _records_of(self, e: int) -> tuple[int, dict[tuple[str, str], bytes]]:
        out = {}
        for s, ep in self._epoch_arrays.items():
            lo, hi = np.searchsorted(ep, [e, e + 1])
            for k in range(lo, hi):
                rec = self.records[s][k]  # bytes, or a row of the scan's character array
                text = rec.tobytes() if isinstance(rec, np.ndarray) else rec
                out[(s, self.sat_of[s][k])] = text.rstrip()
        return self.flags[e], out

    def _epochs(self, version3: bool) -> np.ndarray:
        """Check dates and order, resolve repeated epochs; return the kept labels."""
        h = self.header
        dates = np.asarray(self.times, dtype=np.float64).reshape(-1, 6)
        k = check_dates(dates, h.time_system, version3)
        if k is not None:
            raise self.fail(
                f"impossible epoch date {' '.join(f'{v:g}' for v in dates[k])} (month 1-12, day "
                f"in the month, hour 0-23, minute 0-59, seconds 0-60, year "
                f"{YEAR_RANGE[0]}-{YEAR_RANGE[1]})",
                self.lines[k],
            )
        labels = date_labels(dates)
        step = np.diff(labels)
        if np.any(step < 0):
            k = int(np.argmax(step < 0)) + 1
            raise self.fail(
                f"epoch {fmt_date(dates[k])} is earlier than the epoch before it "
                f"({fmt_date(dates[k - 1])}, line {_error_line(h, self.lines[k - 1])}): epochs "
                "must increase (the file is damaged or was concatenated out of order)",
                self.lines[k],
            )
        self._check_span(labels, dates)
        if not np.any(step == 0):
            return labels
        keep = self._repeats(dates, np.flatnonzero(step == 0) + 1)
        self._drop_epochs(keep)
        return labels[keep]

    def _repeats(self, dates: np.ndarray, repeated: np.ndarray) -> np.ndarray:
        """Epochs to keep when ``repeated`` ones have the label of the epoch before them.

        A repeat with the same records is dropped with a warning (also when its
        seconds read differently, ``29.9999999`` and ``30.0000000``); with other
        records it is refused.
        """
        h = self.header
        self._epoch_arrays = {s: np.asarray(v) for s, v in self.epoch_of.items()}
        keep = np.ones(dates.shape[0], dtype=bool)
        for k in repeated:
            prev = k - 1
            while not keep[prev]:
                prev -= 1
            if self._records_of(int(prev)) != self._records_of(int(k)):
                raise self.fail(
                    f"epoch {fmt_date(dates[k])} appears twice with different data "
                    f"(lines {_error_line(h, self.lines[prev])} and "
                    f"{_error_line(h, self.lines[k])}); which one is right is unknown",
                    self.lines[k],
                )
            keep[k] = False
        first = int(repeated[0])
        self.warnings.append(
            f"line {_error_line(h, self.lines[first])}: {repeated.size} epoch(s) repeated with "
            f"identical data (first {fmt_date(dates[first])}, also on line "
            f"{_error_line(h, self.lines[first - 1])}); the repeats are ignored"
        )
        return keep

    def _drop_epochs(self, keep: np.ndarray) -> None:
        new = np.cumsum(keep) - 1
        for s, ep in self._epoch_arrays.items():
            m = keep[ep]
            idx = np.flatnonzero(m)
            recs = self.records[s]
            self.records[s] = recs[idx] if isinstance(recs, np.ndarray) else [recs[i] for i in idx]
            self.line_of[s] = np.asarray(self.line_of[s])[idx].tolist()
            self.sat_of[s] = [self.sat_of[s][i] for i in idx]
            if s in self.sat_key:
                self.sat_key[s] = self.sat_key[s][idx]
            self.epoch_of[s] = new[ep[m]].tolist()
        self.flags = [f for f, k in zip(self.flags, keep, strict=True) if k]
        self.lines = [f for f, k in zip(self.lines, keep, strict=True) if k]

    def _check_span(self, labels: np.ndarray, dates: np.ndarray) -> None:
        h = self.header
        for rec, name, sign in (
            (h.first_obs, "TIME OF FIRST OBS", -1),
            (h.last_obs, "TIME OF LAST OBS", 1),
        ):
            if rec is None or _bad_date(rec, h.time_system):
                continue
            limit = _label(rec)
            out = sign * (labels - limit) > 1.0
            if out.any():
                k = int(np.argmax(out))
                where = "before" if sign < 0 else "after"
                raise self.fail(
                    f"epoch {fmt_date(dates[k])} is {where} the header's {name} "
                    f"{fmt_date(rec)}: a damaged date, or the header does not belong to the data",
                    self.lines[k],
                )

    def finish(self, codes_wanted: Collection[str] | None, offset: int) -> Parsed:
        """Return epochs (GPS s), epoch flags, the per-system blocks, warnings and the systems.

        The systems are those of every record of the file, read or not.
        """
        seen = tuple(sorted(self.seen))
        if len(self.times) == 0:
            return np.zeros(0), np.zeros(0, np.int8), {}, (), seen
        labels = self._epochs(offset == 3)
        absent = set(self.systems or ()) - set(self.records)
        if absent:
            raise missing_systems(self.path, absent, self.seen, "its observed satellites")
        t = _to_gps_s(labels, self.header)
        blocks = _build_blocks(self, len(self.flags), codes_wanted, offset)
        return t, np.asarray(self.flags, dtype=np.int8), blocks, tuple(self.warnings), seen


# ------------------------------------------------------------------- records
def _check_sats(acc: _Collector, system: str, sats: np.ndarray) -> None:
    lo, hi = PRN_RANGE.get(system, (1, 99))
    for sat in map(str, sats):
        num = sat[1:]
        if len(sat) == 3 and num.isdigit() and lo <= int(num) <= hi:
            continue
        k = acc.sat_of[system].index(sat)
        raise acc.fail(
            f"satellite id {sat!r} is not valid: expected {system} and a number from "
            f"{lo:02d} to {hi:02d}",
            acc.line_of[system][k],
        )


def _check_widths(acc: _Collector, system: str, recs: list[bytes], width: int) -> None:
    lengths = np.fromiter(map(len, recs), dtype=np.int64, count=len(recs))
    for r in np.flatnonzero(lengths > width):
        extra = recs[r][width:]
        if extra.strip():
            n = len(acc.header.obs_types[system])
            raise acc.fail(
                f"satellite {acc.sat_of[system][r]}: the record is {len(recs[r].rstrip())} "
                f"characters long, but the header's {n} observation types of {system} end at "
                f"column {width}; found {extra.strip()[:16].decode('ascii', 'replace')!r} beyond "
                "(observation types missing from the header, or columns shifted)",
                acc.line_of[system][r],
            )


def _check_values(
    acc: _Collector, system: str, codes: Sequence[str], values: np.ndarray, row0: int = 0
) -> None:
    for k, code in enumerate(codes):
        lim = VALUE_LIMITS.get(code[0])
        if lim is None:
            continue
        v = values[:, k]
        bad = (v < lim[0]) | (v > lim[1])
        if bad.any():
            j = int(np.argmax(bad))
            r = row0 + j
            raise acc.fail(
                f"satellite {acc.sat_of[system][r]}, observation {code}: {v[j]:.3f} is not a "
                f"{lim[2]} (expected {lim[0]:g} to {lim[1]:g}; columns shifted against the "
                "header's observation types?)",
                acc.line_of[system][r],
            )


def _unique_sats(acc: _Collector, system: str) -> tuple[np.ndarray, np.ndarray]:
    """Sorted distinct satellite ids of a system's records and each record's index into them."""
    key = acc.sat_key.get(system)
    if key is None:
        return np.unique(np.array(acc.sat_of[system]), return_inverse=True)
    uk, first, inv = np.unique(key, return_index=True, return_inverse=True)
    ids = acc.sat_of[system]
    return np.array([ids[k] for k in first]), inv


def _build_blocks(
    acc: _Collector, n_epoch: int, codes_wanted: Collection[str] | None, offset: int
) -> dict[str, RawBlock]:
    blocks = {}
    header = acc.header
    for system in list(acc.records):
        recs = acc.records.pop(system)  # released once parsed (tens of MB a day at 1 Hz)
        types = header.obs_types.get(system)
        if types is None:
            raise acc.fail(
                f"satellite {acc.sat_of[system][0]} has no observation types in the header",
                acc.line_of[system][0],
            )
        sats, sat_idx = _unique_sats(acc, system)
        _check_sats(acc, system, sats)
        n_types = len(types)
        width = offset + FIELD_WIDTH * n_types
        if offset and not isinstance(recs, np.ndarray):  # arrays: checked by the scan
            _check_widths(acc, system, recs, width)
        ep = np.asarray(acc.epoch_of[system])
        key = ep * len(sats) + sat_idx
        order = np.argsort(key, kind="stable")
        if np.any(np.diff(key[order]) == 0):
            r = int(order[np.flatnonzero(np.diff(key[order]) == 0)[0] + 1])
            raise acc.fail(
                f"satellite {acc.sat_of[system][r]} has two records in the same epoch",
                acc.line_of[system][r],
            )
        if codes_wanted is None:
            cols = list(range(n_types))
        else:
            cols = [k for k, c in enumerate(types) if c in codes_wanted]
        if not cols:
            continue
        lines = recs if isinstance(recs, np.ndarray) else pad_lines(recs, width)
        del recs
        values, lli, ssi = _parse_block(acc, system, lines[:, offset:width], n_types, cols)
        del lines
        shape = (n_epoch, len(sats), len(cols))
        v = np.full(shape, np.nan)
        li = np.full(shape, -1, dtype=np.int8)
        si = np.full(shape, -1, dtype=np.int8)
        v[ep, sat_idx] = values
        li[ep, sat_idx] = lli
        si[ep, sat_idx] = ssi
        blocks[system] = RawBlock(
            system, tuple(str(s) for s in sats), tuple(types[k] for k in cols), v, li, si
        )
    return blocks


def _parse_block(
    acc: _Collector, system: str, chars: np.ndarray, n_types: int, cols: list[int]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Parse every field of every record, a chunk of rows at a time; keep ``cols``.

    All fields are parsed and range-checked, also those not kept: a column
    shift in a field the run does not use must still be refused, never turn
    into a wrong value in one it does use.

    Parameters
    ----------
    acc : _Collector
        For error messages (satellite and line of a bad field).
    system : str
        System letter.
    chars : ndarray of uint8, shape (n_record, 16 * n_types)
        The records' observation columns.
    n_types : int
        Observation types of the system in the header.
    cols : list of int
        Indices of the types to parse.

    Returns
    -------
    values : ndarray of float64, shape (n_record, len(cols))
    lli, ssi : ndarray of int8, same shape
    """
    n = chars.shape[0]
    types = acc.header.obs_types[system]
    values = np.empty((n, len(cols)))
    lli = np.empty((n, len(cols)), dtype=np.int8)
    ssi = np.empty((n, len(cols)), dtype=np.int8)
    fields = chars.reshape(n, n_types, FIELD_WIDTH)
    for lo in range(0, n, _PARSE_ROWS):
        hi = min(n, lo + _PARSE_ROWS)
        try:
            v, li, si = parse_fields(fields[lo:hi])
        except FieldError as exc:
            row = lo + exc.row
            raise acc.fail(
                f"satellite {acc.sat_of[system][row]}, observation "
                f"{types[exc.field]}: {exc.text!r} is not an F14.3 number with its "
                "indicators (line cut short or columns shifted?)",
                acc.line_of[system][row],
            ) from None
        _check_values(acc, system, types, v, lo)
        values[lo:hi], lli[lo:hi], ssi[lo:hi] = v[:, cols], li[:, cols], si[:, cols]
    return values, lli, ssi


_REDEFINING = (b"SYS / # / OBS TYPES", b"# / TYPES OF OBSERV")


def _event(acc: _Collector, lines: list[bytes], i: int, flag: int, n: int) -> None:
    """Check the header records of an event (flag 4): the observation types may not change."""
    if flag != 4:
        return
    for j in range(i + 1, i + 1 + n):
        if any(lab in lines[j][60:] for lab in _REDEFINING):
            raise acc.fail(
                "the observation types are redefined inside the data (event flag 4); "
                "psdbound reads one type list per file: split the file there",
                j,
            )


def _epoch_numbers(acc: _Collector, ln: bytes, i: int, a: int, what: str) -> tuple[int, int]:
    """The epoch flag (column ``a``) and the number that follows (3 columns)."""
    f, n = ln[a : a + 1], ln[a + 1 : a + 4]
    if not (f.strip() == b"" or f.isdigit()) or not n.strip().isdigit():
        raise acc.fail(f"bad epoch record {ln[: a + 4].decode('ascii', 'replace')!r} ({what})", i)
    flag = int(f) if f.strip() else 0
    if flag > 6:
        raise acc.fail(f"epoch flag {flag} is not a RINEX epoch flag (0-6)", i)
    return flag, int(n)


def _lines(body: bytes) -> list[bytes]:
    lines = body.split(b"\n")
    while lines and not lines[-1].strip():
        lines.pop()  # the newline ending the file and blank lines after the last epoch
    return lines


def parse_v3(
    body: bytes | memoryview,
    header: ObsHeader,
    path: Path,
    systems: Collection[str] | None,
    codes_wanted: Collection[str] | None,
) -> Parsed:
    """Parse a RINEX 3 data section; return epochs (GPS s), flags, blocks, warnings, systems."""
    widths = {s: 3 + FIELD_WIDTH * len(t) for s, t in header.obs_types.items()}
    scan = scan_v3(body, systems, widths)
    if scan is not None:  # a regular data section, scanned at once
        fast = _Collector(header, path, systems)
        fast.load(scan)
        del scan  # the collector owns the records now and releases them as it parses
        return fast.finish(codes_wanted, 3)
    lines = _lines(bytes(body))
    n_lines = len(lines)
    first = np.frombuffer(b"".join([ln[:1] or b" " for ln in lines]), dtype=np.uint8)
    is_epoch = first == ord(">")
    starts = np.flatnonzero(is_epoch).tolist()
    odd = np.flatnonzero(~is_epoch & ~_LETTER[first])  # lines that cannot be records
    acc = _Collector(header, path, systems)
    if lines and (not starts or starts[0] != 0):
        raise acc.fail(
            "expected an epoch record starting with '>' after the header, found "
            f"{lines[0][:40].decode('ascii', 'replace')!r}",
            0,
        )
    starts.append(n_lines)
    for k in range(len(starts) - 1):
        i, nxt = starts[k], starts[k + 1]
        ln = lines[i]
        flag, nsat = _epoch_numbers(
            acc, ln, i, 31, "expected '> yyyy mm dd hh mm ss.sssssss  f nnn'"
        )
        if i + 1 + nsat != nxt:
            short = i + 1 + nsat > nxt
            where = "the file ends" if nxt == n_lines else "the next epoch starts"
            what = "truncated epoch" if short else "epoch"
            raise acc.fail(
                f"{what} {ln[2:29].decode('ascii', 'replace').strip()}: it announces {nsat} "
                f"{'satellite' if flag in (0, 1, 6) else 'event'} records but {where} after "
                f"{nxt - i - 1} lines",
                i if short else i + 1 + nsat,
            )
        if flag > 1:
            _event(acc, lines, i, flag, nsat)
            continue  # event records (2-5) and cycle-slip records (6) carry no observations
        if odd.size and np.any((odd > i) & (odd < nxt)):
            j = int(odd[np.argmax(odd > i)])
            raise acc.fail(
                "expected a satellite record starting with a satellite id such as 'G05', "
                f"found {lines[j][:20].decode('ascii', 'replace')!r}",
                j,
            )
        e = acc.epoch(ln, i, flag, _DATE_V3)
        for j in range(i + 1, nxt):
            rec = lines[j]
            acc.record(chr(rec[0]), rec, j, e, rec[:3].decode("ascii", "replace").replace(" ", "0"))
    return acc.finish(codes_wanted, 3)


@dataclass(frozen=True)
class _V2Layout:
    """Record layout of a RINEX 2 file: lines per satellite and their widths (characters)."""

    n_types: int
    per_sat: int
    widths: list[int]
    default_sys: str


def _v2_layout(header: ObsHeader) -> _V2Layout:
    """The record layout the header's observation types give (5 types per 80-column line)."""
    n_types = len(next(iter(header.obs_types.values())))
    per_sat = -(-n_types // 5)
    widths = [FIELD_WIDTH * min(5, n_types - 5 * r) for r in range(per_sat)]
    default_sys = header.file_system if header.file_system != "M" else "G"
    return _V2Layout(n_types, per_sat, widths, default_sys)


def _v2_sat_list(
    acc: _Collector, lines: list[bytes], i: int, nsat: int, per_sat: int
) -> tuple[list[str], int]:
    """The satellite ids of the epoch record on line ``i`` and the line of its first record."""
    n_lines = len(lines)
    n_cont = max(-(-nsat // 12) - 1, 0)
    if i + n_cont >= n_lines:
        raise acc.fail("truncated epoch: its satellite list is cut short", i)
    ids = b"".join(lines[i + c][32:68].ljust(36) for c in range(n_cont + 1))
    sats = [ids[3 * s : 3 * s + 3].decode("ascii", "replace") for s in range(nsat)]
    first_obs = i + 1 + n_cont
    missing = first_obs + nsat * per_sat - n_lines
    if 0 < missing < per_sat:
        # the file ends inside the last record's continuation lines: blank lines that a
        # decompressor or an editor dropped at the end of the file (CRX2RNX output of IGS
        # files, e.g. york0440.15d); read as blank, and said
        lines.extend([b""] * missing)
        acc.warnings.append(
            f"line {_error_line(acc.header, i)}: the file ends {missing} line(s) into the last "
            f"epoch's last record (satellite {sats[-1].strip()}), where its layout has "
            "continuation lines: trailing blank lines taken as blank observations"
        )
    elif first_obs + nsat * per_sat > n_lines:
        raise acc.fail(
            f"truncated epoch {lines[i][:26].decode('ascii', 'replace').strip()}: it announces "
            f"{nsat} satellites x {per_sat} lines but the file ends",
            i,
        )
    return sats, first_obs


def _v2_records(
    acc: _Collector, lines: list[bytes], sats: list[str], first_obs: int, e: int, lay: _V2Layout
) -> None:
    """Check and keep the records of epoch ``e`` (``lay.per_sat`` lines per satellite)."""
    systems, per_sat, widths, default_sys = acc.systems, lay.per_sat, lay.widths, lay.default_sys
    for s_idx, sat in enumerate(sats):
        sys_ = sat[0] if sat[0] != " " else default_sys
        j = first_obs + s_idx * per_sat
        acc.seen.add(sys_)
        if systems is not None and sys_ not in systems:
            continue
        parts = [lines[j + r] for r in range(per_sat)]
        for r, (part, w) in enumerate(zip(parts, widths, strict=True)):
            if len(part) > w and part[w:].strip():
                raise acc.fail(
                    f"satellite {sys_ + sat[1:]}: characters beyond column {w}, where the "
                    f"header's {lay.n_types} observation types end on this line (observation "
                    "types missing from the header, or columns shifted)",
                    j + r,
                )
        rec = b"".join(p[:80].ljust(80) for p in parts)
        acc.record(sys_, rec, j, e, sys_ + sat[1:].replace(" ", "0"))


def parse_v2(
    body: bytes,
    header: ObsHeader,
    path: Path,
    systems: Collection[str] | None,
    codes_wanted: Collection[str] | None,
) -> Parsed:
    """Parse a RINEX 2.1x data section; return epochs (GPS s), flags, blocks, warnings, systems."""
    lines = _lines(body)
    n_lines = len(lines)
    lay = _v2_layout(header)
    acc = _Collector(header, path, systems)
    i = 0
    while i < n_lines:
        ln = lines[i]
        if not ln.strip():
            i += 1
            continue
        flag, nsat = _epoch_numbers(acc, ln, i, 28, "expected ' yy mm dd hh mm ss.sssssss  f nnn'")
        if flag in (2, 3, 4, 5):
            if i + 1 + nsat > n_lines:
                raise acc.fail(f"truncated event: {nsat} records announced, the file ends", i)
            _event(acc, lines, i, flag, nsat)
            i += 1 + nsat
            continue
        sats, first_obs = _v2_sat_list(acc, lines, i, nsat, lay.per_sat)
        if flag != 6:  # cycle-slip records (6): observation layout, no observations used
            e = acc.epoch(ln, i, flag, _DATE_V2)
            _v2_records(acc, lines, sats, first_obs, e, lay)
        i = first_obs + nsat * lay.per_sat
    return acc.finish(codes_wanted, 0)
