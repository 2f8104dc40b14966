"""Screening against ground truth: simulated days with and without ionospheric disturbances."""

from __future__ import annotations

import json

import numpy as np
import pytest

import psdbound
from psdbound.screening.spans import TESTS
from psdbound.simulate import IonoDisturbance, MultipathModel, preset, simulate

F_C_HZ = 9.55e-4
MAPPING = {"kind": "fixed", "a": 1.0, "b": 9.0, "c_deg": 15.0}  # the simulator's mapping


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    base = preset("short").replace(
        name="iono",
        duration_s=8 * 3600.0,
        interval_s=30.0,
        dual_antenna=False,
        seed=11,
        multipath=MultipathModel(sigma_gm_m=0.003, tau_s=60.0, sigma_wn_m=0.0005),
        slip_rate_per_h=0.0,
        gap_rate_per_h=0.0,
    )
    disturbances = (
        IonoDisturbance(3600.0, 2700.0, 1.0),  # every satellite, 45 min, ROTI 1 TECU/min
        IonoDisturbance(5 * 3600.0, 1800.0, 0.6, ("G05", "G12", "G15", "G20", "G25", "G29")),
    )
    out = {}
    for key, sc in (("clean", base), ("disturbed", base.replace(disturbances=disturbances))):
        r = simulate(sc, tmp_path_factory.mktemp(key))
        fit = psdbound.fit(
            r.obs_paths[0], nav=r.nav_path, cutoff={"f_c_hz": F_C_HZ}, mapping=MAPPING
        )
        out[key] = (r, fit)
    return out


def _spans(truth_json, t0):
    meta = json.loads(truth_json.read_text())
    return [
        (t0 + d["start_s"], t0 + d["start_s"] + d["duration_s"], set(d["sats"]))
        for d in meta["scenario"]["disturbances"]
    ]


def test_truth_file_lists_the_disturbances(pair):
    r, _ = pair["disturbed"]
    meta = json.loads(r.truth_json_path.read_text())
    assert [d["roti_tecu_min"] for d in meta["scenario"]["disturbances"]] == [1.0, 0.6]


def test_disturbed_time_is_excluded_and_the_bound_is_unchanged(pair):
    r, fit = pair["disturbed"]
    _, clean = pair["clean"]
    iso = fit.isolated.series
    kept = fit.screened.series
    t0 = float(fit.inputs.t_ref_gps_s)
    spans = _spans(r.truth_json_path, t0)
    memory = 0.5 / F_C_HZ  # the high-pass spreads a disturbance over +- half a cutoff period
    kept_keys = set(
        zip(kept.t_gps_s.round(3), [kept.arc_sats[k] for k in kept.arc_id], strict=True)
    )
    sats = np.array([iso.arc_sats[k] for k in iso.arc_id])
    disturbed = np.zeros(iso.t_gps_s.size, bool)
    near = np.zeros(iso.t_gps_s.size, bool)
    for a, b, which in spans:
        hit = np.array([not which or s in which for s in sats])
        disturbed |= hit & (iso.t_gps_s >= a) & (iso.t_gps_s < b)
        near |= hit & (iso.t_gps_s >= a - memory) & (iso.t_gps_s < b + memory)
    is_kept = np.array(
        [(round(t, 3), s) in kept_keys for t, s in zip(iso.t_gps_s, sats, strict=True)]
    )
    excluded_disturbed = 1.0 - is_kept[disturbed].mean()
    excluded_quiet = 1.0 - is_kept[~near].mean()
    ratio = fit.bound.total_variance_m2 / clean.bound.total_variance_m2
    print(
        f"disturbed time excluded {100 * excluded_disturbed:.1f} %, undisturbed excluded "
        f"{100 * excluded_quiet:.1f} %, bound variance ratio {ratio:.3f} "
        f"(sigma_GM {1000 * fit.bound.sigma_gm_m:.2f} vs {1000 * clean.bound.sigma_gm_m:.2f} mm)"
    )
    assert disturbed.sum() > 0
    assert excluded_disturbed >= 0.90
    assert excluded_quiet <= 0.05
    assert fit.bound.sigma_gm_m == pytest.approx(clean.bound.sigma_gm_m, rel=0.10)
    assert fit.verdict == clean.verdict == "bounded"
    reasons = {e["kind"] for e in fit.document["screening"]["excluded"]}
    assert "ionosphere" in reasons
    # every entry names its test; the ionosphere ones carry the false-alarm probability used
    scr = fit.document["screening"]
    share = scr["block_test"]["false_alarm"]
    assert share == pytest.approx(scr["false_alarm_per_block"] / 3)
    for e in scr["excluded"]:
        assert e["test"] in TESTS
        if e["kind"] == "ionosphere":
            assert e["false_alarm"] == pytest.approx(share)
            if e["test"] == "block":
                assert 0.0 <= e["false_alarm_at_threshold"] <= share * (1 + 1e-9)
        else:
            assert e["false_alarm"] is None
