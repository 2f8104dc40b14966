"""Atomic file and folder writes: build beside the target, then rename.

A reader never sees a half-written file: the content goes to a temporary
name in the target's folder (same file system, so :func:`os.replace` is
atomic) and is renamed over the target only when complete. On any error the
temporary is removed and the target is left as it was.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_write_bytes", "atomic_write_text", "atomic_folder"]


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically.

    Parameters
    ----------
    path : str or path-like
        Target file; its folder is created if missing.
    data : bytes
        The complete content.

    Returns
    -------
    Path
        The target path.
    """
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}-", suffix=".part", dir=p.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)  # mkstemp makes 0600; give the file normal permissions
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise
    return p


def atomic_write_text(path: str | os.PathLike[str], text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically (see :func:`atomic_write_bytes`)."""
    return atomic_write_bytes(path, text.encode(encoding))


@contextlib.contextmanager
def atomic_folder(path: str | os.PathLike[str], *, replace: bool = True) -> Iterator[Path]:
    """Build a folder under a temporary name and rename it to ``path`` on success.

    Low level: with ``replace=True`` an existing ``path`` is swapped out
    whatever it holds. For folders the user names (``--out``) use
    :func:`psdbound.common.outputs.output_folder`, which refuses to replace
    anything psdbound did not create.

    Parameters
    ----------
    path : str or path-like
        The folder to create.
    replace : bool, default True
        If ``path`` exists, swap it out after the new folder is complete
        (the old folder is then removed). If False, an existing ``path``
        raises :class:`FileExistsError` on completion and the new content is
        discarded.

    Yields
    ------
    Path
        The temporary folder to write into (same parent as ``path``).
    """
    out = Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    mask = os.umask(0)
    os.umask(mask)
    os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; give the folder normal permissions
    try:
        yield tmp
        if out.exists() or out.is_symlink():
            if not replace:
                raise FileExistsError(f"{out} exists")
            old = Path(tempfile.mkdtemp(prefix=f".{out.name}-old-", dir=out.parent))
            os.replace(out, old / "content")
            os.replace(tmp, out)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(tmp, out)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)
