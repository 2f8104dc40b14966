"""The isolated multipath as data: every sample with its direction, screening and window (#32)."""

from __future__ import annotations

import csv
import gzip

import numpy as np
import pytest

import psdbound
from psdbound.results.series_table import COLUMNS, series_table


@pytest.fixture(scope="module")
def demo():
    return psdbound.fit()


def test_every_isolated_sample_is_a_row_with_what_became_of_it(demo):
    tab = demo.series_table()
    n = demo.isolated.series.t_gps_s.size
    assert list(tab) == list(COLUMNS) and all(len(v) == n for v in tab.values())
    assert np.all((tab["elevation_deg"] > 0) & (tab["elevation_deg"] <= 90))
    assert np.all((tab["azimuth_deg"] >= 0) & (tab["azimuth_deg"] < 360))  # every DF sample
    # samples inside the windows: the time the document says the windows cover
    dt = demo.document["sampling"]["interval_s"]
    covered = demo.document["windows"]["covered_s"]
    assert (tab["window"] >= 0).sum() * dt == pytest.approx(covered, rel=0.01)
    assert np.all(tab["window"][tab["screened"] != ""] == -1)
    kept = demo.screened.series.t_gps_s.size
    assert (tab["screened"] == "").sum() == kept


def test_screened_spans_and_windows_are_marked_by_satellite_and_time():
    from types import SimpleNamespace

    t = np.arange(0.0, 300.0, 30.0)
    series = SimpleNamespace(
        t_gps_s=np.r_[t, t],
        value_m=np.zeros(20),
        elevation_deg=np.full(20, 40.0),
        arc_sats=("G01", "G02"),
        arc_bounds=lambda: [(0, 10), (10, 20)],
    )
    excluded = [{"sat": "G02", "start_gps_s": 60.0, "stop_gps_s": 120.0, "kind": "ionosphere"}]
    windows = [
        {"sats": "G01", "t_start_gps_s": 0.0, "t_stop_gps_s": 150.0},
        {"sats": "G02", "t_start_gps_s": 0.0, "t_stop_gps_s": 270.0},
    ]
    tab = series_table(series, None, excluded, windows)
    assert list(tab["screened"][10:]) == [""] * 2 + ["ionosphere"] * 3 + [""] * 5
    assert list(tab["window"][:10]) == [0] * 6 + [-1] * 4
    assert list(tab["window"][10:]) == [1, 1, -1, -1, -1, 1, 1, 1, 1, 1]
    assert np.isnan(tab["azimuth_deg"]).all()  # no arcs: no azimuth


def test_csv_round_trip_and_a_loaded_result_says_why_it_has_none(demo, tmp_path):
    path = demo.write_series(tmp_path / "series.csv.gz")
    with gzip.open(path, "rt") as f:
        rows = list(csv.DictReader(f))
    tab = demo.series_table()
    assert len(rows) == len(tab["t_gps_s"]) and list(rows[0]) == list(COLUMNS)
    k = len(rows) // 2
    assert float(rows[k]["value_m"]) == pytest.approx(tab["value_m"][k], abs=1e-6)
    assert int(rows[k]["window"]) == tab["window"][k] and rows[k]["sat"] == tab["sat"][k]
    out = tmp_path / "r.json"
    from psdbound.results import write_document

    write_document(out, demo.document)
    with pytest.raises(psdbound.InputError, match="holds no per-epoch series"):
        psdbound.load(out).series_table()


def test_fit_series_writes_the_table_with_the_report(tmp_path, capsys):
    from psdbound.cli.main import main

    out = tmp_path / "out"
    code = main(["fit", "--series", "--no-pdf", "--quiet", "--out", str(out)])
    assert code == 0
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "result.json", "series.csv.gz"]
    with gzip.open(out / "series.csv.gz", "rt") as f:
        head = f.readline().strip().split(",")
        first = f.readline().strip().split(",")
    assert head == list(COLUMNS) and len(first) == len(COLUMNS)
    assert str(out / "series.csv.gz") in capsys.readouterr().out
    # the configuration records it, so the run can be repeated as it was
    doc = psdbound.load(out / "result.json").document
    assert doc["provenance"]["configuration"]["output"]["series"] is True
