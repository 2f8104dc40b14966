"""Base files for the robustness tests: cut-down copies of the shared station files.

Built once per process in a temporary folder (never in the repository):
30 min of ESBC (RINEX 3, every system), 5 min of UPC1 (RINEX 2, 1 Hz), the
ESBC and UPC navigation files reduced to the records of the first hours, 6 h
of the GRG SP3 file, and 3 h of ESBC (GPS + Galileo) for ``fit``.
"""

from __future__ import annotations

import atexit
import functools
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import ESBC_NAV, ESBC_OBS, ESBC_SP3, UPC1_OBS, UPC_NAV, shared_file

from psdbound.io._source import read_bytes


@dataclass(frozen=True)
class Bases:
    """The base texts (bytes, not shown in reprs) and the folder holding their files."""

    folder: Path
    esbc: bytes = field(repr=False)  # 30 min, RINEX 3.05, all systems
    esbc_fit: bytes = field(repr=False)  # 3 h, GPS + Galileo
    upc: bytes = field(repr=False)  # 5 min, RINEX 2.11, 1 Hz
    esbc_nav: bytes = field(repr=False)  # RINEX 3 mixed navigation, the first hours
    upc_nav: bytes = field(repr=False)  # RINEX 2 GPS navigation
    sp3: bytes = field(repr=False)  # SP3-c, 6 h
    esbc_nav_path: Path
    upc_nav_path: Path


def _cut_obs(raw: bytes, stop: bytes, systems: bytes | None = None) -> bytes:
    end = raw.index(b"\n", raw.index(b"END OF HEADER")) + 1
    head, body = raw[:end], raw[end : raw.index(stop)]
    if systems is None:
        return head + body
    out, keep = [], []
    for ln in body.split(b"\n"):
        if ln[:1] == b">":
            if keep:
                out.append(keep[0][:32] + f"{len(keep) - 1:3d}".encode() + keep[0][35:])
                out += keep[1:]
            keep = [ln]
        elif ln and ln[:1] in systems:
            keep.append(ln)
    if keep:
        out.append(keep[0][:32] + f"{len(keep) - 1:3d}".encode() + keep[0][35:])
        out += keep[1:]
    return head + b"\n".join(out) + b"\n"


def _cut_nav_v3(raw: bytes, keep_first: bytes) -> bytes:
    end = raw.index(b"\n", raw.index(b"END OF HEADER")) + 1
    out, rec = [raw[:end]], []
    for ln in raw[end:].split(b"\n"):
        if ln[:1].strip():
            if rec and keep_first in rec[0][3:20]:
                out.append(b"\n".join(rec) + b"\n")
            rec = [ln]
        elif ln:
            rec.append(ln)
    if rec and keep_first in rec[0][3:20]:
        out.append(b"\n".join(rec) + b"\n")
    return b"".join(out)


def _cut_sp3(raw: bytes, n_epochs: int) -> bytes:
    lines = raw.split(b"\n")
    starts = [i for i, ln in enumerate(lines) if ln[:1] == b"*"]
    lines[0] = lines[0][:32] + f"{n_epochs:7d}".encode() + lines[0][39:]
    return b"\n".join(lines[: starts[n_epochs]] + [b"EOF", b""])


@pytest.fixture(scope="session")
def bases() -> Bases:
    """The base files (built once per process; the tests skip without ../shared/data)."""
    for name in (ESBC_OBS, UPC1_OBS, ESBC_NAV, UPC_NAV, ESBC_SP3):
        shared_file(name)
    return _build()


@functools.cache
def _build() -> Bases:
    folder = Path(tempfile.mkdtemp(prefix="psdbound-fuzz-bases-"))
    atexit.register(shutil.rmtree, folder, True)
    esbc_raw = read_bytes(shared_file(ESBC_OBS))
    upc_raw = read_bytes(shared_file(UPC1_OBS))
    nav_raw = read_bytes(shared_file(ESBC_NAV))
    b = Bases(
        folder=folder,
        esbc=_cut_obs(esbc_raw, b"> 2020 06 25 00 30 "),
        esbc_fit=_cut_obs(esbc_raw, b"> 2020 06 25 03 00 ", systems=b"GE"),
        upc=_cut_obs(upc_raw, b" 10  3 18  5  5  0.0000000"),
        esbc_nav=_cut_nav_v3(nav_raw, b"2020 06 25 0"),
        upc_nav=read_bytes(shared_file(UPC_NAV)),
        sp3=_cut_sp3(read_bytes(shared_file(ESBC_SP3)), 24),
        esbc_nav_path=folder / "esbc_nav.rnx",
        upc_nav_path=folder / "upc_nav.10n",
    )
    b.esbc_nav_path.write_bytes(b.esbc_nav)
    b.upc_nav_path.write_bytes(b.upc_nav)
    return b
