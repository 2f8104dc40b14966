"""Dask ``distributed`` client: a local cluster by default, or a running scheduler.

:func:`dask_client` opens what the run needs and closes what it opened:

* no ``scheduler``: a :class:`~dask.distributed.LocalCluster` of ``workers``
  single-threaded worker processes (no dashboard, quiet logs), closed on
  exit with its client. On Linux the worker processes are **forked** from
  this one (``start_method="fork"``), so they inherit its imports: the
  cluster is ready in about 0.6 s instead of 6-8 s with Python's "spawn"
  (every worker re-importing SciPy, PyIRI and matplotlib), which is most of
  a station-year's time. ``start_method="spawn"`` restores Dask's default
  (use it if this process runs threads that hold locks while forking);
* a ``scheduler`` address (``tcp://host:8786``): a client of that running
  cluster (its workers need psdbound installed); only the client is closed.
"""

from __future__ import annotations

import contextlib
import logging
import sys
from collections.abc import Callable, Iterator
from typing import Any

from psdbound.errors import InputError

__all__ = ["START_METHODS", "dask_client", "default_start_method", "lazy_client"]

#: How local worker processes start: forked from this process, or fresh interpreters.
START_METHODS = ("fork", "spawn", "forkserver")


def default_start_method() -> str:
    """Return ``"fork"`` on Linux, else ``"spawn"`` (Dask's default)."""
    return "fork" if sys.platform.startswith("linux") else "spawn"


@contextlib.contextmanager
def dask_client(
    *,
    workers: int = 2,
    scheduler: str | None = None,
    processes: bool = True,
    timeout_s: float = 20.0,
    start_method: str | None = None,
) -> Iterator[Any]:
    """Open a Dask client for the duration of a ``with`` block.

    Parameters
    ----------
    workers : int, default 2
        Workers of the local cluster (ignored with ``scheduler``); at least 1.
    scheduler : str, optional
        Address of a running Dask scheduler to use instead of a local cluster.
    processes : bool, default True
        Local cluster workers are processes (True) or threads of this one.
    timeout_s : float, default 20
        How long to wait for the scheduler, s.
    start_method : {"fork", "spawn", "forkserver"}, optional
        How local worker processes start (default :func:`default_start_method`).

    Yields
    ------
    dask.distributed.Client

    Raises
    ------
    InputError
        For fewer than one local worker, or a scheduler that cannot be reached.
    """
    import dask
    from dask.distributed import Client, LocalCluster

    cluster = None
    if scheduler is None:
        if workers < 1:
            raise InputError(f"workers = {workers} must be >= 1 for a Dask cluster")
        method = start_method or default_start_method()
        if method not in START_METHODS:
            raise InputError(f"start_method {method!r} not in {START_METHODS}")
        with dask.config.set({"distributed.worker.multiprocessing-method": method}):
            cluster = LocalCluster(
                n_workers=workers,
                threads_per_worker=1,
                processes=processes,
                dashboard_address=None,
                silence_logs=logging.ERROR,
            )
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout=f"{timeout_s:g}s")
        except (OSError, TimeoutError) as exc:
            raise InputError(f"cannot reach the Dask scheduler at {scheduler!r}: {exc}") from None
    try:
        yield client
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


@contextlib.contextmanager
def lazy_client(*, workers: int = 2, scheduler: str | None = None) -> Iterator[Callable[[], Any]]:
    """Yield a function that opens one Dask client at its first call, closed on exit.

    For a run of several passes (a campaign's fits, then the days fitted
    again): every pass uses the same client, and none is opened when every
    result comes from the cache. A second local cluster would fork its
    workers from a process whose first client left threads running (its
    event loop), and a fork taken while another thread holds a lock can
    deadlock the child: a campaign stalled at 0 % CPU after its first pass.

    Parameters
    ----------
    workers : int, default 2
        Workers of the local cluster (:func:`dask_client`).
    scheduler : str, optional
        Address of a running scheduler instead.

    Yields
    ------
    callable
        ``get() -> dask.distributed.Client``.
    """
    with contextlib.ExitStack() as stack:
        opened: list[Any] = []

        def get() -> Any:
            if not opened:
                opened.append(
                    stack.enter_context(dask_client(workers=workers, scheduler=scheduler))
                )
            return opened[0]

        yield get
