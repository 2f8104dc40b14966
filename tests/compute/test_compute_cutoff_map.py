"""The cutoff map on the compute layer: a re-run reads the cache and computes nothing."""

from __future__ import annotations

import pytest

import psdbound.ionosphere.batch as batch
from psdbound.ionosphere import CutoffSettings, Station, map_cutoffs, station_cutoffs
from psdbound.ionosphere.tasks import station_day

STATIONS = (Station("CHI", 41.84, -87.63), Station("SASK", 52.20, -106.40))
KW = {
    "stations": STATIONS,
    "satellites": ("G01", "G02"),
    "settings": CutoffSettings(grid_size=11, ut_step_h=2.0),
    "workers": 0,
}


@pytest.fixture
def calls(monkeypatch):
    seen: list[str] = []

    def counting(spec):
        seen.append(f"{spec['lat_deg']} {spec['date']}")
        return station_day(spec)

    monkeypatch.setattr(batch, "station_day", counting)
    return seen


def test_map_rerun_reads_the_cache(tmp_path, calls):
    cache = tmp_path / "cache"
    first = map_cutoffs(["2020-01-06"], cache_dir=cache, **KW)
    assert len(calls) == 2 and [s.from_cache for s in first.stations] == [[False], [False]]
    assert len(list(cache.glob("*.json"))) == 2 and not list(cache.glob("*.npz"))
    second = map_cutoffs(["2020-01-06"], cache_dir=cache, **KW)
    assert len(calls) == 2  # nothing recomputed
    assert [s.from_cache for s in second.stations] == [[True], [True]]
    assert second.rows() == first.rows()
    # a changed setting is a different entry: both stations recomputed
    other = {**KW, "settings": CutoffSettings(grid_size=11, ut_step_h=2.0, drop_db=30.0)}
    map_cutoffs(["2020-01-06"], cache_dir=cache, **other)
    assert len(calls) == 4
    # a station run needs the delays the map did not keep: computed once, then cached
    kw = {
        "satellites": KW["satellites"],
        "settings": KW["settings"],
        "workers": 0,
        "keep_series": True,
    }
    res = station_cutoffs(41.84, -87.63, ["2020-01-06"], name="CHI", cache_dir=cache, **kw)
    assert len(calls) == 5 and res.from_cache == [False]
    assert res.series_by_date["2020-01-06"]["sats"] == ["G01", "G02"]
    again = station_cutoffs(41.84, -87.63, ["2020-01-06"], name="CHI", cache_dir=cache, **kw)
    assert len(calls) == 5 and again.from_cache == [True]
    assert [r["f_c_hz"] for r in again.rows] == [r["f_c_hz"] for r in res.rows]
    assert again.summary()["recommended_f_c_hz"] == first.rows()[0]["recommended_f_c_hz"]
