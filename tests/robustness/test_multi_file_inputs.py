"""Inputs of several files, as users give them (regression tests of reported crashes and hints).

* the same observation file given twice to ``fit`` (was exit 1, ValueError);
* a zip archive of several navigation files (was "damaged or truncated file?");
* ``--nav`` given twice (the last one only was used);
* a station's zip of observations and navigation given as OBS without ``--nav``
  (was refused);
* ``--system R`` on a GPS-only file (the message listed no system);
* an epoch repeated with its seconds written ``29.9999999`` (was exit 1).

Small synthetic files (a nominal GPS constellation seen from near ESBC,
seeded), no ../shared/data.
"""

from __future__ import annotations

import importlib.util
import zipfile
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from fuzzlib import check_run, run_cli
from samples import moving_observations

from psdbound.errors import InputError
from psdbound.io import Navigation, PreciseOrbit, read_obs, read_orbit
from psdbound.io.archive import file_kind
from psdbound.io.navigation import merge_navigation
from psdbound.io.sp3 import merge_precise
from psdbound.io.write import format_obs_v3, write_nav_v3, write_obs_v3
from psdbound.pipeline.config import InputsConfig
from psdbound.pipeline.inputs import read_inputs

_spec = importlib.util.spec_from_file_location(
    "orbit_samples", Path(__file__).resolve().parents[1] / "io" / "orbit_samples.py"
)
samples = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(samples)

T0 = samples.T2020


def _split(nav: Navigation, t_split: float) -> tuple[Navigation, Navigation]:
    """The records before and from ``t_split`` (two files of one day)."""
    g = nav.ephemerides["G"]
    early = g.toe_gps_s < t_split
    return (
        replace(nav, ephemerides={"G": g.select(early)}),
        replace(nav, ephemerides={"G": g.select(~early)}),
    )


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("multi")
    nav = samples.nominal("G")
    a, b = _split(nav, T0 + 3600.0)
    out = {
        "obs": write_obs_v3(d / "SYNT1770.20o", samples.geometric_observations(nav, "G")),
        "nav": write_nav_v3(d / "brdc.rnx", nav),
        "nav_a": write_nav_v3(d / "brdc_a.rnx", a),
        "nav_b": write_nav_v3(d / "brdc_b.rnx", b),
    }
    out["navs_zip"] = _zip(d / "navs.zip", out["nav_a"], out["nav_b"])
    out["station_zip"] = _zip(d / "station.zip", out["obs"], out["nav"])
    out["obs_zip"] = _zip(
        d / "obs.zip",
        out["obs"],
        write_obs_v3(d / "SYNT1771.20o", samples.geometric_observations(nav, "G", t0=T0 + 7200.0)),
    )
    return out


def _zip(path: Path, *members: Path) -> Path:
    with zipfile.ZipFile(path, "w") as z:
        for m in members:
            z.write(m, m.name)
    return path


# ------------------------------------------------------------- the same file twice


@pytest.mark.parametrize("how", ["same name", "two names", "a copy"])
def test_the_same_observation_file_twice_is_refused(files, tmp_path, monkeypatch, how):
    obs = files["obs"]
    monkeypatch.chdir(obs.parent)
    second = {"same name": obs.name, "two names": str(obs), "a copy": tmp_path / "copy.20o"}[how]
    if how == "a copy":
        second.write_bytes(obs.read_bytes())
    out = tmp_path / "out"
    r = run_cli(["fit", obs.name, second, "--nav", files["nav"], "--out", out, "--no-pdf"])
    name = "copy.20o" if how == "a copy" else obs.name
    assert check_run(r, name, allowed=(2,)) is None, r.err
    expected = "same content as" if how == "a copy" else "observation file given twice"
    assert expected in r.err and "give each file once" in r.err
    assert not out.exists()


# ------------------------------------------------------------- several navigation files


def test_a_zip_of_navigation_files_is_read_whole(files):
    whole = read_orbit(files["navs_zip"])
    ref = read_orbit(files["nav"])
    assert isinstance(whole, Navigation)
    assert str(whole.path) == "navs.zip:brdc_a.rnx + navs.zip:brdc_b.rnx"
    assert len(whole.ephemerides["G"]) == len(ref.ephemerides["G"])
    t = T0 + np.arange(0.0, 7200.0, 600.0)
    for sat in ("G01", "G17"):
        np.testing.assert_allclose(whole.positions_ecef_m(sat, t), ref.positions_ecef_m(sat, t))


