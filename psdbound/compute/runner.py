"""Run independent tasks on Dask (or in this process), skipping cached ones.

:func:`run_tasks` maps a function over items: each item whose result the
cache holds is read back, the others are computed on a Dask cluster (see
:func:`~psdbound.compute.cluster.dask_client`) or, with ``workers=0`` and no
scheduler, one after the other in this process (debugging, tiny runs). Each
computed result is written to the cache as soon as it arrives, so an
interrupted run keeps its finished tasks and a re-run computes only what is
missing or changed.

The function and the items travel to the workers by pickle: the function
must be importable (module level) and the items picklable.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from psdbound.compute.cache import TaskCache
from psdbound.compute.cluster import dask_client
from psdbound.errors import InputError

__all__ = ["TaskRun", "run_tasks"]


@dataclass
class TaskRun:
    """Results of :func:`run_tasks`, in the order of the items.

    Attributes
    ----------
    results : list
        One result per item.
    from_cache : list of bool
        Per item, whether its result was read from the cache.
    elapsed_s : float
        Wall time of the run, s.
    """

    results: list[Any]
    from_cache: list[bool] = field(default_factory=list)
    elapsed_s: float = 0.0

    @property
    def n_cached(self) -> int:
        """Number of results read from the cache."""
        return sum(self.from_cache)

    @property
    def n_computed(self) -> int:
        """Number of results computed by this run."""
        return len(self.results) - self.n_cached


def run_tasks(
    func: Callable[[Any], Any],
    items: Iterable[Any],
    *,
    workers: int = 2,
    scheduler: str | None = None,
    cache: TaskCache | None = None,
    progress: Callable[[int, int], None] | None = None,
    client: Callable[[], Any] | None = None,
) -> TaskRun:
    """Compute ``func(item)`` for every item, reading cached results instead.

    Parameters
    ----------
    func : callable
        ``func(item) -> result``, module-level (it is pickled to the workers).
    items : iterable
        Task inputs (picklable).
    workers : int, default 2
        Worker processes of a local Dask cluster; 0 runs the tasks in this
        process without Dask. Ignored when ``scheduler`` is given.
    scheduler : str, optional
        Address of a running Dask scheduler to submit to instead.
    cache : TaskCache, optional
        E.g. a :class:`~psdbound.compute.cache.DiskCache`; None computes
        every item and stores nothing.
    progress : callable, optional
        ``progress(done, total)`` after each computed task (``total`` counts
        the tasks to compute, not the cached ones).
    client : callable, optional
        ``client() -> dask.distributed.Client`` to submit to (e.g. from
        :func:`~psdbound.compute.cluster.lazy_client`, shared by the passes
        of one run) instead of opening a cluster for this call. Not called
        with ``workers=0`` and no scheduler: the tasks then run in this process.

    Returns
    -------
    TaskRun
        Results in item order, with which came from the cache.

    Raises
    ------
    InputError
        For a negative ``workers`` or an unreachable scheduler; whatever
        ``func`` raises is re-raised.
    """
    t0 = time.perf_counter()
    if scheduler is None and workers < 0:
        raise InputError(f"workers = {workers} must be >= 0")
    todo_items = list(items)
    results: list[Any] = [None] * len(todo_items)
    cached = [False] * len(todo_items)
    if cache is not None:
        for i, item in enumerate(todo_items):
            hit = cache.get(item)
            if hit is not None:
                results[i], cached[i] = hit, True
    todo = [i for i in range(len(todo_items)) if not cached[i]]

    def done(j: int, result: Any, n_done: int) -> None:
        i = todo[j]
        results[i] = result
        if cache is not None:
            cache.put(todo_items[i], result)
        if progress:
            progress(n_done, len(todo))

    _compute(func, [todo_items[i] for i in todo], workers, scheduler, done, client)
    return TaskRun(results=results, from_cache=cached, elapsed_s=time.perf_counter() - t0)


def _compute(
    func: Callable[[Any], Any],
    items: list[Any],
    workers: int,
    scheduler: str | None,
    done: Callable[[int, Any, int], None],
    client: Callable[[], Any] | None = None,
) -> None:
    """Compute ``func`` over ``items``; call ``done(index, result, n_done)`` as each ends."""
    if not items:
        return
    if scheduler is None and workers == 0:
        for j, item in enumerate(items):
            done(j, func(item), j + 1)
        return
    if client is not None:
        _submit(client(), func, items, done)
        return
    with dask_client(workers=workers, scheduler=scheduler) as opened:
        _submit(opened, func, items, done)


def _submit(
    client: Any, func: Callable[[Any], Any], items: list[Any], done: Callable[[int, Any, int], None]
) -> None:
    """Map ``func`` over ``items`` on ``client``; call ``done`` as each result arrives."""
    from dask.distributed import as_completed

    futures = client.map(func, items, pure=False)
    index = {f.key: j for j, f in enumerate(futures)}
    for n_done, fut in enumerate(as_completed(futures), start=1):
        done(index[fut.key], fut.result(), n_done)
