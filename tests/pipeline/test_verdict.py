"""The verdict: one test per rule, and the real cases that must not exit 0."""

from __future__ import annotations

import copy
import subprocess
import sys

import pytest
from conftest import ESBC_NAV, ESBC_OBS, GRAS_OBS, NYA1_NAV, NYA1_OBS, UPC1_OBS, shared_file
from samples import esbc_hours

import psdbound
from psdbound.pipeline.verdict import VerdictOptions, judge, verdict_checks
from psdbound.results.headline import DO_NOT_USE, headline

GOOD = {
    "bound": {
        "sigma_gm_m": 0.006,
        "tau_s": 58.0,
        "sigma_wn_m": 0.0,
        "tau_grid_s": [15.0, 60.0, 2.0e5],
    },
    "sampling": {"interval_s": 30.0, "nyquist_hz": 1 / 60},
    "cutoff": {"f_c_hz": 9.55e-4},
    "isolation": {"safety": {"removed_above_fc_median": 0.18}, "offered": {"offered_s": 7200.0}},
    "screening": {"excluded_fraction": 0.02, "multipath_limit_m": 0.0770},
    "validation": {"max_removed_rms_m": 0.0025, "geometries_used": ["ground:h=0.216"]},
    "windows": {
        "per_window": [
            {"arc": 0, "t_start_gps_s": 0.0, "t_stop_gps_s": 3570.0},
            {"arc": 0, "t_start_gps_s": 1800.0, "t_stop_gps_s": 5370.0},
            {"arc": 1, "t_start_gps_s": 0.0, "t_stop_gps_s": 1770.0},
        ]
    },
}


def _with(path, value):
    d = copy.deepcopy(GOOD)
    *head, last = path.split(".")
    cur = d
    for k in head:
        cur = cur[k]
    cur[last] = value
    return d


def test_good_document_is_bounded():
    assert judge(GOOD) == ("bounded", [])


@pytest.mark.parametrize(
    ("path", "value", "words", "n"),
    [
        ("bound.sigma_gm_m", 0.0, "sigma_GM = 0", 1),
        ("bound.tau_s", 15.0, "end of its search grid", 1),
        # tau at the top of the grid: also far more than the data can resolve
        ("bound.tau_s", 2.0e5, "end of its search grid", 2),
        ("bound.tau_s", 200.0, "too little stationary data", 1),  # 2 h covered < 50 x 200 s
        ("isolation.safety", {"removed_above_fc_median": 0.875}, "filter loss", 1),
        ("cutoff.f_c_hz", 9.5e-3, "below the Nyquist", 1),
        ("screening.excluded_fraction", 0.62, "most data excluded", 1),
        (
            "bound.low_frequency",
            {"status": "prior", "tau_max_s": 900.0, "envelope_at_0_m2_hz": None},
            "only time constants above",
            1,
        ),
        # 2 h in windows of 24 h offered (e.g. an orbit file covering 17 % of the day)
        ("isolation.offered", {"offered_s": 86400.0}, "data used", 1),
        # 19.7 cm "bounded" on a real 1.6 m pair with a forced baseline (issue 30)
        ("bound.sigma_gm_m", 0.197, "physical limit", 1),
    ],
)
def test_each_rule_fires(path, value, words, n):
    verdict, reasons = judge(_with(path, value))
    assert verdict == "not-bounded"
    assert len(reasons) == n and any(words in r for r in reasons), reasons


def test_removed_multipath_is_modelled_not_a_refusal():
    """Issue 28 part 2: what the high-pass removes is the error model's slow component."""
    d = _with("validation", {"max_removed_rms_m": 0.009, "geometries_used": ["ground:h=1.5"]})
    assert judge(d) == ("bounded", [])


def test_low_frequency_policy_is_an_option():
    d = _with(
        "bound.low_frequency", {"status": "prior", "tau_max_s": 900.0, "envelope_at_0_m2_hz": 1e-3}
    )
    assert judge(d) == ("bounded", [])
    verdict, reasons = judge(d, VerdictOptions(low_frequency="refuse"))
    assert verdict == "not-bounded" and "policy is 'refuse'" in reasons[0]


def test_thresholds_are_options():
    d = _with("screening.excluded_fraction", 0.62)
    assert judge(d, VerdictOptions(max_excluded_fraction=0.7)) == ("bounded", [])


def _one_hour_of_esbc(tmp_path):
    return esbc_hours(tmp_path / "ESBC1H.rnx", [12])  # 12:00-12:59:30


@pytest.mark.realdata
@pytest.mark.slow
def test_one_hour_file_exits_3_with_outputs_and_reasons(tmp_path):
    obs = _one_hour_of_esbc(tmp_path)
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            str(obs),
            "--nav",
            str(shared_file(ESBC_NAV)),
            "--cutoff-hz",
            "9.55e-4",
            "--out",
            str(tmp_path / "out"),
            "--no-pdf",
            # the thesis test accepts 10-min windows; the spectral test needs 68 samples (34 min)
            "--stationarity",
            "thesis",
            "--windows",
            "slide",
            "--rule",
            "envelope",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 3, r.stderr
    doc = psdbound.load(tmp_path / "out" / "result.json").document
    assert doc["verdict"] == "not-bounded"
    reasons = " ".join(doc["verdict_reasons"])
    assert "filter loss" in reasons or "too little stationary data" in reasons
    assert "NOT-BOUNDED" in r.stdout and "reason:" in r.stdout
    html = (tmp_path / "out" / "report.html").read_text()
    assert "not-bounded" in html[: html.index("<h2>Bound</h2>")]  # on the first page