def test_inspect_reads_a_zip_of_navigation_files(files):
    r = run_cli(["inspect", files["obs"], "--nav", files["navs_zip"], "--min-arc-min", "10"])
    assert check_run(r, "navs.zip", allowed=(0,)) is None, r.err
    assert "orbit navs.zip:brdc_a.rnx + navs.zip:brdc_b.rnx (navigation file)" in r.out
    assert "damaged" not in r.err


def test_a_zip_of_several_files_given_to_one_file_reader_lists_its_members(files):
    with pytest.raises(
        InputError,
        match=r"obs\.zip: zip archive of 2 files \(SYNT1770\.20o, "
        r"SYNT1771\.20o\): this reader takes one file; unzip "
        r"it",
    ):
        read_obs(files["obs_zip"])


@pytest.mark.parametrize("command", ["fit", "inspect"])
def test_nav_option_accumulates(files, tmp_path, command):
    args = [command, files["obs"], "--nav", files["nav_a"], "--nav", files["nav_b"]]
    if command == "fit":
        from psdbound.cli.fit import build_config
        from psdbound.cli.main import build_parser

        cfg = build_config(build_parser().parse_args([str(a) for a in args]))
        assert cfg.inputs.nav == (str(files["nav_a"]), str(files["nav_b"]))
        data = read_inputs(cfg.inputs)
        assert [f["name"] for f in data.files if f["role"] == "nav"] == ["brdc_a.rnx", "brdc_b.rnx"]
        assert len(data.orbit.ephemerides["G"]) == len(read_orbit(files["nav"]).ephemerides["G"])
    else:
        r = run_cli([*args, "--min-arc-min", "10"])
        assert check_run(r, "brdc", allowed=(0,)) is None, r.err
        assert "orbit brdc_a.rnx + brdc_b.rnx (navigation file)" in r.out


def test_navigation_records_in_two_files_count_once(files):
    nav = read_orbit(files["nav"])
    twice = merge_navigation([nav, nav], "a + a")
    assert len(twice.ephemerides["G"]) == len(nav.ephemerides["G"])


def test_navigation_and_sp3_files_together_are_refused(files):
    from psdbound.io import orbits

    with pytest.raises(
        InputError,
        match=r"the orbit files mix broadcast navigation \(brdc\.rnx\) "
        r"and SP3 precise orbits \(orbit\.sp3\)",
    ):
        orbits._join([read_orbit(files["nav"]), _sp3(T0, 900.0, 4, "orbit.sp3")])


def _sp3(t0: float, step: float, n: int, name: str, sats=("G01", "G02")) -> PreciseOrbit:
    t = t0 + step * np.arange(n)
    rng = np.random.default_rng(int(t0) % 1000)
    xyz = rng.normal(2e7, 1e6, (n, len(sats), 3))
    return PreciseOrbit(Path(name), t, tuple(sats), xyz, np.zeros((n, len(sats))), "GPS")


def test_sp3_files_of_consecutive_periods_are_joined():
    a = _sp3(T0, 900.0, 8, "a.sp3")
    b = _sp3(T0 + 6300.0, 900.0, 8, "b.sp3", sats=("G02", "G03"))  # first epoch repeats a's last
    j = merge_precise([a, b], "a.sp3 + b.sp3")
    assert j.sats == ("G01", "G02", "G03") and j.t_gps_s.size == 15
    np.testing.assert_array_equal(j.xyz_m[:8, :2], a.xyz_m)  # the repeated epoch from a
    np.testing.assert_array_equal(j.xyz_m[8:, 1:], b.xyz_m[1:])
    assert np.isnan(j.xyz_m[8:, 0]).all() and np.isnan(j.xyz_m[:8, 2]).all()
    with pytest.raises(
        InputError,
        match=r"SP3 files with different epoch intervals: a\.sp3 "
        r"\(900 s\), c\.sp3 \(300 s\)",
    ):
        merge_precise([a, _sp3(T0 + 7200.0, 300.0, 8, "c.sp3")], "a + c")


# ------------------------------------------------------------- a station's zip (obs + nav)


