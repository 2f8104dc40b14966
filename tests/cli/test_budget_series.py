"""``psdbound budget`` over time (--nominal / --nav): outputs, exit 2 naming the option."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import ESBC_NAV, NYA1_NAV, shared_file

from psdbound.aviation import budget_report
from psdbound.cli import main

KMDE = ("--k-md-e", "5")  # a test K_md_e (required: the station broadcasts it)
ESBC_POSITION = "55.4936,8.4568,59.5"  # ESBC's header XYZ as WGS84 latitude, longitude, height


def _err_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.strip().count("\n") == 0, err
    return err


def test_nominal_ge_writes_json_and_figure(tmp_path, capsys):
    out = tmp_path / "vpl"
    argv = [
        "budget",
        *KMDE,
        "--nominal",
        "GE",
        "--position",
        ESBC_POSITION,
        "--hours",
        "6",
        "--val-m",
        "10",
        "--out",
        str(out),
    ]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "VPL over 72 epochs, 2009-01-01 00:00:00 to 2009-01-01 05:55:00 GPS time" in text
    assert "availability at VAL = 10 m: 100.00 % of epochs" in text
    assert f"wrote {out / 'vpl.json'}" in text and f"wrote {out / 'vpl.png'}" in text
    d = json.loads((out / "vpl.json").read_text())["vpl"]
    assert d["n_epochs"] == 72 and d["n_unavailable"] == 0 and d["availability"] == 1.0
    assert min(d["n_sats"]) >= 10 and d["elevation_mask_deg"] == 5.0
    assert d["orbit"].startswith("nominal: GPS 24-slot") and "Galileo Walker" in d["orbit"]
    assert d["options"]["x_air_m"] == 5000.0 and d["options"]["process"] == "SF"
    assert np.allclose(d["vpl_m"], np.maximum(d["vpl_h0_m"], d["vpl_eph_m"]))
    assert (out / "vpl.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporaries left


def test_nominal_options_reach_the_budget(capsys):
    argv = [
        "budget",
        *KMDE,
        "--nominal",
        "G",
        "--position",
        "36.37,127.36,100",
        "--hours",
        "1",
        "--step-s",
        "600",
        "--mask-deg",
        "10",
        "--process",
        "IF",
        "--tau-gnd",
        "30",
        "--tau-air",
        "30",
        "--x-air-km",
        "20",
        "--start",
        "2020-06-25T12:00",
    ]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "IF L1, tau 30/30 s" in text and "x_air = 20 km" in text
    assert "VPL over 6 epochs, 2020-06-25 12:00:00 to 2020-06-25 12:50:00" in text
    assert "satellites above 10 deg" in text and "Galileo" not in text


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--position", "55.5,8.5"], "--position '55.5,8.5': expected LAT,LON,H (deg, deg, m)"),
        (["--position", "a,b,c"], "--position 'a,b,c': expected LAT,LON,H"),
        (["--position", "91,8,0"], "latitude 91.0 deg is outside [-90, 90]"),
        ([], "--position LAT,LON,H is required"),
        (["--position", ESBC_POSITION, "--hours", "0"], "--hours must be a number > 0 h, got 0"),
        (["--position", ESBC_POSITION, "--hours", "-2"], "--hours must be a number > 0 h, got -2"),
        (["--position", ESBC_POSITION, "--step-s", "0"], "--step-s must be a number > 0 s, got 0"),
        (["--position", ESBC_POSITION, "--mask-deg", "-1"], "--mask-deg must be in [0, 90)"),
        (["--position", ESBC_POSITION, "--val-m", "0"], "--val-m must be a number > 0 m"),
        (["--position", ESBC_POSITION, "--start", "2009-13-01"], "--start '2009-13-01': expected"),
        (["--position", ESBC_POSITION, "--systems", "G"], "--systems applies to --nav"),
        (["--position", ESBC_POSITION, "--receivers", "6"], "no tabulated K_ffmd for --receivers"),
        (["--position", ESBC_POSITION, "--step-s", "0.1"], "at most 100000 (raise --step-s)"),
    ],
)
def test_bad_nominal_input_exits_2_naming_the_option(tmp_path, capsys, extra, message):
    out = tmp_path / "o"
    assert main(["budget", *KMDE, "--nominal", "GE", *extra, "--out", str(out)]) == 2
    assert message in _err_line(capsys)
    assert not out.exists()


def test_modes_are_exclusive_and_series_options_need_a_series(capsys):
    sats = [a for s in ("10,12", "80,25", "150,38", "200,47") for a in ("--sat", s)]
    for argv in ([*sats, "--nominal", "GE"], ["--nominal", "GE", "--nav", "x.rnx"]):
        with pytest.raises(SystemExit) as exc:  # argparse: usage error, exit 2
            main(["budget", *KMDE, *argv])
        assert exc.value.code == 2
        err = _err_line(capsys)
        assert "not allowed with argument" in err and argv[-2] in err
    assert main(["budget", *KMDE, *sats, "--position", ESBC_POSITION, "--hours", "3"]) == 2
    assert "--position, --hours apply only to --nominal / --nav" in _err_line(capsys)
    assert main(["budget"]) == 2
    assert "at least 4 --sat AZ,EL (got 0), or --nominal / --nav" in _err_line(capsys)


def test_sat_mode_output_is_the_budget_report(capsys):
    pairs = [(10, 12), (80, 25), (150, 38), (200, 47), (260, 60), (320, 75)]
    argv = [
        "budget",
        *KMDE,
        *[a for az, el in pairs for a in ("--sat", f"{az},{el}")],
        "--tau-gnd",
        "30",
        "--tau-air",
        "30",
        "--x-air-km",
        "12",
    ]
    assert main(argv) == 0
    az, el = zip(*pairs, strict=True)
    expected = budget_report(
        az,
        el,
        k_md_e=5.0,
        n_receivers=3,
        process="SF",
        base_frequency="L1",
        tau_gnd_s=30.0,
        tau_air_s=30.0,
        gad="B",
        rho=0.1,
        x_air_m=12000.0,
        xi_formula="exact",
    )
    assert capsys.readouterr().out == expected + "\n"


@pytest.mark.realdata
def test_nav_file_day_at_esbc(tmp_path, capsys):
    nav = shared_file(ESBC_NAV)
    argv = ["budget", *KMDE, "--nav", str(nav), "--position", ESBC_POSITION, "--out", str(tmp_path)]
    assert main(argv) == 0
    text = capsys.readouterr().out
    # the file's records run from 2020-06-24 19:50 (Galileo) to 06-26 00:00 (GPS):
    # the default start is 00:00 of the first whole day they cover
    assert "VPL over 288 epochs, 2020-06-25 00:00:00 to 2020-06-25 23:55:00" in text
    assert "unavailable (< 4 satellites or singular geometry): 0 epoch(s)" in text
    d = json.loads((tmp_path / "vpl.json").read_text())["vpl"]
    assert min(d["n_sats"]) >= 10 and d["orbit"].endswith(ESBC_NAV)


@pytest.mark.realdata
def test_nav_start_outside_the_file_span_exits_2_with_the_span(capsys):
    nav = shared_file(ESBC_NAV)
    argv = [
        "budget",
        *KMDE,
        "--nav",
        str(nav),
        "--position",
        ESBC_POSITION,
        "--start",
        "2020-06-27",
    ]
    assert main(argv) == 2
    err = _err_line(capsys)
    assert "--start 2020-06-27 00:00:00 is outside the span of the file for systems GE" in err
    assert "2020-06-24 15:50:00 to 2020-06-26 04:00:00 GPS time" in err and ESBC_NAV in err


@pytest.mark.realdata
def test_nav_without_the_requested_system_exits_2(capsys):
    nav = shared_file(NYA1_NAV)  # GPS only
    assert main(["budget", *KMDE, "--nav", str(nav), "--position", "78.93,11.87,80"]) == 2
    err = _err_line(capsys)
    assert "no Galileo (E) orbits for --systems GE; the file has G (give --systems G)" in err
    assert (
        main(
            [
                "budget",
                *KMDE,
                "--nav",
                str(nav),
                "--position",
                "78.93,11.87,80",
                "--systems",
                "G",
                "--hours",
                "1",
            ]
        )
        == 0
    )
    assert "VPL over 12 epochs" in capsys.readouterr().out


def test_missing_nav_file_exits_2(tmp_path, capsys):
    f = tmp_path / "none.rnx"
    assert main(["budget", *KMDE, "--nav", str(f), "--position", ESBC_POSITION]) == 2
    assert "none.rnx: file not found" in _err_line(capsys)


def test_k_md_e_is_required_and_named_with_its_source(tmp_path, capsys):
    sats = [a for s in ("10,12", "80,25", "150,38", "200,47", "260,60") for a in ("--sat", s)]
    assert main(["budget", *sats]) == 2
    assert "--k-md-e is required" in _err_line(capsys)
    assert main(["budget", *sats, "--k-md-e", "0"]) == 2
    assert "--k-md-e must be a number > 0" in _err_line(capsys)
    assert main(["budget", *sats, "--k-md-e", "5.085", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    assert "K_md_e = 5.085" in text and "user-supplied" in text and "Type 2 message" in text
    assert "K_ffmd = 5.810" in text and "not verified" in text and "xi formula: exact" in text
    d = json.loads((tmp_path / "budget.json").read_text())["budget"]
    assert d["multipliers"]["k_md_e"]["value"] == 5.085
    assert "user-supplied" in d["multipliers"]["k_md_e"]["source"]
    assert d["multipliers"]["k_ffmd"]["value"] == 5.810
    assert d["options"]["xi_formula"] == "exact" and "GAD_PARAMETERS" in d["sources"]
    assert d["vpl_m"] == max(d["vpl_h0_m"], d["vpl_eph_m"]) and len(d["satellites"]) == 5
    assert main(["budget", *sats, *KMDE, "--xi-formula", "seed"]) == 0
    assert "xi formula: seed" in capsys.readouterr().out
    out = tmp_path / "series"
    assert (
        main(
            [
                "budget",
                "--nominal",
                "G",
                "--position",
                ESBC_POSITION,
                "--hours",
                "1",
                *KMDE,
                "--k-ffmd",
                "6",
                "--out",
                str(out),
            ]
        )
        == 0
    )
    k = json.loads((out / "vpl.json").read_text())["vpl"]["options"]["multipliers"]
    assert k["k_ffmd"] == {"value": 6.0, "source": "user-supplied"}
    assert k["k_md_e"]["value"] == 5.0
