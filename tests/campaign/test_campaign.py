"""Campaigns: station-days on Dask tasks, cached; each day judged as fit does, tested held out."""

from __future__ import annotations

import importlib.util
import json
import shutil

import numpy as np
import pytest

import psdbound
from psdbound.campaign import plan_campaign, run_campaign, write_campaign
from psdbound.campaign.pool import pool_station
from psdbound.campaign.tasks import station_day_task
from psdbound.cli.main import main
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.simulate import preset, simulate


def _simulated_day(root, k: int, start: str):
    """One simulated day of station DEMO (30 s, 12 h), as `simulate` names its files."""
    sc = preset("demo").replace(
        name="DEMO",
        start_gps=start,
        duration_s=12 * 3600.0,
        interval_s=30.0,
        dual_antenna=False,
        seed=11 + k,
    )
    return simulate(sc, root / f"sim{k}")


@pytest.fixture(scope="module")
def two_days(tmp_path_factory):
    """Two simulated days of one station, the files as `simulate` wrote them (no renaming)."""
    root = tmp_path_factory.mktemp("campaign")
    obs, nav = [], []
    for k, start in enumerate(("2020-11-24T06:00:00", "2020-11-25T06:00:00")):
        res = _simulated_day(root, k, start)
        obs.append(res.obs_paths[0])
        nav.append(res.nav_path)
    return root, obs, nav


@pytest.fixture(scope="module")
def two_day_run(two_days, tmp_path_factory):
    _, obs, nav = two_days
    cache = tmp_path_factory.mktemp("cache")
    return run_campaign(obs, nav, workers=0, cache_dir=cache), cache


def test_simulate_output_matched_by_content(two_days):
    _, obs, nav = two_days
    assert obs[0].name.endswith("-A_MO.rnx.gz") and nav[0].name.endswith("_MN.rnx.gz")
    plan = plan_campaign(obs[::-1], nav[::-1])
    assert [(p.station, p.day) for p in plan] == [("DEMO", "2020-11-24"), ("DEMO", "2020-11-25")]
    assert [p.nav for p in plan] == [str(nav[0]), str(nav[1])]


def test_renamed_nav_matched_by_content(two_days, tmp_path):
    _, obs, nav = two_days
    # names that say the wrong day: the content decides
    wrong = [tmp_path / "brdc3300.20n.gz", tmp_path / "brdc3290.20n.gz"]
    for src, dst in zip(nav, wrong, strict=True):
        shutil.copy(src, dst)
    plan = plan_campaign(obs, wrong)
    assert [p.nav for p in plan] == [str(wrong[0]), str(wrong[1])]


def test_missing_nav_names_the_files_and_their_shares(two_days, tmp_path):
    _, obs, nav = two_days
    with pytest.raises(InputError) as exc:
        plan_campaign(obs, nav[:1])
    msg = str(exc.value)
    assert obs[1].name in msg and "no navigation file covers" in msg
    assert f"{nav[0].name} (0 %" in msg  # the candidate and the share of the day it covers


def test_a_day_several_files_cover_uses_the_stations_own_then_the_first_given(two_days, tmp_path):
    """Each station's own broadcast file of a day: one is used, and a warning says which."""
    _, obs, nav = two_days
    twin = tmp_path / "twin_MN.rnx.gz"
    shutil.copy(nav[0], twin)
    assert nav[0].name[:4].upper() == "DEMO"  # the station's own file
    for given in ([nav[0], twin, nav[1]], [twin, nav[0], nav[1]]):
        with pytest.warns(PsdboundWarning) as caught:
            plan = plan_campaign(obs[:1], given)
        assert plan[0].nav == str(nav[0])
        msg = " ".join(str(w.message) for w in caught)
        assert obs[0].name in msg and "2 navigation files cover this day" in msg
        assert f"used {nav[0].name} (100 %" in msg and "the station's own file" in msg
        assert "not used: twin_MN.rnx.gz (100 %" in msg
        assert plan[0].nav_note and plan[0].nav_note in msg
    other = tmp_path / "othr_MN.rnx.gz"
    shutil.copy(nav[0], other)
    with pytest.warns(PsdboundWarning, match=r"used twin_MN.rnx.gz .*\(the first given\)"):
        plan = plan_campaign(obs[:1], [twin, other, nav[1]])
    assert plan[0].nav == str(twin)


