"""Output folders that never lose a user's file.

An output folder is built under a temporary name (hidden, beside the
destination or inside it) and installed only when complete; no missing
parent of the destination is created before the install. Where it goes is
checked before any computation (:func:`check_output_folder`) and again when
it is installed (:func:`output_folder`). The same policy serves two kinds of
folder, each a :class:`FolderKind`: the report folders (:data:`REPORT_FOLDER`,
the default: ``result.json``, ``report.html``, ``report.pdf``,
``series.csv.gz``) and the simulator's (:mod:`psdbound.simulate.folder`). A
kind says which files of an existing folder are its own (an earlier output's),
which names may be written, and which files a merge removes.

``create``
    The folder does not exist: it is created (with missing parents).
``replace``
    The folder is empty, or holds nothing but the kind's own files (a
    previous report folder: nothing in it but :data:`REPORT_FILES`, with a
    ``result.json`` that has a ``schema_version``): the new folder replaces
    it atomically.
``merge``
    Any other existing folder, only with ``overwrite=True`` (or a previous
    output behind a symbolic link): the new files are written into it
    (same-named files replaced); the kind's own files not written again are
    removed when the kind prunes (simulations) or when the folder holds
    nothing else; nothing else in it is touched.

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
from dataclasses import dataclass
from pathlib import Path

from psdbound.errors import InputError

__all__ = [
    "REPORT_FILES",
    "REPORT_FOLDER",
    "FolderKind",
    "check_output_file",
    "check_output_folder",
    "check_writable_folder",
    "is_report_folder",
    "output_folder",
]

#: The files psdbound writes into a report folder.
REPORT_FILES = ("result.json", "report.html", "report.pdf", "series.csv.gz")


def _no_names(name: str) -> tuple[str, ...]:
    """Return no further stale names (the default of :attr:`FolderKind.supersedes`)."""
    return ()


@dataclass(frozen=True)
class FolderKind:
    """One kind of output folder: what the shared folder policy needs to know of it.

    Parameters
    ----------
    ours : callable
        ``ours(folder)`` returns the names of the files in ``folder`` that
        earlier outputs of this kind wrote (may be replaced or removed).
    noun : str
        What a folder of this kind is, in messages (``"a psdbound output"``).
    overwrite_does : str
        What ``--overwrite`` does to a folder with other content, in the
        refusal (``"add psdbound's files to it (...)"``).
    writes : tuple of str or None, default None
        The only names that may be written (a folder holding one of them as
        anything but a file is refused before the build); None: any name.
    prune : bool, default False
        On a merge, remove the folder's own files that are not written again
        even when it holds other things (else only when it holds nothing
        else: a previous output behind a symbolic link).
    supersedes : callable, default no name
        ``supersedes(name)`` returns further names a newly written ``name``
        makes stale (removed on a merge, though ``ours`` does not list them).
    """

    ours: Callable[[Path], set[str]]
    noun: str
    overwrite_does: str
    writes: tuple[str, ...] | None = None
    prune: bool = False
    supersedes: Callable[[str], Iterable[str]] = _no_names


def _report_files(folder: Path) -> set[str]:
    """Return the :data:`REPORT_FILES` in ``folder`` when its ``result.json`` has a schema."""
    try:
        names = set(os.listdir(folder)) & set(REPORT_FILES)
        with open(folder / "result.json", "rb") as fh:
            data = json.loads(fh.read(64 << 20))
    except (OSError, ValueError):
        return set()
    return names if isinstance(data, dict) and "schema_version" in data else set()


#: The report folders (the default kind): see the module docstring.
REPORT_FOLDER = FolderKind(
    ours=_report_files,
    noun="a psdbound output",
    overwrite_does="add psdbound's files to it (nothing else in it is touched)",
    writes=REPORT_FILES,
)


def is_report_folder(path: str | os.PathLike[str]) -> bool:
    """Return True if ``path`` is a folder written by psdbound (see the module docstring)."""
    p = Path(path)
    try:
        entries = set(os.listdir(p))
    except OSError:
        return False
    if not entries or not entries <= set(REPORT_FILES):
        return False
    return entries <= _report_files(p)


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
    path: str | os.PathLike[str],
    *,
    overwrite: bool = False,
    option: str = "output folder",
    kind: FolderKind = REPORT_FOLDER,
) -> str:
    """Decide how an output folder would be written to ``path``; refuse what is unsafe.

    Parameters
    ----------
    path : str or path-like
        The destination folder.
    overwrite : bool, default False
        Allow writing into a folder that holds other things (``merge``).
    option : str
        How to name the destination in messages (``"--out"``).
    kind : FolderKind, default REPORT_FOLDER
        The kind of folder written (which files in it are its own).

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
    return _decide(Path(path), overwrite=overwrite, option=option, kind=kind, building="")


