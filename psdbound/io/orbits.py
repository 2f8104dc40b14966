"""One front for satellite orbits: broadcast navigation or SP3 precise orbits.

Several files (e.g. the navigation files of consecutive days, given as a list
or inside one zip archive) are read and joined into one orbit: broadcast
records by :func:`~psdbound.io.navigation.merge_navigation`, SP3 epochs by
:func:`~psdbound.io.sp3.merge_precise`. Broadcast and SP3 files are not mixed.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

from psdbound.errors import InputError
from psdbound.io._source import read_bytes
from psdbound.io.archive import extract_zip, file_kind, member_label, relabel, zip_members
from psdbound.io.nav import Navigation, read_nav
from psdbound.io.navigation import merge_navigation
from psdbound.io.sp3 import PreciseOrbit, merge_precise, read_sp3

__all__ = ["read_orbit"]

Orbit = Navigation | PreciseOrbit
PathLike = str | os.PathLike[str]


def _read_one(path: Path, label: str | None = None) -> Orbit:
    """Read one orbit file; ``label`` names it in messages and in ``path`` (archive members)."""
    try:
        is_sp3 = read_bytes(path)[:2] in (b"#c", b"#d", b"#a", b"#b")
        orbit: Orbit = read_sp3(path) if is_sp3 else read_nav(path)
    except InputError as exc:
        raise (relabel(exc, label) if label else exc) from None
    return orbit if label is None else replace(orbit, path=Path(label))


def _orbit_members(members: list[Path]) -> list[Path]:
    """Return the orbit members of an archive (all when none is surely an orbit file).

    A station's download may hold its observations with its navigation file:
    the observation members are then left to the observation reader.
    """
    kinds = [file_kind(m) for m in members]
    orbits = [m for m, k in zip(members, kinds, strict=True) if k in ("nav", "sp3")]
    return orbits or members


def _read_all(paths: Sequence[Path]) -> list[Orbit]:
    """Read every file, and the orbit members of a zip archive of several files."""
    out: list[Orbit] = []
    for p in paths:
        if len(zip_members(p)) <= 1:
            out.append(_read_one(p))
            continue
        with tempfile.TemporaryDirectory(prefix="psdbound-zip-") as tmp:
            members = _orbit_members(extract_zip(p, tmp))
            out += [_read_one(m, member_label(p, m)) for m in members]
    return out


def _join(orbits: list[Orbit]) -> Orbit:
    """One orbit of several files of one kind."""
    name = " + ".join(Path(o.path).name for o in orbits)
    sp3 = [o for o in orbits if isinstance(o, PreciseOrbit)]
    if not sp3:
        return merge_navigation(orbits, name)  # type: ignore[arg-type]
    if len(sp3) == len(orbits):
        return merge_precise(sp3, name)
    nav = ", ".join(Path(o.path).name for o in orbits if not isinstance(o, PreciseOrbit))
    raise InputError(
        f"the orbit files mix broadcast navigation ({nav}) and SP3 precise orbits "
        f"({', '.join(Path(o.path).name for o in sp3)}): give files of one kind"
    )


def read_orbit(path: PathLike | Sequence[PathLike]) -> Orbit:
    """Read orbit files: RINEX navigation (2/3) or SP3-c/d, detected from content.

    Parameters
    ----------
    path : str or path-like, or a sequence of them
        Navigation or SP3 file(s), plain or compressed; a zip archive may hold
        several (its observation files, if any, are left out). Several files
        are joined into one orbit (navigation files: every record; SP3 files
        of one epoch interval: every epoch).

    Returns
    -------
    Navigation or PreciseOrbit
        Both provide ``positions_ecef_m(sat, t_gps_s)`` and ``satellites``.

    Raises
    ------
    InputError
        A file that cannot be read (named, an archive member as
        ``archive.zip:member``), or navigation and SP3 files together.

    See Also
    --------
    read_obs : The observations the orbits serve.
    psdbound.io.orbit_coverage : Whether the orbits cover the observed systems and epochs.

    References
    ----------
    .. [1] IS-GPS-200 (Navstar GPS Space Segment / Navigation User Interfaces),
       Table 20-IV (broadcast ephemeris to ECEF).
    .. [2] Hilla, S. (2016). The Extended Standard Product 3 Orbit Format (SP3-d).
    .. [3] GLONASS ICD, edition 5.1 (2008), appendix A.3.1.2 (numerical integration).

    Examples
    --------
    >>> from psdbound.simulate import demo_data
    >>> nav = read_orbit(demo_data().nav_path)
    >>> type(nav).__name__
    'Navigation'
    """
    many = not isinstance(path, str | os.PathLike)
    paths = [Path(p) for p in path] if many else [Path(path)]  # type: ignore[union-attr]
    if not paths:
        raise InputError("no orbit file given: expected a navigation or SP3 file")
    orbits = _read_all(paths)
    return orbits[0] if len(orbits) == 1 else _join(orbits)