def test_file_kinds(files, tmp_path):
    import bz2
    import gzip

    import hatanaka

    assert [file_kind(files[k]) for k in ("obs", "nav")] == ["obs", "nav"]
    obs = files["obs"].read_bytes()
    (tmp_path / "o.gz").write_bytes(gzip.compress(obs))
    (tmp_path / "o.crx.bz2").write_bytes(bz2.compress(hatanaka.rnx2crx(obs)))
    (tmp_path / "n.gz").write_bytes(gzip.compress(files["nav"].read_bytes()))
    (tmp_path / "o.sp3").write_text("#dP2020  6 25  0  0  0.00000000      96 ORBIT IGS20\n")
    meteo = "     3.04           METEOROLOGICAL DATA                     RINEX VERSION / TYPE"
    (tmp_path / "m.rnx").write_text(meteo[:20] + "M" + meteo[21:] + "\n")
    (tmp_path / "bad.gz").write_bytes(b"\x1f\x8b" + b"\x00" * 40)
    kinds = [
        file_kind(tmp_path / n) for n in ("o.gz", "o.crx.bz2", "n.gz", "o.sp3", "m.rnx", "bad.gz")
    ]
    assert kinds == ["obs", "obs", "nav", "sp3", "", ""]


def test_station_zip_of_observations_and_navigation(files):
    data = read_inputs(InputsConfig(obs=(str(files["station_zip"]),)))
    assert [o.path for o in data.observations] == [f"{files['station_zip']}:SYNT1770.20o"]
    assert isinstance(data.orbit, Navigation)
    assert str(data.orbit.path).endswith("station.zip:brdc.rnx")
    assert [(f["role"], f["name"]) for f in data.files] == [
        ("obs", "station.zip"),
        ("nav", "station.zip"),
    ]
    given = read_inputs(InputsConfig(obs=(str(files["station_zip"]),), nav=(str(files["nav"]),)))
    assert str(given.orbit.path).endswith("brdc.rnx") and ":" not in str(given.orbit.path)
    assert any("its navigation/SP3 members are not used (--nav given)" in w for w in given.warnings)


def test_station_zip_through_the_command_line(files, tmp_path):
    """No --nav: the configuration check lets the archive through; the reading succeeds."""
    out = tmp_path / "out"
    r = run_cli(
        ["fit", files["station_zip"], "--out", out, "--no-pdf", "--quiet", "--min-arc-min", "500"]
    )
    # every arc is shorter than 500 min: a data error after both files were read
    assert check_run(r, "station.zip", allowed=(2,)) is None, r.err
    assert "station.zip:SYNT1770.20o" in r.err and "shorter than 500 min" in r.err, r.err
    assert "navigation (or SP3) file is needed" not in r.err


@pytest.mark.parametrize(
    ("archive", "message"),
    [
        ("obs_zip", r"a navigation \(or SP3\) file is needed for elevations: give --nav"),
        (
            "navs_zip",
            r"the archive holds no observation file \(2 navigation/SP3 files: brdc_a\.rnx, "
            r"brdc_b\.rnx\); give the observation files, and this archive as --nav",
        ),
    ],
)
def test_archive_without_the_other_kind(files, archive, message):
    with pytest.raises(InputError, match=message):
        read_inputs(InputsConfig(obs=(str(files[archive]),)))


# ------------------------------------------------------------- single-file reports, end to end


def test_fit_system_absent_from_the_file_names_the_systems_it_holds(files, tmp_path):
    r = run_cli(
        [
            "fit",
            files["obs"],
            "--nav",
            files["nav"],
            "--system",
            "R",
            "--out",
            tmp_path / "out",
            "--no-pdf",
            "--quiet",
        ]
    )
    assert check_run(r, files["obs"].name, allowed=(2,)) is None, r.err
    assert "no GLONASS (R) observations: the file holds GPS (G) only" in r.err
    assert "(--system G)" in r.err and "available:" not in r.err


def test_inspect_epoch_repeated_as_29_9999999(tmp_path):
    text = format_obs_v3(moving_observations(seed=11))
    lines = text.split("\n")
    k = next(i for i, ln in enumerate(lines) if ln.startswith("> 2020 06 25 00 05 30."))
    rep = [lines[k].replace("30.0000000", "29.9999999"), *lines[k + 1 : k + 3]]
    lines[k:k] = rep
    p = tmp_path / "rep.rnx"
    p.write_text("\n".join(lines))
    r = run_cli(["inspect", p, "--min-arc-min", "5"])
    assert check_run(r, "rep.rnx", allowed=(0,)) is None, r.err
    assert "1 epoch(s) repeated with identical data (first 2020-06-25 00:05:30.000" in r.err
