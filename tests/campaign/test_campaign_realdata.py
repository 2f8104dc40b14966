"""Campaigns on the real station files: navigation matched by content, fit's verdicts kept."""

from __future__ import annotations

import json

import pytest
from conftest import ESBC_NAV, ESBC_OBS, NYA1_NAV, NYA1_OBS, shared_file

import psdbound
from psdbound.campaign import plan_campaign
from psdbound.cli.main import main
from psdbound.errors import InputError

ZIMM_OBS = ("zimm0010.21o.gz", "zimm0020.21o.gz", "zimm0030.21o.gz")
ZIMM_NAV = ("cbw10010.21n.gz", "brdc0020.21n.gz", "brdc0030.21n.gz")


@pytest.mark.realdata
def test_zimm_navigation_matched_by_the_time_it_covers():
    obs = [shared_file(n) for n in ZIMM_OBS]
    nav = [shared_file(n) for n in ZIMM_NAV]
    # day 001's file is a nearby station's (cbw1), and it also holds day 002's first record
    plan = plan_campaign(obs[::-1], [nav[2], nav[0], nav[1]])
    assert [(p.station, p.day) for p in plan] == [
        ("ZIMM", "2021-01-01"),
        ("ZIMM", "2021-01-02"),
        ("ZIMM", "2021-01-03"),
    ]
    assert [p.nav for p in plan] == [str(n) for n in nav]
    with pytest.raises(InputError) as exc:
        plan_campaign(obs[1:2], [nav[0], nav[2]])
    msg = str(exc.value)
    assert msg.startswith(str(obs[1])) and "no navigation file covers" in msg
    assert "cbw10010.21n.gz (17 %" in msg and "brdc0030.21n.gz (17 %" in msg


@pytest.mark.realdata
@pytest.mark.slow
def test_nya1_refused_as_fit_refuses_it_esbc_pooled_as_fit(tmp_path, capsys):
    files = [shared_file(n) for n in (NYA1_OBS, ESBC_OBS, ESBC_NAV, NYA1_NAV)]
    out = tmp_path / "c"
    code = main(
        [
            "campaign",
            str(files[0]),
            str(files[1]),
            "--nav",
            str(files[2]),
            str(files[3]),
            "--out",
            str(out),
            "--workers",
            "0",
            "--cache-dir",
            str(tmp_path / "cache"),
            "--no-pdf",
        ]
    )
    assert code == 3, capsys.readouterr().err
    doc = json.loads((out / "campaign.json").read_text())
    days = {d["station"]: d for d in doc["days"]}
    nya1 = psdbound.fit(files[0], files[3])
    assert nya1.verdict == "not-bounded"
    assert (days["NYA1"]["verdict"], days["NYA1"]["verdict_reasons"]) == (
        nya1.verdict,
        nya1.verdict_reasons,
    )
    assert days["NYA1"]["in_pool"] is False and days["ESBC"]["in_pool"] is True
    st = {s["station"]: s for s in doc["stations"]}
    assert st["NYA1"]["verdict"] == "not-bounded"
    assert st["NYA1"]["excluded_days"] == [
        {"day": "2024-05-03", "verdict": "not-bounded", "reasons": nya1.verdict_reasons}
    ]
    assert st["ESBC"]["verdict"] == "bounded"
    # one day pooled alone: the pooled bound is fit's (same bands, same low-frequency statement)
    esbc = psdbound.fit(files[1], files[2])
    for key in ("sigma_gm_m", "tau_s", "sigma_wn_m"):
        assert st["ESBC"][key] == pytest.approx(getattr(esbc.bound, key), rel=1e-6, abs=1e-9)
    assert (
        st["ESBC"]["low_frequency"]["status"] == esbc.document["bound"]["low_frequency"]["status"]
    )
    page = (out / "campaign.html").read_text()
    assert "one day: no day-to-day comparison" in page and "no bounded day left" in page
