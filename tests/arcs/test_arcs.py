"""Tracking arcs: gaps, loss of lock, cycle slips, minimum length, elevation mask."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, GRAS_OBS, NYA1_NAV, NYA1_OBS, shared_file
from samples import LAM1, LAM2, make_obs

from psdbound.arcs import find_arcs, require_arcs
from psdbound.errors import InputError, NoDataError
from psdbound.io import read_obs, read_orbit


def smooth_phases(n, seed=0):
    rng = np.random.default_rng(seed)
    k = np.arange(n)
    rho = 2.2e7 + 500.0 * k  # range changing 500 m per epoch
    iono = 2.0 + 0.5 * np.sin(2 * np.pi * k / 800.0)  # metres, slow
    l1 = rho - iono + 3.0 * LAM1 + rng.normal(0, 0.002, n)
    l2 = rho - iono * (1575.42 / 1227.6) ** 2 + 7.0 * LAM2 + rng.normal(0, 0.002, n)
    return l1, l2


def test_one_clean_arc():
    l1, l2 = smooth_phases(200)
    arcs = find_arcs(make_obs(l1, l2), min_length_s=600)
    assert len(arcs) == 1 and arcs[0].n == 200
    assert arcs[0].start_reason == "first epoch"
    np.testing.assert_allclose(arcs[0].phase_m[:, 0], l1)
    assert arcs.breaks == {}


def test_gap_longer_than_one_and_a_half_intervals_breaks():
    l1, l2 = smooth_phases(200)
    t = 1.277e9 + 30.0 * np.arange(200)
    t[100:] += 16.0  # a 46 s step: > 1.5 x 30 s
    arcs = find_arcs(make_obs(l1, l2, t=t), min_length_s=600)
    assert [a.n for a in arcs] == [100, 100]
    assert arcs[1].start_reason == "gap" and arcs.breaks["gap"] == 1
    t = 1.277e9 + 30.0 * np.arange(200)
    t[100:] += 14.0  # a 44 s step: <= 1.5 x 30 s, no break
    assert len(find_arcs(make_obs(l1, l2, t=t), min_length_s=600)) == 1


def test_missing_epochs_break():
    l1, l2 = smooth_phases(200)
    l2[120:122] = np.nan
    arcs = find_arcs(make_obs(l1, l2), min_length_s=600)
    assert [a.n for a in arcs] == [120, 78]
    assert arcs[1].start_reason == "gap"


def test_loss_of_lock_breaks():
    l1, l2 = smooth_phases(200)
    lli = np.zeros(200, np.int8)
    lli[50] = 1
    lli[150] = 2  # bit 1 only (half-cycle): no break
    arcs = find_arcs(make_obs(l1, l2, lli1=lli), min_length_s=600)
    assert [a.n for a in arcs] == [50, 150]
    assert arcs[1].start_reason == "loss of lock"


def test_power_failure_flag_breaks():
    l1, l2 = smooth_phases(200)
    flags = np.zeros(200)
    flags[80] = 1
    arcs = find_arcs(make_obs(l1, l2, flags=flags), min_length_s=600)
    assert [a.start_reason for a in arcs] == ["first epoch", "power failure"]


@pytest.mark.parametrize(("n1", "n2"), [(1, 0), (0, 1), (1, 1), (-2, -1), (3, 2), (40, 0)])
def test_cycle_slip_detected(n1, n2):
    """Slips of one or a few cycles, including the (1, 1) one (0.054 m in L1-L2)."""
    l1, l2 = smooth_phases(300)
    l1[170:] += n1 * LAM1
    l2[170:] += n2 * LAM2
    arcs = find_arcs(make_obs(l1, l2), min_length_s=600)
    assert [a.n for a in arcs] == [170, 130]
    assert arcs[1].start_reason == "cycle slip"


def test_no_false_slip_on_smooth_ionosphere():
    l1, l2 = smooth_phases(2000, seed=3)
    assert len(find_arcs(make_obs(l1, l2), min_length_s=600)) == 1


def test_minimum_length_and_require():
    l1, l2 = smooth_phases(50)  # 24.5 min at 30 s
    arcs = find_arcs(make_obs(l1, l2))
    assert len(arcs) == 0 and arcs.dropped["shorter than minimum"] == 1
    with pytest.raises(NoDataError, match="no arc long enough: 1 tracking stretches"):
        require_arcs(arcs)
    assert len(find_arcs(make_obs(l1, l2), min_length_s=24 * 60)) == 1


def test_bad_signal_pair():
    l1, l2 = smooth_phases(50)
    obs = make_obs(l1, l2)
    with pytest.raises(InputError, match="signal 'L5Q' is not in the file"):
        find_arcs(obs, ("L1C", "L5Q"))
    with pytest.raises(InputError, match="expected a pair"):
        find_arcs(obs, ("L1C",))


@pytest.mark.realdata
def test_esbc_arcs_with_elevations():
    obs = read_obs(shared_file(ESBC_OBS), systems="GE")
    nav = read_orbit(shared_file(ESBC_NAV))
    arcs = find_arcs(obs, ("L1C", "L2W"), system="G", orbit=nav, elevation_mask_deg=5.0)
    assert len(arcs) > 40
    for a in arcs:
        assert a.duration_s >= 1800
        assert np.all(np.diff(a.t_gps_s) <= 45.0)
        assert np.all((a.elevation_deg >= 5.0) & (a.elevation_deg <= 90.0))
        assert np.all((a.azimuth_deg >= 0.0) & (a.azimuth_deg < 360.0))
        # no jump left in the geometry-free phase beyond the slip threshold
        d = np.diff(a.geometry_free_m)
        assert np.max(np.abs(d - np.median(d))) < 0.5
    gal = find_arcs(obs, system="E", orbit=nav, elevation_mask_deg=5.0)
    assert gal.signals == ("L1C", "L5Q") and len(gal) > 20


@pytest.mark.realdata
def test_nya1_loss_of_lock_breaks_arcs():
    obs = read_obs(shared_file(NYA1_OBS), systems="G")
    nav = read_orbit(shared_file(NYA1_NAV))
    arcs = find_arcs(obs, ("L1C", "L2W"), orbit=nav, elevation_mask_deg=10.0)
    assert arcs.breaks["loss of lock"] > 0 and len(arcs) > 20


@pytest.mark.realdata
def test_gras_fifteen_minutes_has_no_long_arc():
    obs = read_obs(shared_file(GRAS_OBS), systems="G")
    arcs = find_arcs(obs)
    assert len(arcs) == 0 and arcs.dropped["shorter than minimum"] >= 8
    with pytest.raises(NoDataError, match="no arc long enough"):
        require_arcs(arcs)


@pytest.mark.parametrize("k", [1, 2, 298, 299])
def test_slip_at_arc_edges_detected(k):
    l1, l2 = smooth_phases(300)
    l1[k:] += 10 * LAM1
    arcs = find_arcs(make_obs(l1, l2), min_length_s=0.0)
    # a one-epoch stretch is no arc
    assert sorted(a.n for a in arcs) == sorted(n for n in (k, 300 - k) if n >= 2)
