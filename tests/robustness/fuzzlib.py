"""Seeded mutations of RINEX/SP3 text and the checks every CLI run must pass.

Each mutation takes the plain text of a file (bytes) and a
``numpy.random.Generator`` and returns the mutated bytes and a short
description. Structure-aware mutations find header records, epoch lines and
satellite records first, so that they hit what a reader must check (the
observation-type list, epoch dates and order, column alignment) rather than
only random bytes.
"""

from __future__ import annotations

import contextlib
import gzip
import io
import math
import re
import signal
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

Mutation = Callable[[bytes, np.random.Generator], tuple[bytes, str]]

# --------------------------------------------------------------------- structure


def split_header(data: bytes) -> tuple[list[bytes], list[bytes]]:
    """Header lines (with END OF HEADER) and body lines, without newlines."""
    lines = data.split(b"\n")
    end = next(i for i, ln in enumerate(lines) if b"END OF HEADER" in ln)
    return lines[: end + 1], lines[end + 1 :]


def join(header: list[bytes], body: list[bytes]) -> bytes:
    return b"\n".join(header + body)


def epoch_starts(body: list[bytes], v3: bool) -> list[int]:
    """Indices of the epoch lines of a data section."""
    if v3:
        return [i for i, ln in enumerate(body) if ln[:1] == b">"]
    pat = re.compile(rb"^ [ \d]\d [ \d]\d [ \d]\d [ \d]\d [ \d]\d [ \d]\d\.\d{7}  \d")
    return [i for i, ln in enumerate(body) if pat.match(ln)]


def epoch_blocks(body: list[bytes], v3: bool) -> list[tuple[int, int]]:
    starts = epoch_starts(body, v3)
    ends = starts[1:] + [len(body) if body[-1:] != [b""] else len(body) - 1]
    return list(zip(starts, ends, strict=True))


def record_lines(body: list[bytes], v3: bool) -> list[int]:
    starts = set(epoch_starts(body, v3))
    return [i for i, ln in enumerate(body) if ln.strip() and i not in starts]


def is_v3(data: bytes) -> bool:
    return data[:9].strip().startswith(b"3")


# --------------------------------------------------------------------- generic mutations

_BYTES = [
    b"0",
    b"9",
    b"5",
    b" ",
    b".",
    b"-",
    b"A",
    b"x",
    b"\x00",
    b"\xff",
    "é".encode(),
    b"\t",
    b"+",
    b"e",
    b"D",
    b"*",
    b">",
    b"\n",
]


