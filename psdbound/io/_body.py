"""RINEX observation data sections (versions 2.1x and 3.0x) -> arrays."""

from __future__ import annotations

from collections.abc import Collection
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from psdbound.errors import InputError
from psdbound.io._fields import FIELD_WIDTH, FieldError, pad_lines, parse_fields
from psdbound.io._header import ObsHeader
from psdbound.io.timescales import calendar_to_gps_s, utc_to_gps_s


@dataclass
class RawBlock:
    system: str
    sats: tuple[str, ...]
    codes: tuple[str, ...]
    values: np.ndarray
    lli: np.ndarray
    ssi: np.ndarray


def _epoch_times(fields: list[tuple], header: ObsHeader) -> np.ndarray:
    if not fields:
        return np.zeros(0)
    y, mo, d, h, mi, s = (np.array(c) for c in zip(*fields, strict=True))
    t = calendar_to_gps_s(y, mo, d, h, mi, s)
    ts = header.time_system.upper()
    if ts in ("GPS", "GAL", "QZS", "IRN", ""):
        return t
    if ts == "BDT":
        return t + 14.0
    if ts == "GLO":
        return utc_to_gps_s(t - 3 * 3600.0)
    if ts == "UTC":
        return utc_to_gps_s(t)
    raise InputError(f"unknown time system {header.time_system!r} in TIME OF FIRST OBS")


def _error_line(header: ObsHeader, idx: int) -> int:
    return header.n_lines + idx + 1


def _build_blocks(
    sat_lines: dict[str, list[int]],
    epoch_of_line: dict[str, list[int]],
    records: dict[str, list[bytes]],
    sat_of_line: dict[str, list[str]],
    header: ObsHeader,
    path: Path,
    n_epoch: int,
    codes_wanted: Collection[str] | None,
    offset: int,
) -> dict[str, RawBlock]:
    blocks = {}
    for system, recs in records.items():
        types = header.obs_types.get(system)
        if types is None:
            first = sat_lines[system][0]
            raise InputError(
                f"satellite {sat_of_line[system][0]} has no observation types in the header",
                path=path,
                line=_error_line(header, first),
            )
        if codes_wanted is None:
            cols = list(range(len(types)))
        else:
            cols = [k for k, c in enumerate(types) if c in codes_wanted]
        if not cols:
            continue
        n_types = len(types)
        width = offset + FIELD_WIDTH * n_types
        chars = pad_lines(recs, width)[:, offset:].reshape(len(recs), n_types, FIELD_WIDTH)
        chars = chars[:, cols, :]
        try:
            values, lli, ssi = parse_fields(chars)
        except FieldError as exc:
            raise InputError(
                f"satellite {sat_of_line[system][exc.row]}, observation "
                f"{types[cols[exc.field]]}: {exc.text!r} is not an F14.3 number "
                "(line cut short or columns shifted?)",
                path=path,
                line=_error_line(header, sat_lines[system][exc.row]),
            ) from None
        sats, sat_idx = np.unique(np.array(sat_of_line[system]), return_inverse=True)
        ep = np.asarray(epoch_of_line[system])
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


_V3_DATE = ((2, 6), (7, 9), (10, 12), (13, 15), (16, 18), (18, 29))
_V2_DATE = ((1, 3), (4, 6), (7, 9), (10, 12), (13, 15), (15, 26))


class _Collector:
    """Gathers epochs and satellite records while a data section is scanned."""

    def __init__(self, header: ObsHeader, path: Path, systems: Collection[str] | None) -> None:
        self.header, self.path, self.systems = header, path, systems
        self.times: list[tuple] = []
        self.flags: list[int] = []
        self.records: dict[str, list[bytes]] = {}
        self.line_of: dict[str, list[int]] = {}
        self.epoch_of: dict[str, list[int]] = {}
        self.sat_of: dict[str, list[str]] = {}

    def epoch(self, ln: bytes, i: int, flag: int, cols: tuple[tuple[int, int], ...]) -> int:
        """Record an epoch's date and flag; return its index."""
        try:
            date = tuple(int(ln[a:b]) for a, b in cols[:5]) + (float(ln[cols[5][0] : cols[5][1]]),)
        except ValueError:
            raise InputError(
                f"bad epoch date {ln[: cols[5][1]].decode('ascii', 'replace')!r}",
                path=self.path,
                line=_error_line(self.header, i),
            ) from None
        self.times.append(date)
        self.flags.append(flag)
        return len(self.flags) - 1

    def record(self, sys_: str, rec: bytes, j: int, e: int, sat: str) -> None:
        """Keep one satellite record (line ``j``, epoch ``e``) if its system is wanted."""
        if self.systems is not None and sys_ not in self.systems:
            return
        if sys_ not in self.records:
            self.records[sys_], self.line_of[sys_] = [], []
            self.epoch_of[sys_], self.sat_of[sys_] = [], []
        self.records[sys_].append(rec)
        self.line_of[sys_].append(j)
        self.epoch_of[sys_].append(e)
        self.sat_of[sys_].append(sat)

    def finish(
        self, codes_wanted: Collection[str] | None, offset: int
    ) -> tuple[np.ndarray, np.ndarray, dict[str, RawBlock]]:
        """Return epochs (GPS s), epoch flags and the per-system blocks."""
        t = _epoch_times(self.times, self.header)
        blocks = _build_blocks(
            self.line_of, self.epoch_of, self.records, self.sat_of, self.header, self.path,
            len(self.flags), codes_wanted, offset,
        )  # fmt: skip
        return t, np.asarray(self.flags, dtype=np.int8), blocks


