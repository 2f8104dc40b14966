"""End to end: psdbound fit / report, result schema, reports, CLI errors."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest
from browser import chromium, needs_browser, not_blank
from conftest import UPC1_OBS, UPC2_OBS, UPC_NAV, shared_file

import psdbound
from psdbound.pipeline import REQUIRED_FIELDS, FitConfig
from psdbound.results import get_field


def run_cli(*args, cwd, env_extra=None, timeout=600):
    env = dict(os.environ)
    env.update(env_extra or {})
    return subprocess.run(
        [sys.executable, "-m", "psdbound", *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        env=env,
        timeout=timeout,
    )


@pytest.fixture(scope="module")
def demo_run(tmp_path_factory):
    """`python -m psdbound fit` with no arguments, in an empty folder."""
    work = tmp_path_factory.mktemp("empty")
    cache = tmp_path_factory.mktemp("cache")
    r = run_cli("fit", cwd=work, env_extra={"PSDBOUND_CACHE": str(cache)})
    assert r.returncode == 0, r.stderr
    return work, r


def test_fit_without_arguments_uses_the_demo(demo_run):
    work, r = demo_run
    out = work / "reports" / "demo"
    assert sorted(p.name for p in out.iterdir()) == ["report.html", "report.pdf", "result.json"]
    d = psdbound.load(out / "result.json").document
    for f in REQUIRED_FIELDS:
        get_field(d, f)
    b = d["bound"]
    assert 1e-4 < b["sigma_gm_m"] < 0.05 and b["tau_s"] > 0 and b["sigma_wn_m"] >= 0
    assert d["sampling"] == {"interval_s": 1.0, "nyquist_hz": 0.5}
    assert d["cutoff"]["f_c_hz"] > 0 and d["cutoff"]["source"]
    assert d["windows"]["count"] == len(d["windows"]["per_window"]) > 0
    # pooled rule: the bound is above every group's limit (margins per window may be < 1)
    assert b["rule"] == "pooled" and b["min_margin"] >= 1.0 and b["confidence_level"] == 0.95
    assert all(np.isfinite(w["margin"]) for w in d["windows"]["per_window"])
    assert d["validation"]["verdict"] in ("pass", "fail")
    assert d["mapping"]["a"] == 1.0
    assert all(len(i["sha256"]) == 64 for i in d["provenance"]["inputs"])
    assert d["provenance"]["configuration"]["inputs"]["method"] == "df"
    assert "demo" in d and d["demo"]["seed"] == 2020
    # the figures can be redrawn from the file: data present and the bound over every PSD
    bc = d["figures"]["bound_curve"]
    assert max(bc["f_hz"]) <= d["sampling"]["nyquist_hz"] * (1 + 1e-9)
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64,") >= 5 and "sigma" not in html[:50]
    assert "Caveats" in html and "data covered by the bound: " in html  # page 1 (headline)
    # issue 15: the demo recovers its truth: injected PSD under the bound, ratio printed
    demo = d["demo"]
    # issue 27: the bound covers every window's truth, not the mean spectrum (its tightness:
    # test_demo_bound_is_within_twice_the_truth_variance below)
    assert demo["min_psd_ratio"] >= 1.0 and 1.0 <= demo["variance_ratio"]
    assert demo["min_psd_ratio_all_f"] >= 1.0  # down to 0 Hz (issue 28)
    assert "bound variance / injected variance" in r.stdout
    assert "Bound variance / injected variance" in html
    assert (out / "report.pdf").stat().st_size > 50_000
    assert (out / "report.pdf").read_bytes()[:5] == b"%PDF-"
    assert "psdbound fit (DF)" in r.stdout


def test_report_rerenders_from_result_alone(demo_run, tmp_path):
    work, _ = demo_run
    src = work / "reports" / "demo" / "result.json"
    copy = tmp_path / "r" / "result.json"
    copy.parent.mkdir()
    shutil.copy(src, copy)
    r = run_cli("report", copy, "--no-pdf", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    html = (tmp_path / "r" / "report.html").read_text()
    assert html.count("data:image/png;base64,") >= 5


def test_no_report_writes_the_result_alone_without_drawing(demo_run, tmp_path):
    """--no-report: result.json only, the same result, matplotlib never imported; and
    ``psdbound report`` draws the reports from it afterwards."""
    work, _ = demo_run
    code = (
        "import sys; from psdbound.cli.main import main; "
        "c = main(['fit', '--no-report', '--quiet', '--out', 'r']); "
        "print('drawing modules:', sorted(m for m in sys.modules "
        "if m.split('.')[0] in ('matplotlib', 'jinja2', 'PIL'))); sys.exit(c)"
    )
    r = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=600
    )
    assert r.returncode == 0, r.stderr
    assert "drawing modules: []" in r.stdout
    assert sorted(p.name for p in (tmp_path / "r").iterdir()) == ["result.json"]
    ours = json.loads((tmp_path / "r" / "result.json").read_text())["bound"]
    full = json.loads((work / "reports" / "demo" / "result.json").read_text())["bound"]
    assert ours["sigma_gm_m"] == full["sigma_gm_m"] and ours["tau_s"] == full["tau_s"]
    r = run_cli("report", tmp_path / "r" / "result.json", "--no-pdf", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert sorted(p.name for p in (tmp_path / "r").iterdir()) == ["report.html", "result.json"]


def test_report_out_never_loses_a_user_file(demo_run, tmp_path, capsys):
    """--out: a user's folder is refused (or, with --overwrite, only added to); a previous
    output is replaced atomically; a file is never replaced."""
    from psdbound.cli import main

    work, _ = demo_run
    src = work / "reports" / "demo" / "result.json"
    user = tmp_path / "user"
    user.mkdir()
    (user / "notes.txt").write_text("my notes\n")
    assert main(["report", str(src), "--out", str(user), "--no-pdf"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not a psdbound output" in err[0]
    assert sorted(p.name for p in user.iterdir()) == ["notes.txt"]
    assert main(["report", str(src), "--out", str(user), "--no-pdf", "--overwrite"]) == 0
    assert sorted(p.name for p in user.iterdir()) == ["notes.txt", "report.html", "result.json"]
    assert (user / "notes.txt").read_text() == "my notes\n"
    # re-rendered in its own folder, the run's other files stay as they were (the series,
    # and the PDF when none is drawn); nothing hidden is left behind
    prev = tmp_path / "prev"
    shutil.copytree(work / "reports" / "demo", prev)
    (prev / "series.csv.gz").write_bytes(b"series of the run")
    pdf = (prev / "report.pdf").read_bytes()
    assert main(["report", str(prev / "result.json"), "--no-pdf", "--quiet"]) == 0
    assert sorted(p.name for p in prev.iterdir()) == [
        "report.html",
        "report.pdf",
        "result.json",
        "series.csv.gz",
    ]
    assert (prev / "series.csv.gz").read_bytes() == b"series of the run"
    assert (prev / "report.pdf").read_bytes() == pdf
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]
    # rendered into another folder, nothing of the source folder is copied
    other = tmp_path / "other"
    assert main(["report", str(prev / "result.json"), "--out", str(other), "--no-pdf"]) == 0
    assert sorted(p.name for p in other.iterdir()) == ["report.html", "result.json"]
    afile = tmp_path / "afile"
    afile.write_text("x")
    assert main(["report", str(src), "--out", str(afile)]) == 2
    assert afile.read_text() == "x" and not [
        p for p in tmp_path.iterdir() if p.name.startswith(".")
    ]


def test_config_file_is_applied_and_saved(tmp_path, demo_run):
    work, _ = demo_run
    cfg = tmp_path / "run.toml"
    cfg.write_text(
        '[cutoff]\nf_c_hz = 1.2e-3\n[spectra]\nestimator = "welch"\n'
        '[output]\nname = "toml-run"\npdf = false\n'
    )
    cache = {"PSDBOUND_CACHE": str(next(work.parent.glob("cache*")))}
    r = run_cli("fit", "--config", cfg, "--quiet", cwd=tmp_path, env_extra=cache)
    assert r.returncode == 0, r.stderr
    d = json.loads((tmp_path / "reports" / "toml-run" / "result.json").read_text())
    assert d["cutoff"] == {**d["cutoff"], "f_c_hz": 1.2e-3, "source": "given"}
    assert d["bound"]["estimator"] == "welch"
    assert d["provenance"]["configuration"]["spectra"]["estimator"] == "welch"
    assert not (tmp_path / "reports" / "toml-run" / "report.pdf").exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["fit", "missing.rnx", "--nav", "nav.rnx"], "missing.rnx: observation file not found"),
        (["fit", "reports", "--nav", "nav.rnx"], "reports: is a folder, not an observation file"),
        (["fit", "--frobnicate"], "unrecognized arguments: --frobnicate"),
        (
            ["fit", "a.rnx", "--method", "da"],
            "--method da needs the observation files of two antennas",
        ),
        (["fit", "--config", "nope.toml"], "nope.toml: configuration file not found"),
        (["report", "nothing.json"], "nothing.json: result file not found"),
    ],
)
def test_cli_errors_one_line_exit_2_no_output(tmp_path, args, message):
    (tmp_path / "a.rnx").write_text("x")
    if "folder" in message:  # a folder given as the observation file: nothing written in it
        (tmp_path / "reports").mkdir()
    r = run_cli(*args, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and message in lines[0], r.stderr
    assert not (tmp_path / "reports").exists() or not any((tmp_path / "reports").iterdir())


def test_bad_toml_option(tmp_path):
    cfg = tmp_path / "bad.toml"
    cfg.write_text("[spectra]\nestimater = 'welch'\n")
    with pytest.raises(Exception, match="unknown option spectra.estimater"):
        FitConfig.from_toml(cfg)


@pytest.mark.realdata
@pytest.mark.slow
@pytest.mark.parametrize("case", ["upc-da"])
def test_fit_real_data(tmp_path, case):
    # the ESBC day runs through the library in tests/pipeline/test_regression_pins.py
    args = [shared_file(UPC1_OBS), shared_file(UPC2_OBS), "--nav", shared_file(UPC_NAV)]
    r = run_cli("fit", *args, "--name", case, "--quiet", cwd=tmp_path)
    assert r.returncode == 2  # two stations: a pair is named explicitly
    assert "--pair UPC1 UPC2" in r.stderr and r.stderr.count("\n") == 1
    assert not (tmp_path / "reports").exists()
    r = run_cli("fit", *args, "--pair", "UPC1", "UPC2", "--name", case, "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    out = tmp_path / "reports" / case
    d = psdbound.load(out / "result.json").document
    b = d["bound"]
    print(
        f"{case}: sigma_GM {100 * b['sigma_gm_m']:.2f} cm, tau {b['tau_s']:.0f} s, "
        f"sigma_WN {100 * b['sigma_wn_m']:.2f} cm, {d['windows']['count']} windows, "
        f"validation {d['validation']['verdict']}"
    )
    assert 1e-4 < b["sigma_gm_m"] < 0.05
    assert d["method"] == "DA"
    assert any("cancel" in w for w in d["warnings"])
    est = d["isolation"]["baseline_estimate"]  # UPC's header positions agree with the phases
    assert est["used"] is False and est["estimate"]["correction_length_m"] < 0.05
    assert (out / "report.html").stat().st_size > 100_000
    assert (out / "report.pdf").stat().st_size > 50_000


@needs_browser
def test_reports_as_a_person_sees_them(demo_run, tmp_path):
    """Render report.html in headless Chromium and the PDF pages with pdftoppm."""
    work, _ = demo_run
    out = work / "reports" / "demo"
    shot = tmp_path / "report.png"
    chromium(
        out / "report.html", tmp_path / "ud", "--window-size=1100,2400", f"--screenshot={shot}"
    )
    assert shot.stat().st_size > 20_000 and not_blank(shot) > 0.05
    subprocess.run(
        ["pdftoppm", "-r", "40", "-png", str(out / "report.pdf"), str(tmp_path / "page")],
        check=True,
        timeout=120,
    )
    pages = sorted(tmp_path.glob("page-*.png"))
    assert len(pages) >= 5
    for p in pages:
        assert not_blank(p) > 0.02, p.name


def test_cutoff_map_lookup_nearest_station():
    from psdbound.ionosphere.policy import cutoff_from_map

    f_c, info = cutoff_from_map(41.84, -87.63)  # Chicago -> SASK (Saskatoon)
    assert info["station"] == "SASK" and 10 < info["station_distance_deg"] < 20
    assert 1e-4 < f_c < 1 / 24
    f_c2, info2 = cutoff_from_map(-26.0, -110.0)
    assert info2["station"] == "ISPA" and f_c2 != f_c


@pytest.mark.xfail(
    strict=False,
    reason=(
        "known gap (issue 27): after the screening against the multipath null (issue 29) the demo "
        "keeps every block, and one of its 13 homogeneous windows (G22, 160 min) fails the "
        "family-wise shape test and forms a group of its own; with its bands merged to 40 "
        "degrees of freedom the bound is 5.11 mm / 26.1 s, variance 2.7 x the truth's (5.4 "
        "before the merging; 1.8 with 14 windows in one group)"
    ),
)
def test_demo_bound_is_within_twice_the_truth_variance():
    import psdbound

    assert psdbound.fit().document["demo"]["variance_ratio"] <= 2.0


def test_time_in_windows_is_one_number_in_every_output(demo_run):
    """'data covered by the bound', the verdict's 'data for tau' and the windows' hours
    are one measure: the union of the windows' epochs, each sample once."""
    from psdbound.stationarity import covered_time_s

    assert covered_time_s([(1, 0.0, 100.0), (1, 50.0, 200.0), (2, 0.0, 10.0)], 1.0) == 212.0
    work, r = demo_run
    d = psdbound.load(work / "reports" / "demo" / "result.json").document
    w = d["windows"]
    spans = [(x["arc"], x["t_start_gps_s"], x["t_stop_gps_s"]) for x in w["per_window"]]
    assert w["covered_s"] == pytest.approx(covered_time_s(spans, d["sampling"]["interval_s"]))
    assert w["covered_s"] <= w["data_s"] and w["covered_fraction"] <= 1.0
    hours = f"{w['covered_s'] / 3600:.2f} h"
    tau_check = [c for c in d["verdict_checks"] if c["rule"] == "data for tau"][0]
    assert tau_check["measured"].startswith(hours), (tau_check, hours)
    assert f"data covered by the bound: {hours}" in r.stdout
    assert f"stationary windows ({hours})" in r.stdout
