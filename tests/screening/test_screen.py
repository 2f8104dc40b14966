"""screen_series on synthetic series: disturbed spans found, quiet data kept."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.isolation import MultipathSeries
from psdbound.screening import ScreeningOptions, geometry_free_m_per_tecu, screen_series

K = geometry_free_m_per_tecu(1575.42e6, 1227.60e6)


def _series(disturb=(), implausible=(), dt=30.0, n_arcs=3, hours=4.0, seed=1):
    rng = np.random.default_rng(seed)
    arcs = []
    for a in range(n_arcs):
        t = 1e6 + a * 86400.0 + np.arange(0.0, hours * 3600.0, dt)
        # quiet: smooth TEC trend + mm multipath; ROTI ~ 0.02 TECU/min
        gf = K * (
            5.0 + 2.0 * np.sin(2 * np.pi * (t - t[0]) / 20000.0)
        ) + 0.002 * rng.standard_normal(t.size)
        v = 0.002 * rng.standard_normal(t.size)
        for arc, t0, t1 in disturb:  # fast TEC fluctuations, ROTI ~ 1 TECU/min
            if arc == a:
                sel = (t - t[0] >= t0) & (t - t[0] < t1)
                gf[sel] += K * 0.3 * rng.standard_normal(sel.sum())
        for arc, t0, t1 in implausible:
            if arc == a:
                sel = (t - t[0] >= t0) & (t - t[0] < t1)
                v[sel] += 0.12
        arcs.append(
            {
                "sats": f"G{a + 1:02d}",
                "t_gps_s": t,
                "value_m": v,
                "elevation_deg": np.full(t.size, 45.0),
                "unfiltered_m": gf,
            }
        )
    return MultipathSeries.from_arcs(
        "DF", arcs, signals=("L1C", "L2W"), scaling=2**-0.5, interval_s=dt, cutoff_hz=9.55e-4
    )


def test_quiet_series_is_untouched():
    s = _series()
    sc = screen_series(s)
    assert sc.excluded == () and sc.excluded_fraction == 0.0
    assert sc.series.n_arcs == s.n_arcs and np.array_equal(sc.series.value_m, s.value_m)


@pytest.mark.parametrize("dt", [1.0, 30.0])
def test_disturbed_span_is_excluded_and_listed(dt):
    s = _series(disturb=[(1, 3600.0, 5400.0)], dt=dt, hours=3.0 if dt == 1.0 else 4.0)
    sc = screen_series(s, ScreeningOptions(guard_s=0.0))
    iono = [e for e in sc.excluded if e.kind == "ionosphere"]
    assert len(iono) == 1 and iono[0].sat == "G02"
    t0 = s.t_gps_s[s.arc_id == 1][0]
    # the excluded span covers the disturbance (5-min block resolution)
    assert iono[0].start_gps_s <= t0 + 3600.0 + 1 and iono[0].stop_gps_s >= t0 + 5400.0 - dt - 1
    assert iono[0].stop_gps_s - iono[0].start_gps_s <= 1800.0 + 600.0
    assert iono[0].statistic > iono[0].threshold == 0.15
    assert "ROTI" in iono[0].reason and "TECU/min" in iono[0].reason
    # the arc is split, nothing outside the span is lost
    assert sc.series.n_arcs == s.n_arcs + 1
    assert sc.excluded_s == pytest.approx(sum(e.duration_s + dt for e in sc.excluded), rel=0.02)


def test_implausible_values_are_excluded_with_the_limit():
    s = _series(implausible=[(0, 7200.0, 7500.0)])
    sc = screen_series(s)
    imp = [e for e in sc.excluded if e.kind == "implausible"]
    assert len(imp) == 1 and imp[0].threshold == pytest.approx(0.0770, abs=2e-4)
    assert imp[0].statistic > imp[0].threshold and "cm" in imp[0].reason


def test_short_remainders_are_excluded_not_dropped_silently():
    # two disturbances 8 min apart leave a remainder shorter than a 10-min window
    s = _series(disturb=[(0, 1800.0, 3000.0), (0, 3480.0, 4800.0)])
    sc = screen_series(s, ScreeningOptions(guard_s=0.0), min_length_s=600.0)
    kinds = {e.kind for e in sc.excluded}
    assert "short remainder" in kinds
    kept = sc.series.t_gps_s.size * s.interval_s
    assert kept + sc.excluded_s == pytest.approx(sc.input_s)


def test_options_are_checked():
    from psdbound.errors import InputError

    with pytest.raises(InputError, match="roti_threshold_tecu_min"):
        ScreeningOptions(roti_threshold_tecu_min=-1.0)


class _Mapping:
    """Thesis-like mapping: strong multipath at low elevation."""

    def factor(self, el):
        return 1.0 + 29.0 * np.exp(-(np.asarray(el) ** 2) / (2 * 10.0**2))


def _low_elevation_roughness(elevation):
    # a rough but quiet arc: ROTI ~ 0.3 TECU/min from multipath-like GF noise
    rng = np.random.default_rng(7)
    t = 1e6 + np.arange(0.0, 4 * 3600.0, 30.0)
    gf = K * 0.1 * rng.standard_normal(t.size)
    arc = {
        "sats": "G07",
        "t_gps_s": t,
        "value_m": 0.003 * rng.standard_normal(t.size),
        "elevation_deg": np.full(t.size, elevation),
        "unfiltered_m": gf,
    }
    return MultipathSeries.from_arcs(
        "DF", [arc], signals=("L1C", "L2W"), scaling=2**-0.5, interval_s=30.0, cutoff_hz=9.55e-4
    )


def test_fixed_threshold_scales_with_the_multipath_mapping():
    fixed = ScreeningOptions(multipath_null=False)
    low = _low_elevation_roughness(12.0)
    flat = screen_series(low, ScreeningOptions(elevation_scaled=False, multipath_null=False))
    scaled = screen_series(low, fixed, mapping=_Mapping())
    assert flat.excluded_fraction > 0.5  # a flat 0.15 would throw away low-elevation multipath
    assert scaled.excluded_fraction == 0.0  # 0.15 x m(12 deg) = 2.3 TECU/min
    high = _low_elevation_roughness(70.0)  # the same roughness at 70 deg is not multipath-like
    assert screen_series(high, fixed, mapping=_Mapping()).excluded_fraction > 0.5


def test_multipath_null_keeps_rough_multipath_without_a_mapping():
    """Issue 29: the series' own multipath sets the threshold; no mapping is needed."""
    low = _low_elevation_roughness(12.0)
    res = screen_series(low)  # default: the multipath null, no mapping given
    assert res.null is not None and res.null.trusted
    assert res.excluded_fraction < 0.02