def parse_v3(
    body: bytes,
    header: ObsHeader,
    path: Path,
    systems: Collection[str] | None,
    codes_wanted: Collection[str] | None,
) -> tuple[np.ndarray, np.ndarray, dict[str, RawBlock]]:
    """Parse a RINEX 3 data section; return epochs (GPS s), epoch flags, blocks."""
    lines = body.split(b"\n")
    if lines and not lines[-1]:
        lines.pop()
    n_lines = len(lines)
    starts = [i for i, ln in enumerate(lines) if ln[:1] == b">"]
    if lines and (not starts or starts[0] != 0):
        raise InputError(
            "expected an epoch record starting with '>' after the header, found "
            f"{lines[0][:40].decode('ascii', 'replace')!r}",
            path=path,
            line=_error_line(header, 0),
        )
    acc = _Collector(header, path, systems)
    starts.append(n_lines)
    for k in range(len(starts) - 1):
        i, nxt = starts[k], starts[k + 1]
        ln = lines[i]
        try:
            flag = int(ln[31:32] or b"0")
            nsat = int(ln[32:35])
        except ValueError:
            raise InputError(
                f"bad epoch record {ln[:35].decode('ascii', 'replace')!r}",
                path=path,
                line=_error_line(header, i),
            ) from None
        if i + 1 + nsat > nxt:
            where = "the file ends" if nxt == n_lines else "the next epoch starts"
            raise InputError(
                f"truncated epoch {ln[2:29].decode('ascii', 'replace').strip()}: it announces "
                f"{nsat} satellite records but {where} after {nxt - i - 1}",
                path=path,
                line=_error_line(header, i),
            )
        if flag > 1:
            continue  # event records (2-5) and cycle-slip records (6) carry no observations
        e = acc.epoch(ln, i, flag, _V3_DATE)
        for j in range(i + 1, i + 1 + nsat):
            rec = lines[j]
            sys_ = chr(rec[0]) if rec else " "
            acc.record(sys_, rec, j, e, rec[:3].decode("ascii", "replace").replace(" ", "0"))
    return acc.finish(codes_wanted, 3)


def parse_v2(
    body: bytes,
    header: ObsHeader,
    path: Path,
    systems: Collection[str] | None,
    codes_wanted: Collection[str] | None,
) -> tuple[np.ndarray, np.ndarray, dict[str, RawBlock]]:
    """Parse a RINEX 2.1x data section; return epochs (GPS s), epoch flags, blocks."""
    lines = body.split(b"\n")
    if lines and not lines[-1]:
        lines.pop()
    n_lines = len(lines)
    n_types = len(next(iter(header.obs_types.values())))
    per_sat = -(-n_types // 5)
    default_sys = header.file_system if header.file_system != "M" else "G"
    acc = _Collector(header, path, systems)
    i = 0
    while i < n_lines:
        ln = lines[i]
        if not ln.strip():
            i += 1
            continue
        try:
            flag = int(ln[28:29] or b"0")
            nsat = int(ln[29:32])
        except ValueError:
            raise InputError(
                f"bad epoch record {ln[:32].decode('ascii', 'replace')!r} "
                "(expected ' yy mm dd hh mm ss.sssssss  f nnn')",
                path=path,
                line=_error_line(header, i),
            ) from None
        if flag > 1:
            i += 1 + nsat
            continue
        n_cont = -(-nsat // 12) - 1
        ids = b"".join(lines[i + c][32:68].ljust(36) for c in range(n_cont + 1))
        sats = [ids[3 * s : 3 * s + 3].decode("ascii", "replace") for s in range(nsat)]
        first_obs = i + 1 + n_cont
        if first_obs + nsat * per_sat > n_lines:
            raise InputError(
                f"truncated epoch {ln[:26].decode('ascii', 'replace').strip()}: it announces "
                f"{nsat} satellites x {per_sat} lines but the file ends",
                path=path,
                line=_error_line(header, i),
            )
        e = acc.epoch(ln, i, flag, _V2_DATE)
        for s_idx, sat in enumerate(sats):
            sys_ = sat[0] if sat[0] != " " else default_sys
            j = first_obs + s_idx * per_sat
            if systems is not None and sys_ not in systems:
                continue
            rec = b"".join(lines[j + r][:80].ljust(80) for r in range(per_sat))
            acc.record(sys_, rec, j, e, sys_ + sat[1:].replace(" ", "0"))
        i = first_obs + nsat * per_sat
    return acc.finish(codes_wanted, 0)
