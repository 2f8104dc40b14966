"""``psdbound inspect --nav``: the orbit's coverage, and why no arc results."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest
from conftest import ESBC_NAV, GRAS_OBS, shared_file

from psdbound.cli import main
from psdbound.io.write import write_nav_v3, write_obs_v3

_spec = importlib.util.spec_from_file_location(
    "orbit_samples", Path(__file__).resolve().parents[1] / "io" / "orbit_samples.py"
)
samples = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(samples)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("orbits")
    obs = samples.geometric_observations(samples.nominal("GE"))
    obs22 = samples.geometric_observations(
        samples.nominal("G", t0=samples.T2022), systems="G", t0=samples.T2022
    )
    return {
        "obs": write_obs_v3(d / "SYNT00XXX_R_20201770600_02H_30S_MO.rnx", obs),
        "obs2022": write_obs_v3(d / "SYNT00XXX_R_20223151700_02H_30S_MO.rnx", obs22),
        "gps_nav": write_nav_v3(d / "gps.rnx", samples.nominal("G")),
    }


def inspect(capsys, *args):
    code = main(["inspect", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def test_coverage_is_printed(files, capsys):
    code, out, _ = inspect(capsys, files["obs"], "--nav", files["gps_nav"], "--min-arc-min", "10")
    assert code == 0
    assert "orbit gps.rnx (navigation file): systems G; 2020-06-25 " in out
    assert "GPS (G): 12 of 12 observed satellites with a position\n" in out
    galileo = "Galileo (E): 0 of 11 observed satellites with a position (no E ephemerides in"
    assert galileo + " the file)" in out
    assert "G L1C-L2W: " in out and "elevation" in out


def test_system_missing_from_the_navigation_file(files, capsys):
    code, out, err = inspect(capsys, files["obs"], "--nav", files["gps_nav"], "--system", "E")
    assert code == 2
    assert "(no E ephemerides in the file)" in out
    assert err.strip().endswith(
        "gps.rnx: the navigation file has no Galileo (E) ephemerides (it has GPS (G)); observed "
        "systems: G, E: give a navigation file with Galileo (E) ephemerides or choose another "
        "system"
    )
    assert "second frequency" not in err


def test_navigation_file_of_another_day(files, capsys):
    code, out, err = inspect(capsys, files["obs2022"], "--nav", files["gps_nav"])
    assert code == 2
    assert "GPS (G): 0 of " in out and "(observations outside the file's time span)" in out
    assert "the navigation file covers 2020-06-25 " in err
    assert "use a navigation file of the observation day (2022-11-11, day of year 315)" in err


def test_reason_when_no_arc(files, capsys):
    code, out, _ = inspect(
        capsys, files["obs"], "--nav", files["gps_nav"], "--elevation-mask-deg", "89.9"
    )
    assert code == 0
    assert "G L1C-L2W: 0 arcs" in out
    reason = "no satellite tracked on both L1C and L2W (G) is above the elevation mask of 89.9"
    assert f"  no arc: {reason} deg at any epoch" in out


@pytest.mark.realdata
def test_gras_with_the_esbc_navigation_file(capsys):
    code, out, err = inspect(capsys, shared_file(GRAS_OBS), "--nav", shared_file(ESBC_NAV))
    assert code == 2
    assert f"orbit {ESBC_NAV} (navigation file): systems C E G J R; 2020-06-24" in out
    assert "GLONASS (R): 0 of 9 observed satellites with a position (observations outside" in out
    assert f"the observations of {GRAS_OBS} run from 2022-11-11 17:00 to 17:14 GPS time" in err
    assert err.strip().endswith(
        "use a navigation file of the observation day (2022-11-11, day of year 315)"
    )
