"""A third carrier read beside the pair: choice, breaks, and the isolated series."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import shared_file

from psdbound.arcs import add_third_carrier, find_arcs
from psdbound.arcs.third import choose_third_signal, third_candidates
from psdbound.io import ObsHeader, read_obs, read_orbit
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import wavelength_m
from psdbound.isolation import isolate_dual_frequency

CODES = ("L1C", "L2W", "L5Q")
LAM = [wavelength_m("G01", c) for c in CODES]
ZIMM_OBS, ZIMM_NAV = "zimm0010.21o.gz", "cbw10010.21n.gz"


def _obs(n=400, seed=0, lli5=None, l5=None):
    """G07 tracked on L1C, L2W and L5Q (metres -> cycles), 30 s."""
    rng = np.random.default_rng(seed)
    k = np.arange(n)
    rho = 2.2e7 + 500.0 * k
    iono = 2.0 + 0.5 * np.sin(2 * np.pi * k / 800.0)
    f = np.array([1575.42, 1227.60, 1176.45])
    ph = rho[:, None] - iono[:, None] * (f[0] / f) ** 2 + rng.normal(0, 0.002, (n, 3))
    if l5 is not None:
        ph[:, 2] = l5(ph[:, 2])
    v = (ph / np.array(LAM))[:, None, :]
    lli = np.where(np.isfinite(v), 0, -1).astype(np.int8)
    if lli5 is not None:
        lli[:, 0, 2] = lli5
    header = ObsHeader(
        version=3.04,
        file_system="G",
        marker_name="T",
        receiver_type="X",
        antenna_type="X",
        approx_position_m=None,
        antenna_delta_hen_m=np.zeros(3),
        interval_s=30.0,
        time_system="GPS",
        obs_types={"G": CODES},
    )
    block = SystemBlock("G", ("G07",), CODES, v, lli, np.full(v.shape, -1, np.int8))
    t = 1.277e9 + 30.0 * k
    return Observations("synthetic", header, t, np.zeros(n, np.int8), {"G": block})


def test_candidates_skip_the_pair_bands():
    assert third_candidates("G", ("L1C", "L2W"))[:3] == ("L5Q", "L5X", "L5I")
    assert third_candidates("G", ("L1C", "L5Q"))[0] == "L2W"
    assert third_candidates("E", ("L1C", "L5Q"))[0] == "L7Q"
    assert third_candidates("S", ("L1C", "L5I")) == ()


def test_third_phase_carried_and_breaks_marked():
    lli5 = np.zeros(400, np.int8)
    lli5[100] = 1
    obs = _obs(lli5=lli5, l5=lambda x: np.where(np.arange(x.size) >= 250, x + LAM[2], x))
    arcs = find_arcs(obs, ("L1C", "L2W"), min_length_s=600)
    assert len(arcs) == 1  # the third carrier's loss of lock and slip do not break the arc
    out = add_third_carrier(arcs, obs)
    assert out.third_signal == "L5Q" and choose_third_signal(obs, "G", ("L1C", "L2W")) == "L5Q"
    l5 = out[0].third_m
    assert np.flatnonzero(np.isnan(l5)).tolist() == [100, 250]
    gf = out[0].phase_m[:, 0] - l5
    jumps = np.abs(np.diff(gf))
    assert np.nanmax(jumps) < 0.05  # no difference spans the one-cycle (25 cm) slip


def test_no_third_signal_leaves_arcs_unchanged():
    obs = _obs()
    arcs = find_arcs(obs, ("L1C", "L5Q"), min_length_s=600)
    out = add_third_carrier(arcs, obs)  # L2W is there: taken as the third
    assert out.third_signal == "L2W"
    arcs2 = find_arcs(obs, ("L1C", "L2W"), min_length_s=600)
    assert add_third_carrier(arcs2, obs, "L2W") is not arcs2
    series = isolate_dual_frequency(arcs2, 2e-3)
    assert series.third_m is None and series.third_signal is None


def test_isolated_series_keeps_the_third_geometry_free_phase():
    obs = _obs()
    arcs = add_third_carrier(find_arcs(obs, ("L1C", "L2W"), min_length_s=600), obs)
    series = isolate_dual_frequency(arcs, 2e-3)
    assert series.third_signal == "L5Q" and series.meta["arcs_with_third"] == 1
    assert series.third_m.shape == series.unfiltered_m.shape
    assert abs(np.nanmean(series.arc(0).third_m)) < 0.5
    np.testing.assert_array_equal(
        series.value_m,
        isolate_dual_frequency(find_arcs(obs, ("L1C", "L2W"), min_length_s=600), 2e-3).value_m,
    )


@pytest.mark.realdata
@pytest.mark.filterwarnings("ignore:.*navigation file gives positions")
def test_zimm_rinex2_l5_is_the_third_carrier():
    path, nav = shared_file(ZIMM_OBS), shared_file(ZIMM_NAV)
    obs = read_obs(
        path,
        systems="G",
        codes=("L1C", "L2W"),
        optional_codes=third_candidates("G", ("L1C", "L2W")),
    )
    arcs = add_third_carrier(
        find_arcs(obs, ("L1C", "L2W"), orbit=read_orbit(nav), elevation_mask_deg=10.0), obs
    )
    with_l5 = [a for a in arcs if np.isfinite(a.third_m).any()]
    assert arcs.third_signal == "L5"
    assert 15 <= len(with_l5) < len(arcs)  # the Block IIF/III satellites only
