"""Turn a file name into the plain text of a RINEX/SP3 file.

Handles plain text, gzip/Z/bz2/zip (via :mod:`hatanaka`'s detection) and
Hatanaka compact RINEX (``.crx``, ``.??d``, compressed or not).
"""

from __future__ import annotations

import gzip
import os
from pathlib import Path

from psdbound.common.compression import compression_of
from psdbound.errors import InputError
from psdbound.io.archive import zip_members

__all__ = ["read_bytes"]


def read_bytes(path: str | os.PathLike[str]) -> bytes:
    """Return the decompressed text of a RINEX or SP3 file as bytes.

    Parameters
    ----------
    path : str or path-like
        Plain, gzip/Z/bz2/zip-compressed, or Hatanaka-compressed file.

    Returns
    -------
    bytes
        The plain file content (``\\r\\n`` normalised to ``\\n``).

    Raises
    ------
    InputError
        If the file is missing, a folder, unreadable (permissions), empty,
        not decompressable (any error of the compressed stream), or a
        corrupted Hatanaka stream.
    """
    p = Path(path)
    raw = _read_file(p)
    _one_member(p, raw)
    raw = _decompress(p, raw)
    if not raw or raw.isspace():  # (no stripped copy of a large file)
        raise InputError("file is empty after decompression", path=p)
    if b"\r" in raw:
        raw = raw.replace(b"\r\n", b"\n")
    if b"COMPACT RINEX" in raw[:200]:
        raw = _crx_to_rnx(raw, p)
    return raw


def _read_file(p: Path) -> bytes:
    """Return the file's bytes as stored; refuse a folder, a missing, unreadable or empty file."""
    if p.is_dir():
        raise InputError("is a folder, not a file", path=p)
    if not p.is_file():
        raise InputError("file not found", path=p)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the file: {exc.strerror or exc}", path=p) from None
    if not raw:
        raise InputError("file is empty (0 bytes); expected a RINEX or SP3 file", path=p)
    return raw


def _decompress(p: Path, raw: bytes) -> bytes:
    """Return ``raw`` decompressed (gzip, Z, bz2, zip) when it starts with their magic bytes."""
    kind = compression_of(raw[:4])
    try:
        if kind == "gzip":
            raw = gzip.decompress(raw)
        elif kind == "zip":
            raw = _zip_member(p)
            if compression_of(raw[:4]) in ("gzip", "Z", "bz2"):
                raw = _decompress(p, raw)  # a compressed file inside the archive
        elif kind in ("Z", "bz2"):
            import hatanaka

            raw = hatanaka.decompress(raw)
    except (MemoryError, InputError):
        raise
    except Exception as exc:  # gzip/zlib/bz2/zip/LZW errors: the compressed stream is damaged
        detail = " ".join(str(exc).split()) or type(exc).__name__
        raise InputError(
            f"cannot decompress: {detail} (damaged or truncated file?)", path=p
        ) from None
    return raw


def _zip_member(p: Path) -> bytes:
    """Return the bytes of a zip archive's one file member (refused when it has none)."""
    import zipfile

    names = zip_members(p)
    if not names:
        raise InputError("zip archive holds no file; expected one RINEX or SP3 file", path=p)
    with zipfile.ZipFile(p) as z:
        return z.read(names[0])


def _one_member(p: Path, raw: bytes) -> None:
    """Refuse a zip archive of several files, listing them (the readers take one file)."""
    names = zip_members(p) if compression_of(raw[:4]) == "zip" else []
    if len(names) > 1:
        shown = ", ".join(names[:6]) + (f" and {len(names) - 6} more" if len(names) > 6 else "")
        raise InputError(
            f"zip archive of {len(names)} files ({shown}): this reader takes one file; unzip "
            "it and give the files one by one (psdbound fit and --nav also take such an "
            "archive whole)",
            path=p,
        )


def _crx_to_rnx(raw: bytes, p: Path) -> bytes:
    import warnings

    import hatanaka

    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            out = hatanaka.crx2rnx(raw)
        # crx2rnx reports damaged epochs as warnings and skips them: a silent data loss
        problems = [str(w.message) for w in caught if "crx2rnx" in str(w.message)]
        if problems:
            raise ValueError(problems[0])
        return out
    except Exception as exc:  # hatanaka raises HatanakaException / ValueError
        msg = str(exc).strip().splitlines()
        detail = msg[0] if msg else type(exc).__name__
        raise InputError(f"corrupted Hatanaka (compact RINEX) stream: {detail}", path=p) from exc
