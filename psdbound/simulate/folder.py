"""The folder ``psdbound simulate`` writes: built aside, installed whole, keeping a user's files.

The policy of the output folders (:mod:`psdbound.common.outputs`, which does
the work), for the simulator's files (``<name>-A_MO.rnx.gz``,
``<name>-B_MO.rnx.gz``, ``<name>_MN.rnx.gz``, ``<name>_truth.csv.gz``,
``<name>_truth.json``). A simulation's files are those its
``<name>_truth.json`` lists (:func:`simulated_files`). Where the folder goes is
checked before the simulation (:func:`check_simulate_folder`) and again when
it is installed (:func:`simulate_folder`):

``create``
    The folder does not exist: it is created (with missing parents).
``replace``
    The folder is empty, or holds nothing but earlier simulations' files:
    the new folder replaces it as a whole (no file of an earlier run is left).
``merge``
    Any other existing folder, only with ``overwrite=True`` (or earlier
    simulations behind a symbolic link): the new files are moved in, and the
    earlier simulations' files in it that are not written again are removed
    (and a second antenna's file of the same name when only one antenna is
    written); nothing else in it is touched.

Refused (:class:`~psdbound.errors.InputError`, nothing written): a path that
is a file, lies below a file or cannot be written, and a folder with other
content without ``overwrite``.
"""

from __future__ import annotations

import json
import os
from contextlib import AbstractContextManager
from pathlib import Path

from psdbound.common.outputs import FolderKind, check_output_folder, output_folder

__all__ = ["check_simulate_folder", "simulate_folder", "simulated_files"]

_MANIFEST_SUFFIX = "_truth.json"
_ANTENNA_A, _ANTENNA_B = "-A_MO.rnx.gz", "-B_MO.rnx.gz"


def _listed(folder: Path, manifest: str) -> set[str]:
    """Return the files one ``*_truth.json`` lists, itself included (empty: not a manifest)."""
    try:
        with open(folder / manifest, "rb") as fh:
            meta = json.loads(fh.read(64 << 20))
        files = meta["files"]
        names = {manifest, files["nav"], files["truth"], *files["obs"]}
    except (OSError, ValueError, KeyError, TypeError):
        return set()
    if not ({"scenario", "digest"} <= set(meta)) or not all(
        isinstance(n, str) and n == Path(n).name and n not in ("", ".", "..") for n in names
    ):
        return set()
    return names


def simulated_files(path: str | os.PathLike[str]) -> set[str]:
    """Return the names of the files in a folder that earlier simulations wrote.

    Parameters
    ----------
    path : str or path-like
        The folder.

    Returns
    -------
    set of str
        Every regular file listed by a ``<name>_truth.json`` of the simulator
        in the folder (the manifest included); empty when the folder holds
        none or cannot be listed.
    """
    p = Path(path)
    try:
        manifests = [e for e in os.listdir(p) if e.endswith(_MANIFEST_SUFFIX)]
    except OSError:
        return set()
    out: set[str] = set()
    for m in manifests:
        out |= _listed(p, m)
    return {n for n in out if (p / n).is_file() and not (p / n).is_symlink()}


def _antenna_b(name: str) -> tuple[str, ...]:
    """Return the second antenna's file beside antenna A's ``name`` (stale if A only is new)."""
    if name.endswith(_ANTENNA_A):
        return (name[: -len(_ANTENNA_A)] + _ANTENNA_B,)
    return ()


#: A simulation's folder: its own files are those the manifests in it list; a merge
#: removes them all (and antenna B beside a new antenna A), whatever else the folder holds.
_SIMULATION = FolderKind(
    ours=simulated_files,
    noun="a simulation's output",
    overwrite_does=(
        "write the simulation into it (the files of earlier simulations in it are removed, "
        "nothing else in it is touched; nothing was written)"
    ),
    prune=True,
    supersedes=_antenna_b,
)


def check_simulate_folder(
    path: str | os.PathLike[str], *, overwrite: bool = False, option: str = "output folder"
) -> str:
    """Decide how a simulation would be written to ``path``; refuse what is unsafe.

    Parameters
    ----------
    path : str or path-like
        Where the simulation's files go.
    overwrite : bool, default False
        Also accept a folder with other content (``merge``: the earlier
        simulations' files in it are removed, nothing else is touched).
    option : str
        The destination's name in messages (the CLI passes ``"--out"``).

    Returns
    -------
    {"create", "replace", "merge"}
        How the folder would be written (see the module docstring).

    Raises
    ------
    InputError
        The destination is refused, nothing is written (see
        :func:`psdbound.common.outputs.check_output_folder`).
    """
    return check_output_folder(path, overwrite=overwrite, option=option, kind=_SIMULATION)


def simulate_folder(
    path: str | os.PathLike[str], *, overwrite: bool = False, option: str = "output folder"
) -> AbstractContextManager[Path]:
    """Build a simulation's folder under a temporary name; install it at ``path`` safely.

    Parameters
    ----------
    path : str or path-like
        Where the simulation's files go.
    overwrite : bool, default False
        Also accept a folder with other content (see the module docstring).
    option : str
        The destination's name in messages (the CLI passes ``"--out"``).

    Returns
    -------
    context manager of Path
        Entered, it checks the destination and yields the temporary folder
        to simulate into (see :func:`psdbound.common.outputs.output_folder`);
        the files are installed at ``path`` when the body returns, and
        ``path`` is left as it was when the body raises.

    Raises
    ------
    InputError
        When it is entered (and again before the install): the destination
        is refused (see :func:`check_simulate_folder`).
    """
    return output_folder(path, overwrite=overwrite, option=option, kind=_SIMULATION)