@pytest.mark.realdata
@pytest.mark.slow
def test_one_hour_file_with_default_test_says_why_no_window(tmp_path):
    obs = _one_hour_of_esbc(tmp_path)
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            str(obs),
            "--nav",
            str(shared_file(ESBC_NAV)),
            "--cutoff-hz",
            "9.55e-4",
            "--out",
            str(tmp_path / "out"),
            "--no-pdf",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert r.returncode == 2
    assert "68 samples" in r.stderr and "34 min" in r.stderr and "the longest of the" in r.stderr
    assert not (tmp_path / "out").exists()


@pytest.mark.realdata
@pytest.mark.slow
def test_map_cutoff_on_nya1_never_gives_a_white_noise_bound_with_exit_0():
    # issue 14: the old leakage-inflated map gave sigma_GM = 0 with exit 0 here
    res = psdbound.fit(shared_file(NYA1_OBS), nav=shared_file(NYA1_NAV), cutoff={"source": "map"})
    assert res.document["cutoff"]["source"].startswith("map")
    if (
        res.bound.sigma_gm_m == 0.0
        or res.document["sampling"]["nyquist_hz"] < 4 * (res.document["cutoff"]["f_c_hz"])
    ):
        assert res.verdict == "not-bounded"
    else:
        assert res.bound.sigma_gm_m > 0


@pytest.mark.realdata
@pytest.mark.slow
def test_consecutive_files_are_merged_into_the_whole_day(tmp_path):
    # issue 18: six files used to fit only the first; now the day in three pieces = the day
    parts = [esbc_hours(tmp_path / f"ESBC{h:02d}.rnx", range(h, h + 8)) for h in (16, 0, 8)]
    nav = shared_file(ESBC_NAV)
    whole = psdbound.fit(shared_file(ESBC_OBS), nav=nav, cutoff={"f_c_hz": 1.5e-3})
    merged = psdbound.fit(parts, nav=nav, cutoff={"f_c_hz": 1.5e-3})
    assert merged.inputs.observations[0].t_gps_s.size == whole.inputs.observations[0].t_gps_s.size
    assert merged.document["method"] == "DF"
    assert merged.bound.sigma_gm_m == pytest.approx(whole.bound.sigma_gm_m, rel=1e-9)
    assert any("3 observation files merged" in w for w in merged.warnings)
    assert len([f for f in merged.provenance["inputs"] if f["role"] == "obs"]) == 3


@pytest.mark.realdata
def test_files_of_three_stations_are_an_error_naming_them(capsys):
    from psdbound.cli.main import main

    code = main(
        [
            "fit",
            str(shared_file(ESBC_OBS)),
            str(shared_file(NYA1_OBS)),
            str(shared_file(UPC1_OBS)),
            "--nav",
            str(shared_file(ESBC_NAV)),
        ]
    )
    err = capsys.readouterr().err
    assert code == 2 and "3 stations" in err and "ESBC" in err and "NYA1" in err


@pytest.mark.realdata
@pytest.mark.slow
def test_glonass_dual_frequency_end_to_end():
    # issue 18: GLONASS broadcast ephemerides (RK4 of the ICD equations) and FDMA channels
    res = psdbound.fit(shared_file(ESBC_OBS), nav=shared_file(ESBC_NAV), system="R")
    assert res.document["isolation"]["signals"] == ["L1C", "L2P"]
    assert res.verdict == "bounded", res.verdict_reasons
    assert 0.5e-3 < res.bound.sigma_gm_m < 0.01


@pytest.mark.realdata
def test_nav_of_another_year_is_named(capsys):
    from psdbound.cli.main import main

    code = main(["fit", str(shared_file(GRAS_OBS)), "--nav", str(shared_file(ESBC_NAV))])
    err = capsys.readouterr().err
    assert code == 2 and "covers 2020-06-24" in err and "2022-11-11" in err
    assert "second frequency" not in err


@pytest.mark.realdata
@pytest.mark.slow
def test_zip_of_several_files_is_read_whole(tmp_path):
    import zipfile

    parts = [esbc_hours(tmp_path / f"ESBC{h:02d}.rnx", range(h, h + 12)) for h in (0, 12)]
    archive = tmp_path / "esbc_day.zip"
    with zipfile.ZipFile(archive, "w", compression=zipfile.ZIP_DEFLATED) as z:
        for p in parts:
            z.write(p, arcname=f"day/{p.name}")
    nav = shared_file(ESBC_NAV)
    zipped = psdbound.fit(archive, nav=nav, cutoff={"f_c_hz": 1.5e-3})
    whole = psdbound.fit(shared_file(ESBC_OBS), nav=nav, cutoff={"f_c_hz": 1.5e-3})
    assert zipped.bound.sigma_gm_m == pytest.approx(whole.bound.sigma_gm_m, rel=1e-9)
    assert any("2 observation files merged" in w for w in zipped.warnings)
    assert zipped.inputs.observations[0].path.startswith(f"{archive}:ESBC00.rnx")


