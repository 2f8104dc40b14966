"""Shared compute layer: Dask task runs with a content-hash disk cache.

Generic building blocks for batch work (the ionosphere cutoff map, a
campaign of station-days): nothing here knows what the tasks compute.

* :func:`run_tasks` -> :class:`TaskRun`: map a module-level function over
  task items on a Dask cluster (a local one of ``workers`` processes, a
  running scheduler by address, or in-process with ``workers=0``), reading
  cached results instead of recomputing them;
* :func:`dask_client`: the client context manager behind it;
* :class:`DiskCache` (a :class:`TaskCache`), :class:`ResultStore`,
  :func:`cache_key`, :func:`default_cache_dir`: results on disk keyed by a
  SHA-256 of their inputs, written atomically.

Example::

    from psdbound.compute import DiskCache, cache_key, run_tasks

    cache = DiskCache("cache/", key=lambda item: cache_key({"task": "square", **item}))
    run = run_tasks(square, [{"x": 1.0}, {"x": 2.0}], workers=2, cache=cache)
    run.results, run.n_cached
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.compute.cache import (
        CACHE_ENV,
        DiskCache,
        ResultStore,
        TaskCache,
        cache_key,
        default_cache_dir,
    )
    from psdbound.compute.cluster import (
        START_METHODS,
        dask_client,
        default_start_method,
        lazy_client,
    )
    from psdbound.compute.runner import TaskRun, run_tasks

__all__ = [
    "CACHE_ENV",
    "START_METHODS",
    "DiskCache",
    "ResultStore",
    "TaskCache",
    "TaskRun",
    "cache_key",
    "dask_client",
    "default_cache_dir",
    "default_start_method",
    "lazy_client",
    "run_tasks",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "CACHE_ENV": ("psdbound.compute.cache", "CACHE_ENV"),
    "DiskCache": ("psdbound.compute.cache", "DiskCache"),
    "ResultStore": ("psdbound.compute.cache", "ResultStore"),
    "TaskCache": ("psdbound.compute.cache", "TaskCache"),
    "cache_key": ("psdbound.compute.cache", "cache_key"),
    "default_cache_dir": ("psdbound.compute.cache", "default_cache_dir"),
    "START_METHODS": ("psdbound.compute.cluster", "START_METHODS"),
    "dask_client": ("psdbound.compute.cluster", "dask_client"),
    "lazy_client": ("psdbound.compute.cluster", "lazy_client"),
    "default_start_method": ("psdbound.compute.cluster", "default_start_method"),
    "TaskRun": ("psdbound.compute.runner", "TaskRun"),
    "run_tasks": ("psdbound.compute.runner", "run_tasks"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
