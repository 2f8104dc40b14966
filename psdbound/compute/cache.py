"""Disk cache of task results, keyed by a content hash of the task's inputs.

A cached **result** is a dict. Every top-level value that is a NumPy array
goes to ``<key>.npz``; everything else goes to ``<key>.json`` (with the list
of array names), so small results stay readable text and large arrays stay
binary. Both files are written atomically with :mod:`psdbound.common`
(temporary name, then rename), the arrays first: a reader never sees a torn
entry, and two runs computing the same key only replace one identical entry
by another. An entry that cannot be read is a miss (logged), and is
recomputed and overwritten.

The **key** of a task is :func:`cache_key` of a JSON-able payload holding
everything that changes the result (inputs, settings, file digests such as
:func:`psdbound.common.file_sha256`, the code version, a layout version).
Nothing here knows what the tasks compute: a user builds a
:class:`DiskCache` from a key function and passes it to
:func:`psdbound.compute.run_tasks`.
"""

from __future__ import annotations

import hashlib
import io
import json
import logging
import os
import zipfile
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from psdbound.common import atomic_write_bytes, atomic_write_text
from psdbound.common.notices import warn

__all__ = [
    "CACHE_ENV",
    "DiskCache",
    "ResultStore",
    "TaskCache",
    "cache_key",
    "default_cache_dir",
]

#: Environment variable naming the cache directory.
CACHE_ENV = "PSDBOUND_CACHE"

_log = logging.getLogger(__name__)
_UNREADABLE = (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile)


def default_cache_dir(name: str) -> Path:
    """Default cache directory of one kind of task.

    Parameters
    ----------
    name : str
        Kind of task, e.g. ``"cutoff"``.

    Returns
    -------
    Path
        ``$PSDBOUND_CACHE`` if set (keys are content hashes, so different
        kinds of task can share it), else ``~/.cache/psdbound/<name>``.
    """
    env = os.environ.get(CACHE_ENV)
    return Path(env) if env else Path.home() / ".cache" / "psdbound" / name


def cache_key(payload: Any, *, length: int = 32) -> str:
    """Content-hash key of a task's inputs.

    Parameters
    ----------
    payload : JSON-able object
        Everything that changes the result. Dicts are hashed with sorted
        keys; values JSON cannot encode are hashed by their ``str()``.
    length : int, default 32
        Hex digits kept from the SHA-256 digest.

    Returns
    -------
    str
        Lower-case hex key, e.g. a file name.
    """
    text = json.dumps(payload, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:length]


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


class ResultStore:
    """A directory of results, one ``<key>.json`` (+ ``<key>.npz``) per key.

    Parameters
    ----------
    directory : str or path-like
        Where the entries live; created on the first write.
    """

    def __init__(self, directory: str | os.PathLike[str]) -> None:
        self.directory = Path(directory)

    def paths(self, key: str) -> tuple[Path, Path]:
        """Return the JSON and NPZ files of an entry."""
        return self.directory / f"{key}.json", self.directory / f"{key}.npz"

    def read(self, key: str, *, arrays: Sequence[str] | None = None) -> dict[str, Any] | None:
        """Read an entry.

        Parameters
        ----------
        key : str
            Entry key.
        arrays : sequence of str, optional
            Array fields to load; an entry without one of them is a miss.
            Default: every array the entry holds (``()`` loads none).

        Returns
        -------
        dict or None
            The result, or None on a miss (absent, incomplete or unreadable).
        """
        pj, pn = self.paths(key)
        if not pj.is_file():
            return None
        try:
            body = json.loads(pj.read_text())
            out = dict(body["result"])
            stored = list(body["arrays"])
            wanted = stored if arrays is None else list(arrays)
            if not set(wanted) <= set(stored):
                return None
            if wanted:
                with np.load(pn) as z:
                    out.update({name: z[name] for name in wanted})
        except _UNREADABLE as exc:  # torn, foreign or older-layout file: recompute
            _log.warning("ignoring unreadable cache entry %s: %s", pj, exc)
            return None
        return out

    def write(self, key: str, result: Mapping[str, Any]) -> None:
        """Write an entry atomically (arrays first, then the JSON that lists them).

        Parameters
        ----------
        key : str
            Entry key.
        result : mapping
            The result; top-level ndarray values go to the NPZ file, the rest
            must be JSON-able (NumPy scalars and nested arrays are converted).

        Warns
        -----
        PsdboundWarning
            The entry could not be written (the folder is not writable, the
            disk is full): the run goes on without it.
        """
        pj, pn = self.paths(key)
        arrays = {k: v for k, v in result.items() if isinstance(v, np.ndarray)}
        body = {
            "result": {k: v for k, v in result.items() if k not in arrays},
            "arrays": sorted(arrays),
        }
        try:
            if arrays:
                buf = io.BytesIO()
                np.savez_compressed(buf, **arrays)
                atomic_write_bytes(pn, buf.getvalue())
            atomic_write_text(pj, json.dumps(body, default=_json_default))
        except OSError as exc:  # a cache saves time only: the result stands without it
            warn(
                f"cache not written ({exc.strerror or exc}): the result is computed again "
                f"next time; give a writable cache folder (--cache-dir or ${CACHE_ENV})",
                path=self.directory,
            )


class TaskCache(Protocol):
    """What :func:`~psdbound.compute.run_tasks` needs of a cache."""

    def get(self, item: Any) -> Any | None:
        """Return the cached result of a task item, or None on a miss."""

    def put(self, item: Any, result: Any) -> None:
        """Store the result of a task item."""


class DiskCache:
    """Task cache on disk: a :class:`ResultStore` addressed by a key function.

    Parameters
    ----------
    directory : str or path-like
        Cache directory (e.g. :func:`default_cache_dir`).
    key : callable
        ``key(item) -> str``, the content-hash key of a task item (see
        :func:`cache_key`).
    arrays : callable, optional
        ``arrays(item) -> sequence of str or None``: the array fields a
        cached result must hold for this item (and the only ones loaded);
        None loads every stored array. Default: every stored array.

    Attributes
    ----------
    hits, misses : int
        Lookups answered from disk, and not.
    """

    def __init__(
        self,
        directory: str | os.PathLike[str],
        key: Callable[[Any], str],
        *,
        arrays: Callable[[Any], Sequence[str] | None] | None = None,
    ) -> None:
        self.store = ResultStore(directory)
        self.key = key
        self.arrays = arrays
        self.hits = 0
        self.misses = 0

    @property
    def directory(self) -> Path:
        """The cache directory."""
        return self.store.directory

    def get(self, item: Any) -> dict[str, Any] | None:
        """Return the cached result of ``item``, or None (see :meth:`ResultStore.read`)."""
        wanted = self.arrays(item) if self.arrays is not None else None
        out = self.store.read(self.key(item), arrays=wanted)
        if out is None:
            self.misses += 1
        else:
            self.hits += 1
        return out

    def put(self, item: Any, result: Mapping[str, Any]) -> None:
        """Store the result of ``item`` (see :meth:`ResultStore.write`)."""
        self.store.write(self.key(item), result)