def test_day_verdicts_are_fits(two_days, two_day_run):
    _, obs, nav = two_days
    res, _ = two_day_run
    assert [d["verdict"] for d in res.days] == ["bounded", "bounded"]
    one = psdbound.fit(obs[1], nav[1], inputs={"method": "df"})
    day = res.days[1]
    assert (day["verdict"], day["verdict_reasons"]) == (one.verdict, one.verdict_reasons)
    assert day["sigma_gm_m"] == pytest.approx(one.bound.sigma_gm_m, rel=1e-12)
    assert day["nav"] == nav[1].name and day["in_pool"] is True
    assert res.verdict == "bounded"
    st = res.stations[0]
    assert (st["verdict"], st["n_pooled"], st["excluded_days"]) == ("bounded", 2, [])
    assert "low frequencies" in [c["rule"] for c in st["verdict_checks"]]


def test_held_out_rows_and_cache(two_days, two_day_run, tmp_path):
    _, obs, nav = two_days
    res, cache = two_day_run
    assert res.n_computed == 2 and res.n_cached == 0
    assert len(res.stations) == 1 and res.stations[0]["n_days"] == 2
    assert len(res.held_out) == 2
    for row in res.held_out:
        # same truth both days: the other day's bound holds on every window, and the filter
        # designed with it bounds each window's own spectrum
        assert row["windows_covered_fraction"] == 1.0 and row["kf_windows_bounded_fraction"] == 1.0
        assert 0 < row["kf_max_generalized_eigenvalue"] <= 1.0
        assert np.isfinite(row["worst_excess_db"])
    again = run_campaign(obs, nav, workers=0, cache_dir=cache)
    assert again.n_computed == 0 and again.n_cached == 2
    assert again.held_out == res.held_out
    files = write_campaign(res, tmp_path / "out", pdf=False)
    doc = json.loads(files["json"].read_text())
    assert doc["schema"] == "psdbound-campaign/2" and doc["verdict"] == "bounded"
    assert [d["verdict"] for d in doc["days"]] == ["bounded", "bounded"]
    assert doc["held_out"][0]["day"] == "2020-11-24"


@pytest.fixture(scope="module")
def day_results(two_days):
    """The two station-day results with their window spectra (as the Dask tasks return them)."""
    _, obs, nav = two_days
    return [
        station_day_task(
            {"station": p.station, "day": p.day, "obs": list(p.obs), "nav": p.nav, "options": {}}
        )
        for p in plan_campaign(obs, nav)
    ]


def test_not_bounded_day_left_out_of_the_pool(day_results):
    days = [dict(d) for d in day_results]
    days[0].update(verdict="not-bounded", verdict_reasons=["data outside the bound: test"])
    row, pooled = pool_station(days)
    assert pooled == [days[1]] and row["pooled_days"] == ["2020-11-25"]
    assert row["excluded_days"] == [
        {"day": "2020-11-24", "verdict": "not-bounded", "reasons": ["data outside the bound: test"]}
    ]
    assert row["comparison_note"].startswith("one day: no day-to-day comparison")
    alone, _ = pool_station([days[1]])
    assert row["sigma_gm_m"] == alone["sigma_gm_m"] and row["verdict"] == alone["verdict"]
    days[1].update(verdict="failed", verdict_reasons=["no bound (fit exits 2): test"])
    row, pooled = pool_station(days)
    assert pooled == [] and row["verdict"] == "not-bounded" and row["sigma_gm_m"] is None
    assert row["verdict_reasons"][0].startswith("no bounded day left")


