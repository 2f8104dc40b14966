"""psdbound.compute: content-hash keys, the disk cache, and cached task runs."""

from __future__ import annotations

import json

import numpy as np
import pytest

from psdbound.compute import (
    DiskCache,
    ResultStore,
    cache_key,
    dask_client,
    default_cache_dir,
    run_tasks,
)
from psdbound.errors import InputError

CALLS: list[dict] = []


def square(item: dict) -> dict:
    """A task: record the call, return a scalar and an array."""
    CALLS.append(item)
    x = float(item["x"])
    return {"x": x, "y": x * x, "grid": np.arange(3) * x}


def _key(item: dict) -> str:
    return cache_key({"task": "square", **item})


def test_key_is_stable_and_changes_with_any_input():
    a = cache_key({"station": "ESBC", "date": "2020-06-25", "settings": {"f_c": 1e-3}})
    assert a == cache_key({"settings": {"f_c": 1e-3}, "date": "2020-06-25", "station": "ESBC"})
    assert len(a) == 32 and int(a, 16) >= 0
    for changed in (
        {"station": "NYA1", "date": "2020-06-25", "settings": {"f_c": 1e-3}},
        {"station": "ESBC", "date": "2020-06-26", "settings": {"f_c": 1e-3}},
        {"station": "ESBC", "date": "2020-06-25", "settings": {"f_c": 2e-3}},
    ):
        assert cache_key(changed) != a
    assert len(cache_key([1, 2], length=12)) == 12


def test_rerun_reads_the_cache_and_does_not_call_again(tmp_path):
    CALLS.clear()
    items = [{"x": 1.0}, {"x": 2.0}, {"x": 3.0}]
    cache = DiskCache(tmp_path, key=_key)
    first = run_tasks(square, items, workers=0, cache=cache)
    assert len(CALLS) == 3 and first.n_computed == 3 and first.n_cached == 0
    assert [r["y"] for r in first.results] == [1.0, 4.0, 9.0]
    assert len(list(tmp_path.glob("*.json"))) == 3 and len(list(tmp_path.glob("*.npz"))) == 3
    again = DiskCache(tmp_path, key=_key)
    seen = []
    second = run_tasks(
        square, [*items, {"x": 4.0}], workers=0, cache=again, progress=lambda d, n: seen.append(n)
    )
    assert len(CALLS) == 4  # only the new item was computed
    assert second.from_cache == [True, True, True, False]
    assert (again.hits, again.misses) == (3, 1) and seen == [1]
    assert [r["y"] for r in second.results] == [1.0, 4.0, 9.0, 16.0]
    np.testing.assert_array_equal(second.results[2]["grid"], [0.0, 3.0, 6.0])
    assert isinstance(second.results[2]["grid"], np.ndarray)


def test_store_arrays_and_misses(tmp_path):
    store = ResultStore(tmp_path / "sub")
    store.write("k", {"a": 1, "v": np.linspace(0, 1, 5), "s": np.float64(2.5)})
    body = json.loads((tmp_path / "sub" / "k.json").read_text())
    assert body == {"result": {"a": 1, "s": 2.5}, "arrays": ["v"]}
    assert store.read("k", arrays=()) == {"a": 1, "s": 2.5}  # JSON part only
    np.testing.assert_array_equal(store.read("k")["v"], np.linspace(0, 1, 5))
    assert store.read("k", arrays=["w"]) is None  # a required array is absent: miss
    assert store.read("absent") is None
    (tmp_path / "sub" / "k.json").write_text("{torn")
    assert store.read("k") is None  # unreadable: miss, recomputed by the runner
    assert not [p for p in (tmp_path / "sub").iterdir() if p.name.startswith(".")]


def test_default_dir_and_bad_workers(tmp_path, monkeypatch):
    monkeypatch.setenv("PSDBOUND_CACHE", str(tmp_path))
    assert default_cache_dir("campaign") == tmp_path
    monkeypatch.delenv("PSDBOUND_CACHE")
    assert default_cache_dir("campaign").parts[-2:] == ("psdbound", "campaign")
    with pytest.raises(InputError, match="workers = -1 must be >= 0"):
        run_tasks(square, [{"x": 1.0}], workers=-1)
    assert run_tasks(square, [], workers=2).results == []  # nothing to do: no cluster started


def test_run_on_a_cluster_given_by_address(tmp_path):
    from dask.distributed import LocalCluster

    CALLS.clear()
    items = [{"x": 2.0}, {"x": 5.0}]
    with LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        cache = DiskCache(tmp_path, key=_key)
        run = run_tasks(square, items, scheduler=cluster.scheduler_address, cache=cache)
        assert [r["y"] for r in run.results] == [4.0, 25.0]  # item order, not completion order
        assert run.from_cache == [False, False] and len(CALLS) == 2
        again = run_tasks(square, items, scheduler=cluster.scheduler_address, cache=cache)
        assert again.from_cache == [True, True] and len(CALLS) == 2
    with pytest.raises(InputError, match="cannot reach the Dask scheduler"):
        with dask_client(scheduler="tcp://127.0.0.1:1", timeout_s=0.5):
            pass


def test_local_cluster_start_method():
    """Forked workers on Linux (they inherit the imports: ~0.6 s instead of 6-8 s); checked."""
    import sys

    from psdbound.compute import START_METHODS, dask_client, default_start_method

    assert default_start_method() == ("fork" if sys.platform.startswith("linux") else "spawn")
    assert "spawn" in START_METHODS
    with pytest.raises(InputError, match="start_method"):
        with dask_client(workers=1, start_method="teleport"):
            pass


def test_code_digest_keys_results_to_the_code_that_computed_them():
    """A version number stays put while the code changes: caches key on the source digest."""
    import re

    from psdbound.version import code_digest

    d = code_digest()
    assert re.fullmatch("[0-9a-f]{16}", d) and d == code_digest()


def test_passes_share_one_lazy_client(tmp_path, monkeypatch):
    """Two passes, one cluster; every result cached: no cluster at all.

    A campaign fits its days, then fits some again: a second local cluster forked after
    the first one's threads started could hang (seen: 0 % CPU after the first pass).
    """
    import contextlib

    from dask.distributed import LocalCluster

    import psdbound.compute.cluster as cluster_mod

    opened = []
    with LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:

        @contextlib.contextmanager
        def counting(**kw):
            opened.append(kw)
            with dask_client(scheduler=cluster.scheduler_address) as c:
                yield c

        monkeypatch.setattr(cluster_mod, "dask_client", counting)
        cache = DiskCache(tmp_path, key=_key)
        with cluster_mod.lazy_client(workers=2) as client:
            first = run_tasks(square, [{"x": 1.0}, {"x": 2.0}], cache=cache, client=client)
            second = run_tasks(square, [{"x": 3.0}], cache=cache, client=client)
        assert [r["y"] for r in first.results + second.results] == [1.0, 4.0, 9.0]
        assert len(opened) == 1
        with cluster_mod.lazy_client(workers=2) as client:
            again = run_tasks(square, [{"x": 3.0}], cache=cache, client=client)
        assert again.from_cache == [True] and len(opened) == 1


def test_a_cache_that_cannot_be_written_warns_and_the_run_goes_on(tmp_path):
    from psdbound.common.notices import PsdboundWarning

    afile = tmp_path / "afile"
    afile.write_text("x")  # the cache folder is a file: nothing can be written below it
    store = ResultStore(afile)
    with pytest.warns(PsdboundWarning, match="cache not written"):
        store.write("k", {"a": 1, "b": np.arange(3)})
    assert store.read("k") is None and afile.read_text() == "x"
