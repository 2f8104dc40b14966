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
    code = cli([
        "cutoff", "--lat", "41.84", "--lon", "-87.63", "--days", "2020-01-06", "--workers", "0",
        "--name", "CHICAGO", "--out", str(out), "--cache-dir", str(tmp_path / "c"),
    ])  # fmt: skip
    assert code == 0
    printed = capsys.readouterr().out
    assert "recommended f_c =" in printed
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        "cutoff_CHICAGO.csv",
        "cutoff_CHICAGO.json",
        "cutoff_CHICAGO_envelopes.png",
        "cutoff_CHICAGO_psd.png",
    ]
    data = json.loads((out / "cutoff_CHICAGO.json").read_text())
    assert data["orbit_source"] == "nominal:G:24"
    assert data["settings"]["f107_sfu"] == 70.0
    assert data["summary"]["n_series"] == len(data["rows"]) >= 20
    lines = (out / "cutoff_CHICAGO.csv").read_text().splitlines()
    assert lines[0].startswith("date,sat,f_c_hz,tau_c_min")
    assert len(lines) == 1 + data["summary"]["n_series"]
    assert (out / "cutoff_CHICAGO_psd.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--lat", "95", "--lon", "0"], "latitude 95.0 deg is out of range"),
        (["--lat", "41"], "--lat and --lon go together"),
        (["--lat", "41", "--lon", "0", "--days", "1979-12-31"], "outside the supported range"),
        (["--lat", "41", "--lon", "0", "--frequency", "L9"], "unknown carrier 'L9'"),
        ([], "give --lat and --lon for a station, or --map"),
    ],
)
def test_cli_bad_input(tmp_path, argv, message):
    with pytest.raises(InputError, match=message):
        cli(["cutoff", "--workers", "0", "--out", str(tmp_path), *argv])


@pytest.mark.slow
def test_cli_map_of_20_stations_through_dask(tmp_path, capsys):
    out = tmp_path / "map"
    code = cli([
        "cutoff", "--map", "--days", "2020-01-06", "--workers", "2", "--out", str(out),
        "--cache-dir", str(tmp_path / "c"), "--lat", "41.84", "--lon", "-87.63",
    ])  # fmt: skip
    assert code == 0
    printed = capsys.readouterr().out
    assert "nearest station to (41.84, -87.63): SASK" in printed
    lines = (out / "cutoff_map.csv").read_text().splitlines()
    assert len(lines) == 21 and lines[0].startswith("name,lat_deg,lon_deg")
    data = json.loads((out / "cutoff_map.json").read_text())
    assert [s["name"] for s in data["stations"]] == [s.name for s in MAP_STATIONS]
    assert all(s["n_series"] > 10 and s["recommended_f_c_hz"] > 0 for s in data["stations"])
    assert (out / "cutoff_map.png").read_bytes()[:4] == b"\x89PNG"
