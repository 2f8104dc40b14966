"""Campaigns: station-days on Dask tasks, cached; each day tested against the others."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from psdbound.campaign import plan_campaign, run_campaign, write_campaign
from psdbound.cli.main import main
from psdbound.errors import InputError
from psdbound.simulate import preset, simulate


@pytest.fixture(scope="module")
def two_days(tmp_path_factory):
    """Two simulated days of one station (30 s, 12 h each), RINEX-style names with the day."""
    root = tmp_path_factory.mktemp("campaign")
    obs, nav = [], []
    for k, start in enumerate(("2020-11-24T06:00:00", "2020-11-25T06:00:00")):
        sc = preset("demo").replace(name="DEMO", start_gps=start, duration_s=12 * 3600.0,
                                    interval_s=30.0, dual_antenna=False, seed=11 + k)  # fmt: skip
        res = simulate(sc, root / f"sim{k}")
        doy = 329 + k
        o = root / f"DEMO00USA_R_2020{doy}0600_12H_30S_MO.rnx.gz"
        n = root / f"DEMO00USA_R_2020{doy}0000_01D_GN.rnx.gz"
        shutil.copy(res.obs_paths[0], o)
        shutil.copy(res.nav_path, n)
        obs.append(o)
        nav.append(n)
    return root, obs, nav


def test_plan_groups_by_station_and_day(two_days):
    _, obs, nav = two_days
    plan = plan_campaign(obs[::-1], nav)
    assert [(p.station, p.day) for p in plan] == [(plan[0].station, "2020-11-24"),
                                                 (plan[0].station, "2020-11-25")]  # fmt: skip
    assert plan[0].nav.endswith("20203290000_01D_GN.rnx.gz")
    with pytest.raises(InputError, match="no single navigation file for 2020-11-25"):
        plan_campaign(obs, nav[:1])


def test_held_out_rows_and_cache(two_days, tmp_path):
    _, obs, nav = two_days
    cache = tmp_path / "cache"
    res = run_campaign(obs, nav, workers=0, cache_dir=cache)
    assert res.n_computed == 2 and res.n_cached == 0
    assert all(d["ok"] for d in res.days), res.days
    assert len(res.stations) == 1 and res.stations[0]["n_days"] == 2
    assert len(res.held_out) == 2
    for row in res.held_out:
        for key in ("station", "day", "windows_covered_fraction", "worst_excess_db",
                    "kf_max_generalized_eigenvalue"):  # fmt: skip
            assert key in row
        # same truth both days: the other day's bound holds on most windows
        assert row["windows_covered_fraction"] >= 0.8
        # the truth is each held-out window's own spectrum (a GM + white fit that adds no
        # power below the band): covered windows and the filter check tell one story
        assert row["windows_covered_fraction"] == 1.0 and row["kf_windows_bounded_fraction"] == 1.0
        assert 0 < row["kf_max_generalized_eigenvalue"] <= 1.0
        assert np.isfinite(row["worst_excess_db"])
    again = run_campaign(obs, nav, workers=0, cache_dir=cache)
    assert again.n_computed == 0 and again.n_cached == 2
    assert again.held_out == res.held_out
    files = write_campaign(res, tmp_path / "out", pdf=False)
    doc = json.loads(files["json"].read_text())
    assert doc["held_out"][0]["day"] == "2020-11-24" and "campaign.html" in str(files["html"])


def test_cli_campaign_and_bad_output_folder(two_days, tmp_path, capsys):
    _, obs, nav = two_days
    out = tmp_path / "c"
    code = main(["campaign", *map(str, obs), "--nav", *map(str, nav), "--out", str(out),
                 "--workers", "0", "--cache-dir", str(tmp_path / "cache"), "--no-pdf"])  # fmt: skip
    assert code == 0, capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == ["campaign.html", "campaign.json"]
    assert "held out" in capsys.readouterr().out
    other = tmp_path / "other"
    other.mkdir()
    (other / "mine.txt").write_text("keep")
    code = main(["campaign", *map(str, obs), "--nav", *map(str, nav), "--out", str(other),
                 "--workers", "0", "--cache-dir", str(tmp_path / "cache")])  # fmt: skip
    assert code == 2 and (other / "mine.txt").read_text() == "keep"
