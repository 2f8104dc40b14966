"""The multipath null of ROTI: stated false-alarm rate, robust to disturbed blocks (issue 29)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats
from scipy.signal import lfilter

from psdbound.screening import geometry_free_m_per_tecu, rate_of_tec, roti_blocks
from psdbound.screening.null import Q_HI, fit_null, local_scale


def _chi2_roti(rng, n, s, nu):
    return s * np.sqrt(rng.chisquare(nu, n) / nu)


@pytest.mark.parametrize("nu", [3.0, 8.0, 20.0])
def test_recovers_a_scaled_chi_square_and_holds_its_false_alarm_rate(nu):
    rng = np.random.default_rng(int(nu))
    el = rng.uniform(10.0, 90.0, 4000)
    s = 0.02 + 0.2 * np.exp(-el / 15.0)  # multipath ROT sd falls with elevation, TECU/min
    null = fit_null(_chi2_roti(rng, el.size, s, nu), el)
    assert null is not None
    assert null.dof == pytest.approx(nu, rel=0.35)
    # fresh blocks of the same multipath: the stated rate, at every elevation
    el2 = rng.uniform(10.0, 90.0, 200_000)
    r2 = _chi2_roti(rng, el2.size, 0.02 + 0.2 * np.exp(-el2 / 15.0), nu)
    for p in (1e-2, 1e-3):
        hit = r2 > null.threshold(el2, p)
        assert hit.mean() < 3 * p
        assert hit[el2 < 30].mean() < 4 * p and hit[el2 > 60].mean() < 4 * p


def test_local_scale_holds_at_the_ends_of_the_elevation_range():
    """The window at the lowest elevations is one-sided: its quantile belongs to its median.

    Placed at the lowest block's elevation (as before), the scale came out 13 %
    low at 11.5 deg and 10 % at 12 deg where multipath grows towards the horizon;
    the false alarms of the lowest satellites then ran 2.8 times the stated rate
    against 1.4-2.2 elsewhere (synthetic days, share 1e-3).
    """
    rng = np.random.default_rng(5)
    nu = 8.0
    el = rng.uniform(10.0, 80.0, 48_000)
    s = 0.03 + 0.3 * np.exp(-(el - 10.0) / 10.0)  # ROT sd, TECU/min
    grid, q, _ = local_scale(s**2 * rng.chisquare(nu, el.size) / nu, el)
    e = np.array([11.5, 12.0, 20.0, 40.0, 78.0])
    true = (0.03 + 0.3 * np.exp(-(e - 10.0) / 10.0)) ** 2 * stats.chi2.ppf(Q_HI, nu) / nu
    assert np.allclose(np.interp(e, grid, q), true, rtol=0.04)


def test_disturbed_blocks_do_not_move_the_null_and_are_found():
    rng = np.random.default_rng(7)
    el = rng.uniform(10.0, 90.0, 3000)
    s = 0.03 + 0.1 * np.exp(-el / 20.0)
    r = _chi2_roti(rng, el.size, s, 8.0)
    clean = fit_null(r, el)
    bad = rng.random(el.size) < 0.3  # 30 % of the blocks disturbed
    r_dist = np.where(bad, np.hypot(r, 0.5), r)  # + 0.5 TECU/min of ionosphere
    null = fit_null(r_dist, el)
    e = np.linspace(15.0, 85.0, 8)
    # 30 % of blocks far above move the local quantiles up by at most a few tens of %
    assert np.allclose(null.scale2(e) ** 0.5, clean.scale2(e) ** 0.5, rtol=0.4)
    found = r_dist[bad] > np.maximum(0.15, null.threshold(el[bad], 1e-3))
    assert found.mean() > 0.95


def test_gauss_markov_multipath_rot_at_the_stated_rate():
    """ROTI of a simulated GM + white geometry-free multipath, mapped with elevation."""
    rng = np.random.default_rng(3)
    k = geometry_free_m_per_tecu(1575.42e6, 1227.60e6)
    rot_all, el_all = [], []
    for _ in range(40):  # 40 arcs of 6 h at 30 s
        n = 720
        el = 10.0 + 70.0 * np.sin(np.pi * np.arange(n) / n)
        m = 1.0 + 2.0 * np.exp(-(el**2) / (2 * 15.0**2))
        phi = np.exp(-30.0 / 30.0)
        gm = lfilter([1.0], [1.0, -phi], rng.normal(0, 0.006 * np.sqrt(1 - phi**2), n))
        gf = np.sqrt(2.0) * m * (gm + rng.normal(0, 0.001, n))
        t = 30.0 * np.arange(n)
        tm, rot = rate_of_tec(t, gf, k)
        rb = roti_blocks(tm, rot, t0_gps_s=0.0, t1_gps_s=t[-1])
        rot_all.append(rb.roti_tecu_min)
        el_all.append(np.interp(0.5 * (rb.start_gps_s + rb.stop_gps_s), t, el))
    roti, elb = np.concatenate(rot_all), np.concatenate(el_all)
    null = fit_null(roti, elb)
    hit = roti > null.threshold(elb, 1e-2)
    assert hit.mean() < 3e-2  # stated 1e-2 per block (this multipath trips a fixed 0.15 often)
    assert (roti > 0.15).mean() > 0.3


def test_persistence_finds_a_weak_disturbance_the_single_blocks_miss():
    """A 0.25 TECU/min disturbance over an hour where multipath gives about 0.15 (issue 29)."""
    rng = np.random.default_rng(11)
    el = rng.uniform(10.0, 90.0, 3000)
    null = fit_null(_chi2_roti(rng, el.size, 0.15, 6.0), el)
    arc_el = np.full(60, 21.0)  # 5 h of one arc at 21 deg
    quiet = _chi2_roti(rng, arc_el.size, 0.15, 6.0)
    hit = quiet.copy()
    hit[20:32] = np.hypot(hit[20:32], 0.25)  # one hour disturbed
    single = hit > np.maximum(0.15, null.threshold(arc_el, 1e-3))
    runs = null.persistent(hit, arc_el, floor_tecu_min=0.15)
    assert single[20:32].mean() < 0.9  # the single-block test misses some of it
    assert (single | runs)[20:32].mean() > 0.95
    assert not null.persistent(quiet, arc_el, floor_tecu_min=0.15).any()
