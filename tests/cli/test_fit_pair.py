"""``fit --pair A B``, ``--position-a/-b``, ``--baseline``: a dual-antenna pair is named."""

from __future__ import annotations

import json

import numpy as np
import pytest

from psdbound.cli import main
from psdbound.io import read_obs
from psdbound.io.geometry import ecef_to_geodetic, enu_rotation
from psdbound.simulate import preset, simulate


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    sc = preset("demo").replace(name="duo", duration_s=5400.0, seed=11)
    return simulate(sc, tmp_path_factory.mktemp("duo"))


def fit(capsys, *args):
    code = main(["fit", *map(str, args)])
    out, err = capsys.readouterr()
    return code, out, err


def test_two_stations_without_pair_name_both(pair, tmp_path, capsys):
    a, b = pair.obs_paths
    code, _, err = fit(capsys, a, b, "--nav", pair.nav_path, "--out", tmp_path / "o")
    assert code == 2
    line = err.strip().splitlines()[-1]
    assert "two stations: DUO-A (1 file), DUO-B (1 file)" in line
    assert "--pair DUO- DUO-" not in line  # ambiguous 4-character keys are not suggested
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--pair", "DUO-A", "NOPE"], "--pair 'NOPE': no observation file of that station"),
        (["--pair", "DUO-A", "DUO-B", "--method", "df"], "--pair names a dual-antenna pair"),
    ],
)
def test_bad_pair(pair, tmp_path, capsys, extra, message):
    a, b = pair.obs_paths
    code, _, err = fit(capsys, a, b, "--nav", pair.nav_path, "--out", tmp_path / "o", *extra)
    assert code == 2, err
    assert message in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--position-b", "4789031.3", "176583.4", "4195015.1"], "--position-b"),
        (["--baseline", "given"], "--baseline"),
        (["--baseline-tolerance-m", "0.01"], "--baseline-tolerance-m"),
    ],
)
def test_dual_antenna_options_on_one_station(pair, tmp_path, capsys, extra, message):
    code, _, err = fit(
        capsys, pair.obs_paths[0], "--nav", pair.nav_path, "--out", tmp_path / "o", *extra
    )
    assert code == 2, err
    assert message in err and "dual-antenna option" in err


def test_pair_of_files_with_a_wrong_position(pair, tmp_path, capsys):
    """--pair with files only; --position-b 1.5 m off is corrected and the size is said."""
    a, b = pair.obs_paths
    p_b = np.asarray(read_obs(b).header.approx_position_m)
    lat, lon, _ = ecef_to_geodetic(p_b)
    wrong = p_b + enu_rotation(lat, lon).T @ np.array([0.9, 1.1, -0.4])
    out = tmp_path / "o"
    code, stdout, err = fit(
        capsys,
        "--pair",
        a,
        b,
        "--nav",
        pair.nav_path,
        "--position-b",
        *wrong,
        "--out",
        out,
        "--no-pdf",
    )
    assert code == 0, err
    assert "antenna position corrected: the carrier phases put DUO-B 1.50" in stdout
    d = json.loads((out / "result.json").read_text())
    iso = d["isolation"]
    assert iso["baseline_estimate"]["used"] is True
    assert iso["position_sources"][1].startswith("user")
    assert iso["baseline_m"] == pytest.approx(5.0, abs=0.05)  # the simulated 5 m baseline
    assert d["windows"]["covered_fraction"] > 0.9
    # the console shows every warning of the run, grouped by stage in pipeline order
    assert d["warnings"] and all(w in " ".join(stdout.split()) for w in d["warnings"])
    stages = [g["stage"] for g in d["warnings_by_stage"]]
    assert stages == sorted(
        stages,
        key=["reading", "cutoff", "isolation", "screening", "windows", "bound", "validation"].index,
    )
    assert [w for g in d["warnings_by_stage"] for w in g["warnings"]] == d["warnings"]
    assert f"{stages[0]}:" in stdout