def test_cli_campaign_system_and_bad_output_folder(two_days, tmp_path, capsys):
    _, obs, nav = two_days
    out = tmp_path / "c"
    code = main(
        [
            "campaign",
            *map(str, obs),
            "--nav",
            *map(str, nav),
            "--out",
            str(out),
            "--workers",
            "0",
            "--cache-dir",
            str(tmp_path / "cache"),
            "--no-pdf",
            "--system",
            "G",
            "--elevation-mask-deg",
            "12",
        ]
    )
    assert code == 0, capsys.readouterr().err
    assert sorted(p.name for p in out.iterdir()) == [
        "campaign.html",
        "campaign.json",
        "days",
        "network.html",
    ]
    text = capsys.readouterr().out
    assert "campaign verdict: BOUNDED" in text and "held out" in text
    doc = json.loads((out / "campaign.json").read_text())
    if importlib.util.find_spec("jsonschema"):
        from psdbound.results import schema_errors

        assert schema_errors(doc, schema="campaign") == []
    assert doc["options"] == {"arcs": {"elevation_mask_deg": 12.0}}
    other = tmp_path / "other"
    other.mkdir()
    (other / "mine.txt").write_text("keep")
    code = main(
        [
            "campaign",
            *map(str, obs),
            "--nav",
            *map(str, nav),
            "--out",
            str(other),
            "--workers",
            "0",
            "--cache-dir",
            str(tmp_path / "cache"),
        ]
    )
    assert code == 2 and (other / "mine.txt").read_text() == "keep"


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--system", "X"], "--system"),
        (["--system", "E"], "E"),  # the simulated files hold GPS only
        (["--rule", "envelope", "--windows", "slide"], "pooled rule"),
    ],
)
def test_cli_campaign_bad_day_options(two_days, tmp_path, capsys, extra, message):
    _, obs, nav = two_days
    out = tmp_path / "c"
    try:
        code = main(
            [
                "campaign",
                *map(str, obs),
                "--nav",
                *map(str, nav),
                "--out",
                str(out),
                "--workers",
                "0",
                "--cache-dir",
                str(tmp_path / "cache"),
                *extra,
            ]
        )
    except SystemExit as exc:  # a choice the parser itself refuses
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and message in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_cli_campaign_exits_3_when_a_pool_is_not_bounded(two_days, tmp_path, capsys):
    _, obs, nav = two_days
    cfg = tmp_path / "strict.toml"
    cfg.write_text("[verdict]\nmin_tau_multiple = 100000.0\n")
    out = tmp_path / "c"
    code = main(
        [
            "campaign",
            *map(str, obs),
            "--nav",
            *map(str, nav),
            "--out",
            str(out),
            "--workers",
            "0",
            "--cache-dir",
            str(tmp_path / "cache"),
            "--config",
            str(cfg),
            "--no-pdf",
        ]
    )
    assert code == 3, capsys.readouterr().err
    doc = json.loads((out / "campaign.json").read_text())
    assert doc["verdict"] == "not-bounded"
    assert {d["verdict"] for d in doc["days"]} == {"not-bounded"}
    assert all(
        d["verdict_reasons"][0].startswith("too little stationary data") for d in doc["days"]
    )
    st = doc["stations"][0]
    assert st["verdict"] == "not-bounded" and st["n_pooled"] == 0
    assert [d["day"] for d in st["excluded_days"]] == ["2020-11-24", "2020-11-25"]
    assert doc["held_out"] == []
    page = (out / "campaign.html").read_text()
    assert "no bounded day left" in page and "<img" not in page


def test_one_day_station_says_what_is_missing(two_days, tmp_path):
    _, obs, nav = two_days
    res = run_campaign(obs[:1], nav, workers=0, cache_dir=tmp_path / "cache")
    assert res.held_out == [] and res.stations[0]["n_pooled"] == 1
    files = write_campaign(res, tmp_path / "out")
    page = files["html"].read_text()
    assert "one day: no day-to-day comparison" in page
    assert "<img" not in page  # no empty axes
    assert b"/Count 1" in files["pdf"].read_bytes()  # one text page, no placeholder figure
