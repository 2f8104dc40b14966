"""Output folders that never lose a user's file.

A report folder (``result.json``, ``report.html``, ``report.pdf``) is built
under a temporary name and installed only when complete. Where it goes is
checked before any computation (:func:`check_output_folder`) and again when
it is installed (:func:`output_folder`):

``create``
    The folder does not exist: it is created (with missing parents).
``replace``
    The folder is empty, or a previous psdbound output (nothing in it but
    :data:`REPORT_FILES`, with a ``result.json`` that has a
    ``schema_version``): the new folder replaces it atomically.
``merge``
    Any other existing folder, only with ``overwrite=True``: psdbound's files
    are written into it (same-named files replaced); nothing else in it is
    touched.

Refused (:class:`~psdbound.errors.InputError`, nothing written): a path that
is an existing file (or anything but a folder), a path below a file, a
folder that cannot be written, and a folder with other content without
``overwrite``.
"""

from __future__ import annotations

import contextlib
import json
import os
import shutil
import tempfile
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

from psdbound.errors import InputError

__all__ = [
    "REPORT_FILES",
    "check_output_file",
    "check_output_folder",
    "check_writable_folder",
    "is_report_folder",
    "output_folder",
]

#: The files psdbound writes into a report folder.
REPORT_FILES = ("result.json", "report.html", "report.pdf", "series.csv.gz")


def is_report_folder(path: str | os.PathLike[str]) -> bool:
    """Return True if ``path`` is a folder written by psdbound (see the module docstring)."""
    p = Path(path)
    try:
        entries = set(os.listdir(p))
    except OSError:
        return False
    if not entries or not entries <= set(REPORT_FILES) or "result.json" not in entries:
        return False
    try:
        with open(p / "result.json", "rb") as fh:
            data = json.loads(fh.read(64 << 20))
    except (OSError, ValueError):
        return False
    return isinstance(data, dict) and "schema_version" in data


def _first_existing(p: Path) -> Path:
    cur = p
    while not (cur.exists() or cur.is_symlink()):
        if cur.parent == cur:
            break
        cur = cur.parent
    return cur


def check_writable_folder(path: str | os.PathLike[str], *, option: str = "output folder") -> Path:
    """Check that files can be written into the folder ``path`` (created if missing).

    Parameters
    ----------
    path : str or path-like
        The folder.
    option : str
        How to name it in messages (``"--out"``).

    Returns
    -------
    Path

    Raises
    ------
    InputError
        ``path`` is an existing file, lies below a file, or cannot be
        written (the check leaves nothing behind: its probe folder is
        removed at once).
    """
    p = Path(path)
    if p.is_symlink() and not p.exists():
        raise InputError(f"{option} is a broken symbolic link", path=p)
    if p.exists():
        if not p.is_dir():
            raise InputError(
                f"{option} is an existing file, not a folder; give a folder name (nothing "
                "was written)",
                path=p,
            )
        if not os.access(p, os.W_OK | os.X_OK):
            raise InputError(f"{option}: the folder is not writable (permission denied)", path=p)
        _probe(p, f"{option}: the folder is not writable", p)
        return p
    anc = _first_existing(p.parent if p.parent != p else p)
    if not anc.is_dir():
        raise InputError(
            f"{option} cannot be created: {anc} is a file, not a folder (nothing was written)",
            path=p,
        )
    if not os.access(anc, os.W_OK | os.X_OK):
        raise InputError(
            f"{option} cannot be created: {anc} is not writable (permission denied)", path=p
        )
    _probe(anc, f"{option} cannot be created: {anc} is not writable", p)
    return p


def _probe(folder: Path, message: str, path: Path) -> None:
    """Create and remove an empty folder in ``folder``: what ``os.access`` cannot tell.

    ``os.access`` answers from permissions: for root, or on a file system that
    refuses new entries whatever they say (``/proc``, a read-only or full
    mount, some network shares), it says yes and the run would fail at its
    end, after the analysis.
    """
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".psdbound-probe-", dir=folder))
    except OSError as exc:
        raise InputError(
            f"{message} ({exc.strerror or exc}; nothing was written)", path=path
        ) from None


def check_output_file(
    path: str | os.PathLike[str],
    *,
    overwrite: bool = False,
    option: str = "output file",
    ours: Callable[[Path], bool] | None = None,
) -> Path:
    """Check that one output file can be written at ``path`` (nothing is created).

    Parameters
    ----------
    path : str or path-like
        The file to write.
    overwrite : bool, default False
        Allow replacing an existing file.
    option : str
        How to name the destination in messages (``"-o"``).
    ours : callable, optional
        ``ours(path)`` is True for a file psdbound wrote earlier (replaced
        without ``overwrite``, as a previous report folder is).

    Returns
    -------
    Path

    Raises
    ------
    InputError
        ``path`` is a folder (or anything but a file), an existing file that
        is not ours without ``overwrite``, or its folder cannot be created or
        written.
    """
    p = Path(path)
    if p.exists() or p.is_symlink():
        if not p.is_file():
            raise InputError(
                f"{option} is an existing folder (or not a regular file); give a "
                "file name (nothing was written)",
                path=p,
            )
        if not overwrite and not (ours is not None and ours(p)):
            raise InputError(
                f"{option} is an existing file that psdbound did not write; give "
                "another name, or --overwrite to replace it (nothing was written)",
                path=p,
            )
    check_writable_folder(p.parent if str(p.parent) else Path("."), option=f"{option}'s folder")
    return p


