"""One front for satellite orbits: broadcast navigation or SP3 precise orbits."""

from __future__ import annotations

import gzip
import os
from pathlib import Path

from psdbound.errors import InputError
from psdbound.io.nav import Navigation, read_nav
from psdbound.io.sp3 import PreciseOrbit, read_sp3

__all__ = ["read_orbit"]


def _peek(p: Path, n: int = 80) -> bytes:
    if not p.is_file():
        raise InputError("file not found", path=p)
    with open(p, "rb") as fh:
        head = fh.read(4)
    opener = gzip.open if head[:2] == b"\x1f\x8b" else open
    try:
        with opener(p, "rb") as fh:
            return fh.read(n)
    except (OSError, EOFError) as exc:
        raise InputError(f"cannot decompress: {exc}", path=p) from exc


def read_orbit(path: str | os.PathLike[str]) -> Navigation | PreciseOrbit:
    """Read an orbit file: RINEX navigation (2/3) or SP3-c/d, detected from content.

    Parameters
    ----------
    path : str or path-like
        Navigation or SP3 file, plain or compressed.

    Returns
    -------
    Navigation or PreciseOrbit
        Both provide ``positions_ecef_m(sat, t_gps_s)`` and ``satellites``.
    """
    p = Path(path)
    if _peek(p)[:2] in (b"#c", b"#d", b"#a", b"#b"):
        return read_sp3(p)
    return read_nav(p)
