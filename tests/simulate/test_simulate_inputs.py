"""``simulate``: inputs checked before anything is written, and the --out folder policy.

The navigation files are built here from the nominal constellation
(:func:`psdbound.io.nominal.nominal_navigation`, written as RINEX 3 by
:func:`psdbound.io.write.write_nav_v3`), so no station file is needed.
"""

from __future__ import annotations

import os
import warnings

import pytest

from psdbound.cli import main
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError, NoDataError
from psdbound.io import read_obs
from psdbound.io.nominal import nominal_navigation
from psdbound.io.timescales import calendar_to_gps_s
from psdbound.io.write import write_nav_v3
from psdbound.simulate import preset, simulate

SHORT = ["simulate", "--preset", "short", "--duration-h", "0.02"]
#: 2024-05-06T00:00:00 GPS, seconds.
MAY_6 = float(calendar_to_gps_s(2024, 5, 6, 0, 0, 0.0))


def _run(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err.strip()


def _nav(folder, name, t0, systems="G"):
    """A RINEX 3 navigation file of nominal records from 2 h before t0 to 4 h after it."""
    nav = nominal_navigation(t0, t0 + 3600.0, systems=systems)
    return write_nav_v3(folder / name, nav)


def _entries(folder):
    return sorted(os.listdir(folder))


# --------------------------------------------------------------------- navigation file


def test_nav_without_the_simulated_system_is_bad_input(tmp_path, capsys):
    t0 = float(calendar_to_gps_s(2020, 11, 24, 14, 0, 0.0))  # the short preset's start
    nav = _nav(tmp_path, "gal_EN.rnx", t0, systems="E")
    code, out, err = _run(capsys, *SHORT, "--nav", nav, "--out", tmp_path / "sim")
    assert code == 2, err
    assert err.startswith(f"psdbound simulate: error: {nav}: the navigation file has no GPS ")
    assert "(the file holds Galileo)" in err and 'systems = "E" in a --scenario file' in err
    assert len(err.splitlines()) == 1 and out == ""
    assert _entries(tmp_path) == ["gal_EN.rnx"]  # no folder, no hidden leftover
    with pytest.raises(InputError, match="no GPS ephemerides"):
        simulate(preset("short").replace(nav_path=str(nav)), tmp_path / "lib")
    assert not (tmp_path / "lib").exists()


def test_nav_of_another_day_names_both_days_and_suggests_start(tmp_path, capsys):
    nav = _nav(tmp_path, "day_GN.rnx", MAY_6)
    code, out, err = _run(capsys, *SHORT, "--nav", nav, "--out", tmp_path / "sim")
    assert code == 2, err
    assert f"{nav}: the navigation file has no GPS record valid during the simulation " in err
    assert "(2020-11-24T14:00:00 to 2020-11-24T14:01:11 GPS)" in err
    assert "its records are of 2024-05-06" in err and "--start 2024-05-06T00:00:00" in err
    assert "a navigation file of 2020-11-24" in err
    assert len(err.splitlines()) == 1 and out == ""
    assert _entries(tmp_path) == ["day_GN.rnx"]
    # as suggested: the run works
    args = [*SHORT, "--single-antenna", "--start", "2024-05-06T00:00:00", "--nav", nav]
    code, out, err = _run(capsys, *args, "--out", tmp_path / "sim")
    assert code == 0 and err == "", err
    assert len(out.split()) == 4


def test_nav_covering_part_of_the_span_warns_and_leaves_snr_blank(tmp_path):
    nav = _nav(tmp_path, "day_GN.rnx", MAY_6)  # records up to 04:00, valid up to 08:00
    sc = preset("short").replace(
        nav_path=str(nav), start_gps="2024-05-06T07:57:00", duration_s=360.0, dual_antenna=False
    )
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = simulate(sc, tmp_path / "sim")
    numpy_warnings = [str(w.message) for w in caught if issubclass(w.category, RuntimeWarning)]
    assert not numpy_warnings  # was: invalid value encountered in cast (a NaN SNR as int8)
    ours = [str(w.message) for w in caught if issubclass(w.category, PsdboundWarning)]
    assert len(ours) == 1 and "valid at only 50.3 % of the simulated epochs" in ours[0], ours
    obs = read_obs(res.obs_paths[0])
    assert obs.t_gps_s[-1] == MAY_6 + 8 * 3600.0  # no epoch without a valid record
    block = obs.blocks["G"]
    s1c, l1c = block.codes.index("S1C"), block.codes.index("L1C")
    observed = block.values[:, :, l1c] == block.values[:, :, l1c]
    assert (observed == (block.values[:, :, s1c] == block.values[:, :, s1c])).all()
    assert ((block.ssi[:, :, l1c] >= 1) == observed).all()  # no strength without a value


def test_nothing_above_the_mask_is_no_data(tmp_path):
    sc = preset("short").replace(elevation_mask_deg=89.9, duration_s=60.0, dual_antenna=False)
    with pytest.raises(NoDataError, match=r"no GPS satellite is above the elevation mask \(89.9"):
        simulate(sc, tmp_path / "sim")
    assert not (tmp_path / "sim").exists() or _entries(tmp_path / "sim") == []


def test_duration_shorter_than_the_interval_is_bad_input(tmp_path, capsys):
    args = ["simulate", "--preset", "short", "--duration-h", "0.001", "--interval-s", "30"]
    code, _, err = _run(capsys, *args, "--out", tmp_path / "sim")
    assert code == 2 and "shorter than the sampling interval (30 s)" in err, err
    assert not (tmp_path / "sim").exists()


# --------------------------------------------------------------------- the --out folder


@pytest.mark.parametrize(
    ("name", "text"), [("notes.txt", "mine\n"), ("result.json", '{"schema_version": "1"}\n')]
)
def test_folder_with_other_files_is_refused_without_overwrite(tmp_path, capsys, name, text):
    out = tmp_path / "sim"
    out.mkdir()
    (out / name).write_text(text)
    code, printed, err = _run(capsys, *SHORT, "--out", out)
    assert code == 2 and printed == "", err
    assert f"{out}: --out is an existing folder that is not a simulation's output" in err
    assert f"(it holds 1 entry: {name})" in err and "--overwrite" in err
    assert _entries(out) == [name] and (out / name).read_text() == text


def test_overwrite_adds_the_files_and_touches_nothing_else(tmp_path, capsys):
    out = tmp_path / "sim"
    out.mkdir()
    (out / "notes.txt").write_text("mine\n")
    assert _run(capsys, *SHORT, "--out", out, "--overwrite")[0] == 0
    assert "psdbound-short-B_MO.rnx.gz" in _entries(out)
    # a single-antenna run replaces the earlier run's files: no stale antenna B
    code, printed, err = _run(capsys, *SHORT, "--single-antenna", "--out", out, "--overwrite")
    assert code == 0, err
    assert _entries(out) == [
        "notes.txt",
        "psdbound-short-A_MO.rnx.gz",
        "psdbound-short_MN.rnx.gz",
        "psdbound-short_truth.csv.gz",
        "psdbound-short_truth.json",
    ]
    assert printed.split() == [str(out / n) for n in _entries(out)[1:]]
    assert (out / "notes.txt").read_text() == "mine\n"


def test_an_earlier_simulation_is_replaced_as_a_whole(tmp_path, capsys):
    out = tmp_path / "sim"
    assert _run(capsys, *SHORT, "--out", out)[0] == 0
    assert len(_entries(out)) == 5
    code, _, err = _run(capsys, *SHORT, "--single-antenna", "--out", out)
    assert code == 0, err
    assert "psdbound-short-B_MO.rnx.gz" not in _entries(out) and len(_entries(out)) == 4
    assert [e for e in _entries(tmp_path) if e.startswith(".")] == []


def test_a_failed_run_leaves_the_folder_as_it_was(tmp_path, capsys):
    out = tmp_path / "sim"
    assert _run(capsys, *SHORT, "--out", out)[0] == 0
    before = {n: (out / n).read_bytes() for n in _entries(out)}
    nav = _nav(tmp_path, "day_GN.rnx", MAY_6)
    code, _, err = _run(capsys, *SHORT, "--single-antenna", "--nav", nav, "--out", out)
    assert code == 2 and "no GPS record valid during the simulation" in err, err
    assert {n: (out / n).read_bytes() for n in _entries(out)} == before
    assert _entries(tmp_path) == ["day_GN.rnx", "sim"]


def test_library_single_antenna_run_removes_the_earlier_antenna_b(tmp_path):
    sc = preset("short").replace(duration_s=60.0)
    simulate(sc, tmp_path)
    (tmp_path / "notes.txt").write_text("mine\n")
    res = simulate(sc.replace(dual_antenna=False), tmp_path)
    assert [p.name for p in res.obs_paths] == ["psdbound-short-A_MO.rnx.gz"]
    assert all(p.parent == tmp_path and p.is_file() for p in (*res.obs_paths, res.nav_path))
    assert _entries(tmp_path) == [
        "notes.txt",
        "psdbound-short-A_MO.rnx.gz",
        "psdbound-short_MN.rnx.gz",
        "psdbound-short_truth.csv.gz",
        "psdbound-short_truth.json",
    ]