def _decide(p: Path, *, overwrite: bool, option: str, kind: FolderKind, building: str) -> str:
    """Do :func:`check_output_folder`, ignoring the entry ``building`` (the folder being built)."""
    p = check_writable_folder(p, option=option)
    if not p.exists():
        return "create"
    try:
        entries = sorted(e for e in os.listdir(p) if e != building)
    except OSError as exc:
        raise InputError(f"{option}: cannot list the folder ({exc.strerror})", path=p) from None
    ours = set(entries) <= kind.ours(p)
    if ours and not p.is_symlink():
        if not os.access(p.parent, os.W_OK | os.X_OK):
            raise InputError(
                f"{option}: cannot replace the folder, its parent is not writable", path=p
            )
        return "replace"
    if ours or overwrite:  # a previous output behind a symbolic link: written file by file
        _refuse_clash(p, entries, option=option, kind=kind)
        return "merge"
    shown = ", ".join(entries[:3]) + (", ..." if len(entries) > 3 else "")
    raise InputError(
        f"{option} is an existing folder that is not {kind.noun} (it holds "
        f"{len(entries)} entr{'y' if len(entries) == 1 else 'ies'}: {shown}); give a new or "
        f"empty folder, or --overwrite to {kind.overwrite_does}",
        path=p,
    )


def _refuse_clash(p: Path, entries: list[str], *, option: str, kind: FolderKind) -> None:
    """Refuse a merge into ``p`` where a name the kind writes is not a file."""
    clash = [e for e in kind.writes or () if e in entries and not (p / e).is_file()]
    if clash:
        raise InputError(
            f"{option}: {clash[0]} in the folder is not a file; psdbound cannot write its "
            f"{clash[0]} there",
            path=p,
        )


@contextlib.contextmanager
def output_folder(
    path: str | os.PathLike[str],
    *,
    overwrite: bool = False,
    option: str = "output folder",
    kind: FolderKind = REPORT_FOLDER,
) -> Iterator[Path]:
    """Build an output folder under a temporary name; install it at ``path`` safely.

    Parameters
    ----------
    path : str or path-like
        Destination folder.
    overwrite : bool, default False
        Allow writing into a folder with other content (see the module
        docstring).
    option : str
        How to name the destination in messages.
    kind : FolderKind, default REPORT_FOLDER
        The kind of folder written (for a report folder, only
        :data:`REPORT_FILES` may be written).

    Yields
    ------
    Path
        The temporary folder to write into (hidden, beside or inside
        ``path``; no missing parent of ``path`` is created before the
        install). It is removed, and ``path`` left as it was, when the body
        raises.

    Raises
    ------
    InputError
        Before anything is built (and again before anything is installed)
        when the destination is refused (see :func:`check_output_folder`).
    """
    out = Path(path)
    mode = check_output_folder(out, overwrite=overwrite, option=option, kind=kind)
    if mode == "merge":
        tmp = Path(tempfile.mkdtemp(prefix=".psdbound-", dir=out))
    else:
        tmp = Path(tempfile.mkdtemp(prefix=f".{out.name}-", dir=_first_existing(out.parent)))
    mask = os.umask(0)
    os.umask(mask)
    os.chmod(tmp, 0o777 & ~mask)  # mkdtemp makes 0700; give the folder normal permissions
    try:
        yield tmp
        _finish(tmp, out, mode, overwrite=overwrite, option=option, kind=kind)
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _finish(
    tmp: Path, out: Path, mode: str, *, overwrite: bool, option: str, kind: FolderKind
) -> None:
    """Install the built folder ``tmp`` at ``out``, checked again (``mode``: as first checked)."""
    new = sorted(os.listdir(tmp))
    unknown = [n for n in new if kind.writes is not None and n not in kind.writes]
    if unknown:
        raise ValueError(f"output_folder: unexpected file {unknown[0]!r} written")
    # the destination may have changed while the outputs were built: check again (the
    # folder being built inside it is not counted; a folder emptied meanwhile still merges)
    now = _decide(out, overwrite=overwrite, option=option, kind=kind, building=tmp.name)
    if mode == "merge" and now != "create":
        _merge(tmp, out, new, kind)
    elif mode != "merge" and now != "merge":
        _install(tmp, out, kind)
    else:
        raise InputError(
            f"{option} changed while psdbound was running; nothing was written", path=out
        )


def _merge(tmp: Path, out: Path, new: list[str], kind: FolderKind) -> None:
    """Move the new files into ``out``, then remove the files they leave stale."""
    ours = kind.ours(out)
    alone = set(os.listdir(out)) - {tmp.name} <= ours  # a previous output behind a link
    stale = ours if kind.prune or alone else set()
    stale = stale.union(*(kind.supersedes(name) for name in new))
    for name in new:
        os.replace(tmp / name, out / name)
    for name in sorted(stale - set(new)):
        if (out / name).is_file():
            with contextlib.suppress(FileNotFoundError):
                (out / name).unlink()


def _install(tmp: Path, out: Path, kind: FolderKind) -> None:
    """Put ``tmp`` at ``out`` (absent, empty or the kind's own files only) by renaming."""
    out.parent.mkdir(parents=True, exist_ok=True)
    if not out.exists() or not any(out.iterdir()):
        os.replace(tmp, out)  # renaming over an empty folder is atomic too
        return
    ours = kind.ours(out)
    old = Path(tempfile.mkdtemp(prefix=f".{out.name}-old-", dir=out.parent))
    os.replace(out, old / "content")
    os.replace(tmp, out)
    # whatever appeared in the old folder since it was checked is not ours: put it back
    kept = False
    for name in os.listdir(old / "content"):
        if name in ours:
            continue
        if (out / name).exists():
            kept = True
            continue
        os.replace(old / "content" / name, out / name)
    if kept:
        return  # never delete what is not ours; the old folder stays, hidden
    shutil.rmtree(old, ignore_errors=True)