def test_an_unresolved_plateau_is_said_not_silently_extrapolated():
    """Issue 28, part 1 (in part): the data not bounding tau above is a warning of the bound."""
    from types import SimpleNamespace

    from psdbound.pipeline.document import _bound_notes
    from psdbound.spectra.lowfreq import LowFrequency

    ms = SimpleNamespace(
        open_ends={"tau_s": (False, True)},
        tau_interval_s=(40.0, 8580.0),
        widening=1.3,
        confidence_level=0.95,
    )
    low = LowFrequency(
        "prior", 900.0, before={"sigma_gm_m": 0.004, "tau_s": 40.0, "sigma_wn_m": 0.0}, raised=True
    )
    res = SimpleNamespace(
        pooled=None, model_set=ms, bound=SimpleNamespace(f_min_hz=0.002), low_frequency=low
    )
    notes = _bound_notes(res)
    assert any("prior 900 s" in n and "raised" in n for n in notes)
    assert any("do not bound the time constant above" in n for n in notes)
    assert any("widened 1.3 times" in n for n in notes)


def test_every_rule_reports_its_two_numbers_and_the_verdict_follows_them():
    checks = verdict_checks(GOOD)
    names = [c.rule for c in checks]
    assert names == [
        "time correlation",
        "tau inside its search",
        "data for tau",
        "filter loss",
        "band",
        "data excluded",
        "data used",
        "low frequencies",
        "physical limit",
    ]
    assert all(c.passed and c.measured and c.limit and not c.reason for c in checks)
    bad = verdict_checks(_with("bound.sigma_wn_m", 0.08))  # white noise alone above 7.7 cm
    fired = [c for c in bad if not c.passed]
    assert [c.rule for c in fired] == ["physical limit"]
    assert "8.02 cm" in fired[0].measured and "7.70 cm" in fired[0].limit
    assert fired[0].line().endswith("FAIL")
    assert judge(_with("bound.sigma_wn_m", 0.08))[1] == [fired[0].reason]


def test_headline_says_do_not_use_and_states_nothing_when_not_bounded():
    d = _with("bound.sigma_gm_m", 0.197)
    d["verdict"], d["verdict_reasons"] = judge(d)
    d["verdict_checks"] = [c.to_dict() for c in verdict_checks(d)]
    d["bound"]["covers"] = "with 95 % confidence ..."
    lines = headline(d)
    assert lines[0] == f"VERDICT: NOT-BOUNDED - {DO_NOT_USE}"
    assert lines[1] == "rules: 8 of 9 passed"
    assert sum(x.startswith("reason: physical limit") for x in lines) == 1
    assert any(x.startswith("  physical limit:") and x.endswith("FAIL") for x in lines)
    assert lines[-1].startswith("statement: none") and "95 %" not in " ".join(lines)
    d["verdict"] = "bounded"
    assert headline(d)[-1] == "statement: with 95 % confidence ..."


def test_facts_from_products_are_the_document_s():
    # the verdict judges the typed products; a loaded result.json gives the same facts
    import psdbound
    from psdbound.pipeline.verdict import VerdictFacts, verdict_facts

    r = psdbound.fit()
    typed = verdict_facts(
        bounded=r.bounded,
        windowed=r.windowed,
        screened=r.screened,
        isolated=r.isolated,
        cutoff=r.cutoff,
        interval_s=r.inputs.interval_s,
    )
    loaded = VerdictFacts.from_document(r.document)
    assert typed == loaded
    assert [c.to_dict() for c in verdict_checks(typed)] == r.document["verdict_checks"]


def test_physical_limit_is_on_zenith_and_the_mapped_excess_is_stated():
    """The rule tests the data at zenith (the samples were screened against the limit one
    by one); mapped to the lowest elevation, a bound above the limit is conservative there,
    and a note says so instead of calling the data 'not multipath'."""
    from psdbound.pipeline.verdict import VerdictFacts, physical_note

    d = _with("bound.sigma_gm_m", 0.02)  # 2 cm at zenith: under 7.70 cm
    d["mapping"] = {"lowest_elevation_deg": 10.0, "factor_at_lowest": 4.5}  # 9 cm at 10 deg
    assert judge(d) == ("bounded", [])
    check = [c for c in verdict_checks(d) if c.rule == "physical limit"][0]
    assert "2.00 cm at zenith (9.00 cm mapped to 10.0 deg)" in check.measured
    note = physical_note(VerdictFacts.from_document(d))
    assert note and "9.00 cm" in note and "10.0 deg" in note and "conservative" in note
    d["mapping"]["factor_at_lowest"] = 3.5  # 7 cm at 10 deg: under the limit, nothing to say
    assert physical_note(VerdictFacts.from_document(d)) is None
    assert judge(_with("bound.sigma_gm_m", 0.197))[0] == "not-bounded"  # zenith: refused
