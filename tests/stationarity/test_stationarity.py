"""Elevation mapping, Levene/K-S window test and the slide/trim windowing."""

from __future__ import annotations

import numpy as np
import pytest

import psdbound.stationarity.windowing as windowing
from psdbound.errors import InputError, NoDataError
from psdbound.isolation import MultipathSeries
from psdbound.stationarity import (
    THESIS_MAPPING,
    ElevationMapping,
    StationarityTest,
    find_stationary_windows,
    fit_mapping,
    test_stationarity,
    window_arc,
)


def test_thesis_mapping_closed_form():
    m = THESIS_MAPPING
    assert m.factor(0.0) == pytest.approx(30.0)
    assert m.factor(10.0) == pytest.approx(1 + 29 * np.exp(-0.5))
    assert m.factor(90.0) == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(m.apply([3.0], [0.0]), [0.1])
    with pytest.raises(InputError, match="finite elevations"):
        m.apply([1.0], [np.nan])
    with pytest.raises(InputError, match="a > 0"):
        ElevationMapping(0.0, 1.0, 1.0)


def test_fit_mapping_recovers_parameters():
    rng = np.random.default_rng(3)
    el = rng.uniform(5, 90, 200_000)
    true = ElevationMapping(1.0, 12.0, 14.0)
    x = 0.004 * true.factor(el) * rng.standard_normal(el.size)
    fitted = fit_mapping(x, el, bin_deg=2.5)
    assert fitted.source == "fitted"
    assert fitted.b == pytest.approx(12.0, rel=0.1)
    assert fitted.c_deg == pytest.approx(14.0, rel=0.1)
    with pytest.raises(InputError, match="only 1 elevation bins"):
        fit_mapping(x[:100], np.full(100, 45.0))


def test_stationarity_test_decisions():
    rng = np.random.default_rng(0)
    white = rng.standard_normal(4000)
    res = test_stationarity(white)
    assert res.stationary and res.levene_p > 0.05 and res.ks_p > 0.05
    step = np.r_[rng.standard_normal(2000), 3 * rng.standard_normal(2000)]
    res = test_stationarity(step)
    assert not res.stationary and res.ks_p is None  # Levene already rejects
    shift = np.r_[rng.standard_normal(2000), 1.0 + rng.standard_normal(2000)]
    res = test_stationarity(shift)  # same variance, different mean: K-S rejects
    assert res.levene_p > 0.05 and not res.stationary and res.ks_p < 0.05


def test_window_arithmetic_by_hand(monkeypatch):
    """A fake test (stationary iff the window avoids sample 50) pins the slide/trim rules."""

    def fake(x, alpha=0.05, center="mean"):
        ok = not (x[0] <= 50 <= x[-1])
        return StationarityTest(ok, 1.0 if ok else 0.0, 1.0 if ok else None, alpha)

    monkeypatch.setattr(windowing, "test_stationarity", fake)
    x = np.arange(100.0)  # values = indices
    wins, n_tests = window_arc(x, 20)
    starts_stops = [(s, e) for s, e, _, _ in wins]
    # [0,99] -> trim to [0,79] -> [0,63] -> [0,50] -> [0,39]: stationary, kept
    assert starts_stops[0] == (0, 39)
    # slide by ceil(0.2*40) = 8 -> [8,99] -> trims [8,80], [8,65], [8,53], [8,43]: kept
    assert starts_stops[1] == (8, 43)
    for s, e in starts_stops:
        assert 0 <= s <= e <= 99 and e - s + 1 >= 20 and not s <= 50 <= e
    assert starts_stops[-1][1] == 99  # the algorithm ends on a window reaching the arc end
    assert n_tests > len(wins)


def test_variance_step_in_the_middle():
    rng = np.random.default_rng(11)
    x = np.r_[0.002 * rng.standard_normal(1500), 0.008 * rng.standard_normal(1500)]
    wins, _ = window_arc(x, 200)
    assert wins, "no stationary window found"
    for s, e, _, _ in wins:
        # no kept window straddles the step by more than the test can miss
        straddle = min(e, 2999) - max(s, 1500) + 1 if e >= 1500 and s < 1500 else 0
        inside_low = max(0, min(e, 1499) - s + 1)
        assert straddle == 0 or inside_low < 0.15 * (e - s + 1) or straddle < 0.15 * (e - s + 1)
    covered = np.zeros(3000, bool)
    for s, e, _, _ in wins:
        covered[s : e + 1] = True
    assert covered[:1400].mean() > 0.9 and covered[1600:].mean() > 0.9


def test_outlier_block_is_reported_not_hidden():
    rng = np.random.default_rng(5)
    n = 3000
    x = 0.003 * rng.standard_normal(n)
    x[1400:1460] += 0.05 * rng.choice([-1, 1], 60)
    t = 1.3e9 + np.arange(n, dtype=float)
    series = MultipathSeries(
        method="DF",
        t_gps_s=t,
        value_m=x,
        elevation_deg=np.full(n, 90.0),
        arc_id=np.zeros(n, dtype=np.intp),
        arc_sats=("G01",),
        signals=("L1C", "L2W"),
        scaling=1 / np.sqrt(2),
        interval_s=1.0,
    )
    ws = find_stationary_windows(series, min_length_s=200)
    assert len(ws) >= 2
    for w in ws.windows:
        assert not (w.start <= 1430 <= w.stop), "a window covers the outlier block"
    # the block is among the never-stationary stretches
    assert any(a <= t[1430] <= b for _, _, a, b in ws.uncovered)
    assert ws.uncovered_s >= 60
    assert "never stationary" in ws.summary()


def test_no_arc_long_enough():
    n = 100
    series = MultipathSeries(
        "DF",
        np.arange(n, dtype=float),
        np.zeros(n),
        np.full(n, 45.0),
        np.zeros(n, dtype=np.intp),
        ("G01",),
        ("L1C", "L2W"),
        0.7,
        1.0,
    )
    with pytest.raises(NoDataError, match="no arc is as long as the minimum window"):
        find_stationary_windows(series, min_length_s=600)
