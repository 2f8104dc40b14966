"""Zip archives that hold several files (a day of hourly files, a station's obs + nav).

:func:`zip_members` lists an archive, :func:`extract_zip` unpacks it,
:func:`file_kind` tells an observation file from a navigation or SP3 file by
its first line (also inside gzip/bz2, and Hatanaka-compressed observations),
and :func:`relabel` names an archive member as ``archive.zip:member`` in an
error raised while reading the extracted copy.
"""

from __future__ import annotations

import bz2
import gzip
import os
import zipfile
from pathlib import Path

from psdbound.common.compression import compression_of
from psdbound.errors import InputError

__all__ = ["zip_members", "extract_zip", "file_kind", "member_label", "relabel"]

#: RINEX file types (column 21 of the first line) of navigation files (N; RINEX 2: G GLONASS, H
#: SBAS, L Galileo)
_NAV_TYPES = "NGHL"


def zip_members(path: str | os.PathLike[str]) -> list[str]:
    """Return the file members of a zip archive (empty when ``path`` is not a zip).

    Parameters
    ----------
    path : path

    Returns
    -------
    list of str
        Member names in archive order, folders left out.
    """
    p = Path(path)
    if not p.is_file() or not zipfile.is_zipfile(p):
        return []
    try:
        with zipfile.ZipFile(p) as z:
            return [i.filename for i in z.infolist() if not i.is_dir()]
    except zipfile.BadZipFile as exc:
        raise InputError(f"damaged zip archive: {exc}", path=p) from None


def extract_zip(path: str | os.PathLike[str], dest: str | os.PathLike[str]) -> list[Path]:
    """Extract every file member of a zip archive into a folder (flat, names kept).

    Parameters
    ----------
    path : path
        The archive.
    dest : path
        An existing, empty folder (e.g. a temporary one).

    Returns
    -------
    list of Path
        The extracted files, in archive order.

    Raises
    ------
    InputError
        A damaged archive, or two members with the same file name.
    """
    p, out = Path(path), Path(dest)
    names = zip_members(p)
    files = []
    seen: set[str] = set()
    try:
        with zipfile.ZipFile(p) as z:
            for name in names:
                base = Path(name).name
                if base in seen:
                    raise InputError(f"two members named {base!r} in the archive", path=p)
                seen.add(base)
                target = out / base
                target.write_bytes(z.read(name))
                files.append(target)
    except zipfile.BadZipFile as exc:
        raise InputError(f"damaged zip archive: {exc}", path=p) from None
    return files


def _head(path: Path, size: int = 200) -> bytes:
    """Return the first bytes of a file's decompressed content (b'' when unreadable)."""
    with open(path, "rb") as fh:
        kind = compression_of(fh.read(4))
    if kind == "Z":  # no streaming decoder
        import hatanaka

        try:
            return hatanaka.decompress(path.read_bytes())[:size]
        except Exception:  # a damaged stream: the reader names the problem
            return b""
    opener = {"gzip": gzip.open, "bz2": bz2.open}.get(kind, open)
    try:
        with opener(path, "rb") as fh:
            return fh.read(size)
    except (OSError, EOFError, ValueError):
        return b""


def file_kind(path: str | os.PathLike[str]) -> str:
    """Tell what a RINEX or SP3 file holds, from its first line.

    Parameters
    ----------
    path : path
        A plain, gzip or bz2 file (``.Z`` files are decompressed whole).

    Returns
    -------
    str
        ``"obs"`` (RINEX or Hatanaka observations), ``"nav"`` (RINEX
        navigation), ``"sp3"`` or ``""`` (anything else, e.g. a damaged file:
        its reader names the problem).
    """
    first = _head(Path(path)).split(b"\n", 1)[0]
    if first[:2] in (b"#a", b"#b", b"#c", b"#d"):
        return "sp3"
    if b"COMPACT RINEX" in first:
        return "obs"
    if first[60:80].strip() != b"RINEX VERSION / TYPE":
        return ""
    kind = first[20:21].decode("ascii", "replace").upper()
    if kind == "O":
        return "obs"
    return "nav" if kind in _NAV_TYPES else ""


def member_label(archive: str | os.PathLike[str], member: Path) -> str:
    """How an archive member is named in messages: ``archive.zip:member``."""
    return f"{archive}:{member.name}"


def relabel(exc: InputError, label: str) -> InputError:
    """Return the same error naming ``label`` (e.g. ``archive.zip:member``), not its file."""
    return type(exc)(exc.reason, path=label, line=exc.line)
