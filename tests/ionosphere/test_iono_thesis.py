"""Chicago 2020 against the thesis's cutoffs (section 4.3.3), side by side (issue #16).

Thesis: mean 6.73e-4 Hz, min 5.03e-4 Hz, max (recommended) 9.55e-4 Hz from
the 40 dB Lomb-Scargle criterion on IRI-2016 delays. Ours: the residual
criterion (the fit's high-pass leaves the ionosphere 40 dB below 1 mm in the
fit's series) on PyIRI delays. docs/cutoff.md explains the difference; the
numbers pinned here are those of the table there:

* mean +30 % and min -30 % of the thesis (pinned within +-35 %), max 1.5x
  (within a factor 2);
* at a 30 dB margin our maximum is the thesis's maximum within 30 %: the
  thesis's cutoff leaves at most about 0.03 mm of ionosphere in the fit's
  series over Chicago 2020;
* the issue-#4 criterion (untapered Lomb-Scargle) is 5-10x the thesis.
"""

from __future__ import annotations

import pytest

from psdbound.ionosphere import (
    CHICAGO,
    THESIS_CHICAGO_2020_HZ,
    CutoffSettings,
    select_days,
    station_cutoffs,
)

THESIS = THESIS_CHICAGO_2020_HZ


def test_one_june_day_against_the_thesis():
    """June 1 2020 (the month of Chicago's largest cutoff), in-process: a quick check."""
    res = station_cutoffs(
        CHICAGO.lat_deg,
        CHICAGO.lon_deg,
        ["2020-06-01"],
        workers=0,
        use_cache=False,
        keep_series=False,
    )
    s = res.summary()
    assert s["n_series"] >= 20 and s["n_not_reached"] == 0 and s["n_floor"] == 0
    assert 0.7 < s["mean_f_c_hz"] / THESIS["mean"] < 1.6
    assert 1.0 < s["max_f_c_hz"] / THESIS["max"] < 2.0
    m30 = next(m for m in s["by_margin"] if m["margin_db"] == 30.0)
    assert m30["max_f_c_hz"] == pytest.approx(THESIS["max"], rel=0.3)


@pytest.mark.slow
def test_chicago_2020_station_year_against_the_thesis(tmp_path):
    res = station_cutoffs(
        CHICAGO.lat_deg,
        CHICAGO.lon_deg,
        select_days(2020),
        name="CHICAGO",
        workers=2,
        cache_dir=tmp_path,
        keep_series=False,
    )
    s = res.summary()
    ratios = {k: s[f"{k}_f_c_hz"] / THESIS[k] for k in ("mean", "min", "max")}
    assert 0.65 <= ratios["mean"] <= 1.35, ratios
    assert 0.65 <= ratios["min"] <= 1.35, ratios
    assert 1.0 < ratios["max"] < 2.0, ratios
    m30 = next(m for m in s["by_margin"] if m["margin_db"] == 30.0)
    assert m30["max_f_c_hz"] == pytest.approx(THESIS["max"], rel=0.3)
    assert s["recommended_f_c_hz"] == s["max_f_c_hz"]


@pytest.mark.slow
def test_issue_4_criterion_is_leakage_bound(tmp_path):
    """The untapered 40 dB Lomb-Scargle criterion, two days: 5-10x the thesis."""
    res = station_cutoffs(
        CHICAGO.lat_deg,
        CHICAGO.lon_deg,
        ["2020-01-06", "2020-07-06"],
        workers=2,
        settings=CutoffSettings.legacy(),
        cache_dir=tmp_path,
        keep_series=False,
    )
    s = res.summary()
    assert s["mean_f_c_hz"] / THESIS["mean"] > 4
