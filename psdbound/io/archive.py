"""Zip archives that hold several observation files (e.g. a day of hourly files)."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

from psdbound.errors import InputError

__all__ = ["zip_members", "extract_zip"]


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