def check_output_folder(
    path: str | os.PathLike[str], *, overwrite: bool = False, option: str = "output folder"
) -> str:
    """Decide how a report folder would be written to ``path``; refuse what is unsafe.

    Parameters
    ----------
    path : str or path-like
        The destination folder.
    overwrite : bool, default False
        Allow writing into a folder that holds other things (``merge``).
    option : str
        How to name the destination in messages (``"--out"``).

    Returns
    -------
    {"create", "replace", "merge"}
        See the module docstring.

    Raises
    ------
    InputError
        The destination is a file, lies below a file, is not writable, or
        is a folder with other content and ``overwrite`` is False.
    """
    p = check_writable_folder(path, option=option)
    if not p.exists():
        return "create"
    try:
        entries = sorted(os.listdir(p))
    except OSError as exc:
        raise InputError(f"{option}: cannot list the folder ({exc.strerror})", path=p) from None
    ours = not entries or is_report_folder(p)
    if ours and not p.is_symlink():
        if not os.access(p.parent, os.W_OK | os.X_OK):
            raise InputError(
                f"{option}: cannot replace the folder, its parent is not writable", path=p
            )
        return "replace"
    if ours or overwrite:
        clash = [e for e in REPORT_FILES if e in entries and not (p / e).is_file()]
        if clash:
            raise InputError(
                f"{option}: {clash[0]} in the folder is not a file; psdbound cannot write its "
                f"{clash[0]} there",
                path=p,
            )
        return "merge"
    shown = ", ".join(entries[:3]) + (", ..." if len(entries) > 3 else "")
    raise InputError(
        f"{option} is an existing folder that is not a psdbound output (it holds "
        f"{len(entries)} entr{'y' if len(entries) == 1 else 'ies'}: {shown}); give a new or "
        "empty folder, or --overwrite to add psdbound's files to it (nothing else in it is "
        "touched)",
        path=p,
    )


@contextlib.contextmanager
def output_folder(
    path: str | os.PathLike[str], *, overwrite: bool = False, option: str = "output folder"
) -> Iterator[Path]:
    """Build a report folder under a temporary name; install it at ``path`` safely.

    Parameters
    ----------
    path : str or path-like
        Destination folder.
    overwrite : bool, default False
        Allow writing into a folder with other content (see the module
        docstring).
    option : str
        How to name the destination in messages.

    Yields
    ------
    Path
        The temporary folder to write into. Only :data:`REPORT_FILES` may be
        written.

    Raises
    ------
    InputError
        Before anything is built (and again before anything is installed)
        when the destination is refused (see :func:`check_output_folder`).
    """
    out = Path(path)
    mode = check_output_folder(out, overwrite=overwrite, option=option)
    if mode == "merge":
        tmp = Path(tempfile.mkdtemp(prefix=".psdbound-", dir=out))
    else:
        out.parent.mkdir(parents=True, exist_ok=True)
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=out.parent))
    mask = os.umask(0)
    os.umask(mask)
    os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; give the folder normal permissions
    try:
        yield tmp
        new = sorted(os.listdir(tmp))
        unknown = [n for n in new if n not in REPORT_FILES]
        if unknown:
            raise ValueError(f"output_folder: unexpected file {unknown[0]!r} written")
        # the destination may have changed while the outputs were built: check again
        now = check_output_folder(out, overwrite=overwrite, option=option)
        if now == "merge" and mode != "merge":
            raise InputError(
                f"{option} changed while psdbound was running; nothing was written", path=out
            )
        if now == "merge":
            _merge(tmp, out, new)
        else:
            _install(tmp, out)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _merge(tmp: Path, out: Path, new: Iterable[str]) -> None:
    new = list(new)
    ours = is_report_folder(out)
    for name in new:
        os.replace(tmp / name, out / name)
    if ours:  # a previous output behind a symbolic link: drop its files not written now
        for name in REPORT_FILES:
            if name not in new and (out / name).is_file():
                (out / name).unlink()


def _install(tmp: Path, out: Path) -> None:
    """Put ``tmp`` at ``out`` (absent, empty or a previous output) by renaming."""
    if not out.exists() or not any(out.iterdir()):
        os.replace(tmp, out)  # renaming over an empty folder is atomic too
        return
    old = Path(tempfile.mkdtemp(prefix=f".{out.name}-old-", dir=out.parent))
    os.replace(out, old / "content")
    os.replace(tmp, out)
    # whatever appeared in the old folder since it was checked is not ours: put it back
    kept = False
    for name in os.listdir(old / "content"):
        if name in REPORT_FILES:
            continue
        if (out / name).exists():
            kept = True
            continue
        os.replace(old / "content" / name, out / name)
    if kept:
        return  # never delete what is not ours; the old folder stays, hidden
    shutil.rmtree(old, ignore_errors=True)
