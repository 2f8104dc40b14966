"""Batch cutoff runs: day selection, stations, a 2-worker Dask run with a cache."""

from __future__ import annotations

import pytest

from psdbound.errors import InputError, NoDataError
from psdbound.ionosphere import (
    MAP_STATIONS,
    CutoffSettings,
    nearest_station,
    select_days,
    station_cutoffs,
)


def test_day_selection():
    days = select_days(2020)
    assert [d.isoformat() for d in days[:3]] == ["2020-01-06", "2020-02-03", "2020-03-02"]
    assert all(d.weekday() == 0 and d.day <= 7 for d in days) and len(days) == 12
    assert [d.isoformat() for d in select_days(2020, "2020-05-04, 2021-01-04")] == [
        "2020-05-04",
        "2021-01-04",
    ]
    with pytest.raises(InputError, match="outside the supported range"):
        select_days(2040)
    with pytest.raises(InputError, match="not a valid calendar date"):
        select_days(2020, "mondays")


def test_stations_and_nearest_lookup():
    assert len(MAP_STATIONS) == 20
    st, d = nearest_station(41.84, -87.63)
    assert st.name == "SASK"  # Saskatoon is nearer Chicago than Pie Town
    st, d = nearest_station(-66.0, 111.0)
    assert st.name == "CAS1" and d < 1.0
    with pytest.raises(InputError, match="latitude 95"):
        nearest_station(95.0, 0.0)


# --------------------------------------------------------------------------- batch / Dask


def test_dask_two_workers_and_cache(tmp_path):
    settings = CutoffSettings(grid_size=15, ut_step_h=1.0)
    kw = {
        "satellites": ("G01", "G02"),
        "settings": settings,
        "workers": 2,
        "cache_dir": tmp_path / "cache",
        "keep_series": True,
    }
    days = ["2020-01-06", "2020-07-06"]
    first = station_cutoffs(41.84, -87.63, days, name="CHI", **kw)
    assert first.from_cache == [False, False]
    assert len(first.rows) == 4 and {r["sat"] for r in first.rows} == {"G01", "G02"}
    s = first.summary()
    assert s["recommended_f_c_hz"] == s["max_f_c_hz"] == max(first.f_c_hz)
    assert s["min_f_c_hz"] <= s["mean_f_c_hz"] <= s["max_f_c_hz"]
    assert len(list((tmp_path / "cache").glob("*.json"))) == 2
    second = station_cutoffs(41.84, -87.63, days, name="CHI", **kw)
    assert second.from_cache == [True, True]
    assert [r["f_c_hz"] for r in second.rows] == [r["f_c_hz"] for r in first.rows]
    assert second.series_by_date["2020-01-06"]["sats"] == ["G01", "G02"]
    # any change of input is a different cache entry
    third = station_cutoffs(
        41.84,
        -87.63,
        days[:1],
        name="CHI",
        **{
            **kw,
            "workers": 0,
            "settings": CutoffSettings(grid_size=15, ut_step_h=1.0, margin_db=30.0),
        },
    )
    assert third.from_cache == [False]
    assert third.rows[0]["f_c_hz"] < first.rows[0]["f_c_hz"]


def test_dask_scheduler_address(tmp_path):
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster:
        res = station_cutoffs(
            41.84,
            -87.63,
            ["2020-01-06"],
            satellites=("G07",),
            scheduler=cluster.scheduler_address,
            settings=CutoffSettings(grid_size=11, ut_step_h=2.0),
            use_cache=False,
            cache_dir=tmp_path,
        )
        assert [r["sat"] for r in res.rows] == ["G07"]
        assert res.from_cache == [False]
    assert not list(tmp_path.iterdir())  # use_cache=False writes nothing


def test_station_run_no_satellite_above_mask(tmp_path):
    with pytest.raises(NoDataError, match="no satellite rises above the 89.9 deg"):
        station_cutoffs(
            41.84,
            -87.63,
            ["2020-01-06"],
            workers=0,
            cache_dir=tmp_path,
            settings=CutoffSettings(elevation_mask_deg=89.9),
        )
