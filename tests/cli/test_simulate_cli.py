"""``psdbound simulate`` with truths on demand: --multipath, --receiver-noise-m, --scenario."""

from __future__ import annotations

import json

import pytest

from psdbound.cli import main

SHORT = ["simulate", "--preset", "short", "--duration-h", "0.05", "--single-antenna"]


def _run(capsys, *args):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err.strip()


def _truth(folder):
    (p,) = folder.glob("*_truth.json")
    return json.loads(p.read_text())["scenario"]


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--multipath", "tau=30"], "--multipath: unknown key 'tau'"),
        (["--multipath", "tau_s"], "--multipath: item 'tau_s' has no '='"),
        (["--multipath", "tau_s=abc"], "--multipath tau_s must be a number > 0 and <= 86400 s"),
        (
            ["--multipath", "sigma_gm_m=0.2"],
            "--multipath sigma_gm_m must be a number from 0 to "
            "0.05 m, got 0.2 (carrier multipath cannot exceed",
        ),
        (["--multipath", "tau_s=100000"], "--multipath tau_s must be a number > 0 and <= 86400"),
        (["--multipath", "mapping=1,2"], "--multipath mapping must be three numbers"),
        (["--multipath", ""], "--multipath is empty"),
        (["--receiver-noise-m", "0.1"], "--receiver-noise-m must be a number from 0 to 0.05 m"),
        (["--receiver-noise-m", "-1"], "--receiver-noise-m must be a number from 0 to 0.05 m"),
        (["--start", "2020-11-24"], "--start must be an ISO date-time"),
        (["--scenario", "missing.toml"], "missing.toml: scenario file not found"),
    ],
)
def test_bad_truth_options_exit_2_and_write_nothing(tmp_path, monkeypatch, capsys, args, message):
    monkeypatch.chdir(tmp_path)
    code, out, err = _run(capsys, *SHORT, *args, "--out", "sim")
    assert code == 2, err
    assert err.startswith("psdbound simulate: error: ") and message in err, err
    assert len(err.splitlines()) == 1 and out == ""
    assert not (tmp_path / "sim").exists()


def test_bad_scenario_file_exit_2(tmp_path, capsys):
    p = tmp_path / "sc.toml"
    p.write_text("duration_s = 600\n[multipath]\ntau_s = 30\nsigma = 0.001\n")
    code, _, err = _run(capsys, *SHORT, "--scenario", p, "--out", tmp_path / "sim")
    assert code == 2 and f"{p}: unknown key 'sigma' in [multipath]" in err, err
    assert not (tmp_path / "sim").exists()


def test_multipath_spec_is_simulated_and_recorded(tmp_path, capsys):
    out = tmp_path / "sim"
    code, printed, err = _run(
        capsys,
        *SHORT,
        "--seed",
        5,
        "--receiver-noise-m",
        "0.0008",
        "--multipath",
        "sigma_gm_m=0.004,tau_s=120,sigma_wn_m=0.002,mapping=1,12,10",
        "--out",
        out,
    )
    assert code == 0, err
    assert len(printed.split()) == 4  # antenna A, nav, truth CSV, truth JSON
    sc = _truth(out)
    mp = sc["multipath"]
    assert (mp["sigma_gm_m"], mp["tau_s"], mp["sigma_wn_m"]) == (0.004, 120.0, 0.002)
    assert (mp["a"], mp["b"], mp["c_deg"]) == (1.0, 12.0, 10.0)
    assert sc["receiver_noise_m"] == 0.0008 and sc["seed"] == 5 and sc["dual_antenna"] is False


def test_partial_spec_keeps_the_preset_values(tmp_path, capsys):
    code, _, err = _run(capsys, *SHORT, "--multipath", "tau_s=300", "--out", tmp_path / "s")
    assert code == 0, err
    mp = _truth(tmp_path / "s")["multipath"]
    assert mp == {
        "sigma_gm_m": 0.003,
        "tau_s": 300.0,
        "sigma_wn_m": 0.001,
        "a": 1.0,
        "b": 9.0,
        "c_deg": 15.0,
        "reflections": [],
    }


def test_scenario_file_then_flags(tmp_path, capsys):
    p = tmp_path / "sc.toml"
    p.write_text(
        'name = "fromfile"\nduration_s = 600.0\ninterval_s = 30.0\nseed = 3\n'
        "receiver_noise_m = 0.001\n\n[multipath]\nsigma_gm_m = 0.005\ntau_s = 60\n"
        "mapping = [1, 12, 10]\n"
    )
    out = tmp_path / "sim"
    code, _, err = _run(
        capsys, "simulate", "--scenario", p, "--multipath", "tau_s=240", "--seed", 8, "--out", out
    )
    assert code == 0, err
    sc = _truth(out)
    assert sc["name"] == "fromfile" and sc["interval_s"] == 30.0 and sc["duration_s"] == 600.0
    assert sc["seed"] == 8 and sc["receiver_noise_m"] == 0.001  # flag over file, file over preset
    assert sc["multipath"]["sigma_gm_m"] == 0.005 and sc["multipath"]["tau_s"] == 240.0
    assert sc["multipath"]["b"] == 12.0 and sc["dual_antenna"] is True  # the demo preset's
    assert (out / "fromfile-B_MO.rnx.gz").is_file()


def test_same_seed_same_files(tmp_path, capsys):
    args = [*SHORT, "--seed", 21, "--multipath", "sigma_gm_m=0.002,tau_s=45"]
    assert _run(capsys, *args, "--out", tmp_path / "a")[0] == 0
    assert _run(capsys, *args, "--out", tmp_path / "b")[0] == 0
    for name in ("psdbound-short-A_MO.rnx.gz", "psdbound-short_truth.csv.gz"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
