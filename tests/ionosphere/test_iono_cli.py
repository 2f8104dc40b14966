"""The ``cutoff`` command line (station; the 20-station map is marked slow)."""

from __future__ import annotations

import argparse
import json

import pytest

from psdbound.errors import InputError
from psdbound.ionosphere import MAP_STATIONS

# --------------------------------------------------------------------------- command line


def cli(argv):
    from psdbound.cli.cutoff import add_parser

    parser = argparse.ArgumentParser(prog="psdbound")
    sub = parser.add_subparsers(dest="command")
    add_parser(sub)
    args = parser.parse_args(argv)
    return args.func(args)


def test_cli_station_writes_table_json_and_figures(tmp_path, capsys):
    out = tmp_path / "out"
    code = cli(
        [
            "cutoff",
            "--lat",
            "41.84",
            "--lon",
            "-87.63",
            "--days",
            "2020-01-06",
            "--workers",
            "0",
            "--name",
            "CHICAGO",
            "--out",
            str(out),
            "--cache-dir",
            str(tmp_path / "c"),
        ]
    )
    assert code == 0
    printed = capsys.readouterr().out
    assert "recommended f_c =" in printed
    names = sorted(p.name for p in out.iterdir())
    assert "residual criterion" in printed
    assert names == [
        "cutoff_CHICAGO.csv",
        "cutoff_CHICAGO.html",
        "cutoff_CHICAGO.json",
        "cutoff_CHICAGO_residual.png",
    ]
    data = json.loads((out / "cutoff_CHICAGO.json").read_text())
    assert data["orbit_source"] == "nominal:G:24"
    assert data["settings"]["f107_sfu"] == 70.0 and data["settings"]["criterion"] == "residual"
    s = data["summary"]
    assert s["n_series"] == len(data["rows"]) >= 20
    assert s["threshold_m"] == pytest.approx(1e-5) and len(s["by_margin"]) == 4
    for key in ("mean_f_c_hz", "min_f_c_hz", "max_f_c_hz", "recommended_f_c_hz"):
        assert 1e-4 < s[key] < 1e-2
    lines = (out / "cutoff_CHICAGO.csv").read_text().splitlines()
    assert lines[0].startswith("date,sat,f_c_hz,tau_c_min")
    assert len(lines) == 1 + data["summary"]["n_series"]
    assert (out / "cutoff_CHICAGO_residual.png").read_bytes()[:4] == b"\x89PNG"


def test_cli_legacy_is_the_periodogram_criterion(tmp_path, capsys):
    out = tmp_path / "out"
    code = cli(
        [
            "cutoff",
            "--lat",
            "41.84",
            "--lon",
            "-87.63",
            "--days",
            "2020-01-06",
            "--workers",
            "0",
            "--name",
            "CHI",
            "--out",
            str(out),
            "--no-cache",
            "--legacy",
            "--no-figures",
        ]
    )
    assert code == 0 and "relative criterion" in capsys.readouterr().out
    data = json.loads((out / "cutoff_CHI.json").read_text())
    assert data["settings"]["sampling_s"] == 12.0 and data["settings"]["criterion"] == "relative"
    assert "envelope" in data["rows"][0]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--lat", "95", "--lon", "0"], "latitude 95.0 deg is out of range"),
        (["--lat", "41"], "--lat and --lon go together"),
        (["--lat", "41", "--lon", "0", "--days", "1979-12-31"], "outside the supported range"),
        (["--lat", "41", "--lon", "0", "--frequency", "L9"], "unknown carrier 'L9'"),
        ([], "give --lat and --lon for a station, or --map"),
        (["--map", "--grid-step", "7,60"], "must divide 180 and 360"),
        (["--map", "--grid-step", "20"], "expected LAT,LON"),
    ],
)
def test_cli_bad_input(tmp_path, argv, message):
    with pytest.raises(InputError, match=message):
        cli(["cutoff", "--workers", "0", "--out", str(tmp_path), *argv])


@pytest.mark.slow
def test_cli_world_map_through_dask(tmp_path, capsys):
    """A coarse world map (2 x 2 grid, one day per layer) on a 2-worker local cluster."""
    out = tmp_path / "map"
    code = cli(
        [
            "cutoff",
            "--map",
            "--days",
            "2020-03-02",
            "--grid-step",
            "90,180",
            "--workers",
            "2",
            "--out",
            str(out),
            "--cache-dir",
            str(tmp_path / "c"),
            "--lat",
            "41.84",
            "--lon",
            "-87.63",
        ]
    )
    assert code == 0
    printed = capsys.readouterr().out
    assert "at (41.84, -87.63), F10.7 73.8 sfu (2020): f_c" in printed
    assert "grid interpolation at the stations (solar-min)" in printed
    lines = (out / "cutoff_map.csv").read_text().splitlines()
    assert len(lines) == 1 + 2 * (20 + 4) and lines[0].startswith("layer,f107_sfu,site")
    data = json.loads((out / "cutoff_map.json").read_text())
    assert data["compute"]["n_station_days"] == 2 * 24 and data["compute"]["workers"] == 2
    for layer in data["layers"]:
        assert [s["name"] for s in layer["stations"]] == [s.name for s in MAP_STATIONS]
        assert all(s["n_series"] > 10 and s["recommended_f_c_hz"] > 0 for s in layer["stations"])
    assert (out / "cutoff_map.png").read_bytes()[:4] == b"\x89PNG"
    pytest.importorskip("jsonschema")
    from psdbound.results import schema_errors

    assert schema_errors(data, schema="cutoff_map") == []
    html = (out / "cutoff_map.html").read_text()
    assert "World cutoff map: 20 reference stations and a 2 x 2 grid" in html
    assert 'href="cutoff_map.png"' in html