def byte_flip(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    n = int(rng.integers(1, 4))
    out = bytearray(data)
    for _ in range(n):
        k = int(rng.integers(0, len(out)))
        out[k : k + 1] = _BYTES[int(rng.integers(0, len(_BYTES)))]
    return bytes(out), f"{n} byte(s) replaced"


def truncate(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    k = int(rng.integers(1, len(data)))
    return data[:k], f"truncated at byte {k}"


def crlf(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    if rng.random() < 0.5:
        return data.replace(b"\n", b"\r\n"), "CRLF line ends"
    k = int(rng.integers(0, len(data)))
    return data[:k] + data[k:].replace(b"\n", b"\r\n"), "CRLF from the middle on"


def non_ascii(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    token = [b"\xc3\xa9", b"\xe2\x82\xac", b"\xff\xfe", b"\x00", b"\x85", "Å".encode()][
        int(rng.integers(0, 6))
    ]
    k = int(rng.integers(0, len(data)))
    if rng.random() < 0.5:
        return data[:k] + token + data[k + len(token) :], "non-ASCII byte(s) replacing text"
    return data[:k] + token + data[k:], "non-ASCII byte(s) inserted"


# --------------------------------------------------------------------- observation files

_BAD_NUMBERS = [b"nan", b"inf", b"-30", b"1e30", b"abc", b"", b"0", b"-inf", b"99999999"]


def header_field(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    k = int(rng.integers(1, len(header) - 1))
    ln = header[k]
    label = ln[60:].strip().decode("ascii", "replace")
    token = _BAD_NUMBERS[int(rng.integers(0, len(_BAD_NUMBERS)))]
    a = int(rng.integers(0, 50))
    b = a + int(rng.integers(1, 12))
    new = (ln[:a] + token.rjust(b - a)[: max(b - a, len(token))] + ln[b:])[:60].ljust(60)
    header[k] = new + ln[60:]
    return join(header, body), f"header {label!r} columns {a + 1}-{b} -> {token!r}"


def interval(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    value = [b"nan", b"inf", b"-30", b"1e30", b"0", b"15", b"abc"][int(rng.integers(0, 7))]
    line = value.rjust(10).ljust(60) + b"INTERVAL"
    ks = [i for i, ln in enumerate(header) if ln[60:].strip() == b"INTERVAL"]
    if ks:
        header[ks[0]] = line
    else:
        header.insert(len(header) - 1, line)
    return join(header, body), f"INTERVAL {value.decode()}"


def obs_types(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """Blank, delete, insert or duplicate a code of an observation-type list; or its count."""
    header, body = split_header(data)
    v3 = is_v3(data)
    label = b"SYS / # / OBS TYPES" if v3 else b"# / TYPES OF OBSERV"
    ks = [i for i, ln in enumerate(header) if ln[60:].strip() == label]
    k = ks[int(rng.integers(0, len(ks)))]
    ln = header[k]
    slot0, width, size = (7, 4, 3) if v3 else (10, 6, 2)
    codes = [ln[slot0 + width * j : slot0 + width * j + size] for j in range(13 if v3 else 9)]
    n = sum(1 for c in codes if c.strip())
    j = int(rng.integers(0, max(n, 1)))
    a = slot0 + width * j
    what = ["blank", "delete", "insert", "count", "duplicate"][int(rng.integers(0, 5))]
    body60 = bytearray(ln[:60].ljust(60))
    if what == "blank":
        body60[a : a + size] = b" " * size
    elif what == "delete":
        rest = bytes(body60[a + width : 60]) + b" " * width
        body60[a:60] = rest[: 60 - a]
    elif what == "insert":
        new = (b"C1X" if v3 else b"C2").rjust(width)
        body60[a - (width - size) : 60] = (new + bytes(body60[a - (width - size) : 60]))[
            : 60 - a + (width - size)
        ]
    elif what == "duplicate" and j > 0:
        body60[a : a + size] = body60[a - width : a - width + size]
    else:
        cnt = body60[3:6] if v3 else body60[0:6]
        if cnt.strip():
            val = int(cnt) + int(rng.choice([-1, 1]))
            if v3:
                body60[3:6] = f"{val:3d}".encode()
            else:
                body60[0:6] = f"{val:6d}".encode()
    header[k] = bytes(body60) + ln[60:]
    return join(header, body), f"observation types: {what} code {j + 1} on header line {k + 1}"


def epoch_order(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """Swap two epochs, move one, or repeat one (same or different data)."""
    header, body = split_header(data)
    blocks = epoch_blocks(body, is_v3(data))
    if len(blocks) < 3:
        return data, "too few epochs"
    i, j = sorted(int(x) for x in rng.choice(len(blocks), 2, replace=False))
    chunks = [body[a:b] for a, b in blocks]
    tail = body[blocks[-1][1] :]
    what = ["swap", "repeat", "repeat-changed", "move"][int(rng.integers(0, 4))]
    if what == "swap":
        chunks[i], chunks[j] = chunks[j], chunks[i]
    elif what == "move":
        chunks.insert(j, chunks.pop(i))
    else:
        rep = list(chunks[i])
        if what == "repeat-changed" and len(rep) > 1:
            r = int(rng.integers(1, len(rep)))
            rep[r] = re.sub(rb"(\d)\.(\d)", rb"\2.\1", rep[r], count=1)
        chunks.insert(i + 1, rep)
    return join(header, [x for c in chunks for x in c] + tail), f"epochs: {what} {i}, {j}"


_DATE_FIELDS_V3 = {
    "year": (2, 6),
    "month": (7, 9),
    "day": (10, 12),
    "hour": (13, 15),
    "minute": (16, 18),
    "second": (18, 29),
}
_DATE_FIELDS_V2 = {
    "year": (1, 3),
    "month": (4, 6),
    "day": (7, 9),
    "hour": (10, 12),
    "minute": (13, 15),
    "second": (15, 26),
}
_BAD_DATES = {
    "year": [b"9999", b"1900", b"2021", b"99"],
    "month": [b"13", b" 0", b"12"],
    "day": [b"32", b" 0", b"31"],
    "hour": [b"25", b"24", b"23"],
    "minute": [b"60", b"61"],
    "second": [b"nan", b"1e30", b"99.0000000", b"-1.0000000", b"inf", b"60.0000000"],
}


def epoch_date(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    v3 = is_v3(data)
    starts = epoch_starts(body, v3)
    k = starts[int(rng.integers(0, len(starts)))]
    fields = _DATE_FIELDS_V3 if v3 else _DATE_FIELDS_V2
    name = list(fields)[int(rng.integers(0, len(fields)))]
    a, b = fields[name]
    opts = _BAD_DATES[name]
    token = opts[int(rng.integers(0, len(opts)))]
    if not v3 and name == "year":
        token = token[-2:]
    ln = body[k]
    body[k] = ln[:a] + token.rjust(b - a)[-(b - a) :] + ln[b:]
    return join(header, body), f"epoch line {k}: {name} -> {token!r}"


def column_shift(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """Insert or delete characters in one record line, or in every record of a system."""
    header, body = split_header(data)
    recs = record_lines(body, is_v3(data))
    n = int(rng.integers(1, 21))
    col = int(rng.integers(3, 80))
    delete = rng.random() < 0.5
    if rng.random() < 0.3 and is_v3(data):
        sys_ = body[recs[int(rng.integers(0, len(recs)))]][:1]
        targets = [r for r in recs if body[r][:1] == sys_]
        where = f"every {sys_.decode()} record"
    else:
        targets = [recs[int(rng.integers(0, len(recs)))]]
        where = f"record line {targets[0]}"
    for r in targets:
        ln = body[r]
        body[r] = ln[:col] + ln[col + n :] if delete else ln[:col] + b" " * n + ln[col:]
    what = "deleted" if delete else "inserted"
    return join(header, body), f"{what} {n} chars at {col} in {where}"


def satellite_id(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    v3 = is_v3(data)
    token = [b"G99", b"G00", b"X01", b"G 0", b"GAB", b"E77", b"  1"][int(rng.integers(0, 7))]
    if v3:
        recs = record_lines(body, v3)
        r = recs[int(rng.integers(0, len(recs)))]
        body[r] = token + body[r][3:]
    else:
        starts = epoch_starts(body, v3)
        k = starts[int(rng.integers(0, len(starts)))]
        body[k] = body[k][:32] + token + body[k][35:]
    return join(header, body), f"satellite id -> {token!r}"


def value_token(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    """Replace one observation value by a non-F14.3 token."""
    header, body = split_header(data)
    v3 = is_v3(data)
    recs = record_lines(body, v3)
    r = recs[int(rng.integers(0, len(recs)))]
    off = 3 if v3 else 0
    n = max((len(body[r]) - off) // 16, 1)
    f = int(rng.integers(0, n))
    token = [
        b"nan",
        b"inf",
        b"1e30",
        b"1.0D+05",
        b"-----",
        b"12 34.567",
        b"0x10",
        b"1234567890123.4",
    ][int(rng.integers(0, 8))]
    a = off + 16 * f
    ln = body[r].ljust(a + 16)
    body[r] = ln[:a] + token.rjust(14)[-14:] + ln[a + 14 :]
    return join(header, body), f"value {f + 1} of record line {r} -> {token!r}"


OBS_MUTATIONS: dict[str, Mutation] = {
    "byte_flip": byte_flip,
    "truncate": truncate,
    "crlf": crlf,
    "non_ascii": non_ascii,
    "header_field": header_field,
    "interval": interval,
    "obs_types": obs_types,
    "epoch_order": epoch_order,
    "epoch_date": epoch_date,
    "column_shift": column_shift,
    "satellite_id": satellite_id,
    "value_token": value_token,
}


# --------------------------------------------------------------------- navigation / SP3

_NAV_TOKENS = [b"nan", b"inf", b"-inf", b"1.0D+999", b"NaN", b"       ", b"1.5e+400"]


def nav_value(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    rows = [i for i, ln in enumerate(body) if ln[:4].strip() == b"" and len(ln) > 40]
    r = rows[int(rng.integers(0, len(rows)))]
    token = _NAV_TOKENS[int(rng.integers(0, len(_NAV_TOKENS)))]
    start = 4 if is_v3(data) else 3
    f = int(rng.integers(0, 4))
    a = start + 19 * f
    ln = body[r].ljust(a + 19)
    body[r] = ln[:a] + token.rjust(19) + ln[a + 19 :]
    return join(header, body), f"nav value {f + 1} of line {r} -> {token!r}"


def nav_epoch(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    header, body = split_header(data)
    v3 = is_v3(data)
    rows = [i for i, ln in enumerate(body) if ln[:1].strip() and len(ln) > 22]
    r = rows[int(rng.integers(0, len(rows)))]
    ln = body[r]
    what = int(rng.integers(0, 5))
    if v3:
        spans = [(0, 3), (8, 11), (11, 14), (14, 17), (20, 23)]
        toks = [b"G99", b" 13", b" 32", b" 25", b"nan"]
    else:
        spans = [(0, 2), (5, 8), (8, 11), (11, 14), (17, 22)]
        toks = [b"99", b" 13", b" 32", b" 25", b"  nan"]
    a, b = spans[what]
    body[r] = ln[:a] + toks[what].rjust(b - a) + ln[b:]
    return join(header, body), f"nav epoch line {r}: {toks[what]!r}"


NAV_MUTATIONS: dict[str, Mutation] = {
    "byte_flip": byte_flip,
    "truncate": truncate,
    "crlf": crlf,
    "non_ascii": non_ascii,
    "nav_value": nav_value,
    "nav_epoch": nav_epoch,
}


def sp3_value(data: bytes, rng: np.random.Generator) -> tuple[bytes, str]:
    lines = data.split(b"\n")
    rows = [i for i, ln in enumerate(lines) if ln[:1] in (b"P", b"*")]
    r = rows[int(rng.integers(0, len(rows)))]
    ln = lines[r]
    if ln[:1] == b"*":
        a, b, tok = [(8, 10, b"13"), (11, 13, b"32"), (14, 16, b"25"), (20, 31, b"nan")][
            int(rng.integers(0, 4))
        ]
    else:
        q = int(rng.integers(0, 4))
        a, b = 4 + 14 * q, 18 + 14 * q
        tok = [b"nan", b"inf", b"1e400", b"abc"][int(rng.integers(0, 4))]
    lines[r] = ln[:a] + tok.rjust(b - a) + ln[b:]
    return b"\n".join(lines), f"SP3 line {r} columns {a + 1}-{b} -> {tok!r}"


SP3_MUTATIONS: dict[str, Mutation] = {
    "byte_flip": byte_flip,
    "truncate": truncate,
    "crlf": crlf,
    "sp3_value": sp3_value,
}


# --------------------------------------------------------------------- containers


def container(data: bytes, kind: str, rng: np.random.Generator | None = None) -> bytes:
    """Wrap plain text as ``plain``, ``gz``, ``crx``, ``crx.gz``, or a damaged ``bad.gz``."""
    if kind == "plain":
        return data
    if kind == "gz":
        return gzip.compress(data, mtime=0)
    if kind in ("crx", "crx.gz"):
        import hatanaka

        out = hatanaka.rnx2crx(data)
        return gzip.compress(out, mtime=0) if kind == "crx.gz" else out
    if kind == "bad.gz":
        z = bytearray(gzip.compress(data, mtime=0))
        rng = rng or np.random.default_rng(0)
        k = int(rng.integers(10, len(z) - 8))
        z[k : k + 4] = b"\x00\xff\x13\x37"
        return bytes(z)
    if kind == "cut.gz":
        z = gzip.compress(data, mtime=0)
        return z[: len(z) // 2]
    raise ValueError(kind)


def split_obs(data: bytes, at: bytes) -> tuple[bytes, bytes]:
    """Two observation files of one station: the epochs before the epoch line ``at``, and from it.

    Both keep the whole header (its ``TIME OF FIRST OBS`` precedes the second
    file's epochs, which a reader accepts).
    """
    end = data.index(b"\n", data.index(b"END OF HEADER")) + 1
    head, body = data[:end], data[end:]
    k = body.index(at)
    return head + body[:k], head + body[k:]


def zip_of(members: dict[str, bytes]) -> bytes:
    """A zip archive (deflated) of named members."""
    import zipfile

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in members.items():
            z.writestr(name, data)
    return buf.getvalue()


# --------------------------------------------------------------------- running the CLI


@dataclass
class Run:
    code: int
    out: str
    err: str
    warnings: list[str]


class _Timeout(Exception):
    pass


def run_cli(args: list[str], timeout_s: int = 60) -> Run:
    """Run ``psdbound`` in-process with captured output; numpy/astropy warnings become errors.

    A run longer than ``timeout_s`` raises ``AssertionError`` (a hang).
    """
    from psdbound.cli.main import main

    def on_alarm(signum, frame):  # noqa: ARG001
        raise _Timeout

    out, err = io.StringIO(), io.StringIO()
    old = signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(timeout_s)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("default")
            warnings.simplefilter("error", RuntimeWarning)
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main([str(a) for a in args])
    except _Timeout:
        raise AssertionError(
            f"psdbound {' '.join(map(str, args))}: no answer in {timeout_s} s"
        ) from None
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    return Run(code, out.getvalue(), err.getvalue(), [str(w.message) for w in caught])


def check_run(r: Run, name: str, allowed: tuple[int, ...] = (0, 2, 3)) -> str | None:
    """Return what is wrong with a run (None when it is fine)."""
    if r.code not in allowed:
        return f"exit {r.code}: {r.err.strip()[-400:]}"
    if "Traceback" in r.err:
        return "traceback on stderr"
    if "RuntimeWarning" in r.err or any("RuntimeWarning" in w for w in r.warnings):
        return "numpy RuntimeWarning leaked"
    if r.code == 2:
        lines = r.err.strip().splitlines()
        if len(lines) != 1:
            return f"{len(lines)} lines on stderr for a bad input: {r.err.strip()[:400]}"
        if name not in lines[0]:
            return f"the error does not name the file {name}: {lines[0]}"
    return None


def inspect_sane(out: str) -> str | None:
    """For ``inspect`` exit 0: the interval and span it prints are physical numbers."""
    for m in re.finditer(r"span (\S+) h, interval (\S+) s", out):
        span, dt = float(m.group(1)), float(m.group(2))
        if not (math.isfinite(span) and span >= 0 and math.isfinite(dt) and 0 < dt <= 3600):
            return f"span {span} h, interval {dt} s"
    return None


#: Carrier-multipath limit of the L1/L2 DF series (quarter wavelengths / sqrt 2), m
DF_LIMIT_M = 0.077


def bound_sane(result: dict) -> str | None:
    """For a written result: the bound is physical and documented numbers are numbers."""
    b = result["bound"]
    for key in ("sigma_gm_m", "tau_s", "sigma_wn_m", "n_wn_two_sided_m2_hz"):
        v = b[key]
        if not isinstance(v, int | float) or not math.isfinite(v):
            return f"bound.{key} = {v!r}"
    if not 0 <= b["sigma_gm_m"] <= DF_LIMIT_M:
        return f"sigma_GM = {b['sigma_gm_m']} m beyond the carrier-multipath limit"
    if not b["tau_s"] > 0:
        return f"tau = {b['tau_s']} s"
    s = result["sampling"]
    if not (s["interval_s"] > 0 and math.isfinite(s["nyquist_hz"]) and s["nyquist_hz"] > 0):
        return f"sampling {s}"
    return None


def write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path