def test_default_guard_is_half_a_cutoff_period():
    s = _series(disturb=[(1, 3600.0, 5400.0)])
    no_guard = screen_series(s, ScreeningOptions(guard_s=0.0))
    auto = screen_series(s)
    assert auto.guard_s == pytest.approx(0.5 / 9.55e-4)
    span = [e for e in auto.excluded if e.kind == "ionosphere"][0]
    span0 = [e for e in no_guard.excluded if e.kind == "ionosphere"][0]
    assert span.start_gps_s == pytest.approx(span0.start_gps_s - 540.0, abs=30.0)
    assert span.stop_gps_s == pytest.approx(span0.stop_gps_s + 540.0, abs=30.0)


def test_spans_known_to_hold_multipath_are_kept():
    # a campaign passes the spans that repeat one sidereal day later: flagged there, kept
    s = _series(disturb=[(1, 3600.0, 5400.0), (2, 3600.0, 5400.0)])
    t1 = s.t_gps_s[s.arc_id == 1][0]
    keep = (("G02", t1 + 3000.0, t1 + 6000.0),)
    sc = screen_series(s, ScreeningOptions(guard_s=0.0, keep_spans=keep))
    iono = [e for e in sc.excluded if e.kind == "ionosphere"]
    assert [e.sat for e in iono] == ["G03"]  # G02's span kept, G03's still excluded
    assert any("kept as multipath" in n and "sidereal" in n for n in sc.notes)
    plain = screen_series(s, ScreeningOptions(guard_s=0.0))
    assert sorted(e.sat for e in plain.excluded if e.kind == "ionosphere") == ["G02", "G03"]
    assert sc.excluded_s < plain.excluded_s
