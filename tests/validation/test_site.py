"""The reflection around the antenna, measured from the file's SNR (issue 28, part 2)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from psdbound.io import read_obs, read_orbit
from psdbound.simulate import Reflection, preset, simulate
from psdbound.validation.site import site_reflection, snr_signal


def _day(tmp_path, reflections):
    base = preset("short").replace(
        name="site", duration_s=86400.0, interval_s=30.0, systems="G", dual_antenna=False
    )
    sc = base.replace(multipath=replace(base.multipath, reflections=tuple(reflections)))
    res = simulate(sc, tmp_path)
    obs = read_obs(res.obs_paths[0])
    return obs, read_orbit(res.nav_path), np.asarray(obs.header.approx_position_m)


def test_measured_from_a_simulated_ground_reflection(tmp_path):
    obs, orbit, pos = _day(tmp_path, [Reflection("ground", 2.0, 0.2)])
    site = site_reflection(
        obs, orbit, phase_signal="L1C", system="G", receiver_xyz_m=pos, alpha=0.1
    )
    assert site.measured and site.n_accepted >= 5
    # the 10th percentile of the heights and the 90th of alpha: close to the one reflector
    assert site.ground_height_m == pytest.approx(2.0, abs=0.05)
    assert site.alpha == pytest.approx(0.2, rel=0.15)
    assert "SNR arcs" in site.note


def test_without_a_reflection_the_configured_alpha_is_assumed(tmp_path):
    obs, orbit, pos = _day(tmp_path, [])
    site = site_reflection(
        obs, orbit, phase_signal="L1C", system="G", receiver_xyz_m=pos, alpha=0.1
    )
    assert not site.measured and site.alpha == 0.1 and site.ground_height_m is None
    assert "assumed" in site.note and "0 of" in site.note


def test_no_snr_and_no_orbit_are_said(tmp_path):
    obs, orbit, pos = _day(tmp_path, [])
    site = site_reflection(
        obs, orbit, phase_signal="L7X", system="G", receiver_xyz_m=pos, alpha=0.1
    )
    assert not site.measured and "no SNR analysis" in site.note
    site = site_reflection(obs, None, phase_signal="L1C", system="G", receiver_xyz_m=pos, alpha=0.1)
    assert not site.measured and "no orbit" in site.note
    assert snr_signal("L1C") == "S1C" and snr_signal("L2") == "S2"
