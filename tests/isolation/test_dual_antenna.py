"""Dual-antenna double differences: synthetic truth, UPC1/UPC2 real data, bad input."""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np
import pytest
from conftest import UPC1_OBS, UPC2_OBS, UPC_NAV, shared_file

import psdbound.isolation.dual_antenna as da_mod
from psdbound.constants import OMEGA_E_RAD_S, SPEED_OF_LIGHT_M_S
from psdbound.errors import InputError, NoDataError
from psdbound.io import ObsHeader, read_obs, read_orbit
from psdbound.io.geometry import (
    azimuth_elevation,
    enu_rotation,
    geodetic_to_ecef,
)
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import wavelength_m
from psdbound.isolation.dual_antenna import isolate_dual_antenna

C = SPEED_OF_LIGHT_M_S
LAM1 = wavelength_m("G01", "L1C")
LAM2 = wavelength_m("G01", "L2W")
T0 = 1.3e9  # GPS seconds, 2021-03-17
DURATION_S = 5400
CUT_S = 2700  # the first reference satellite stops being tracked here
GM = 3.986004418e14
R_ORBIT = 26_560e3
N_ORBIT = np.sqrt(GM / R_ORBIT**3)

# (RAAN deg, argument of latitude at T0 deg): all above 15 deg over 1.5 h at Barcelona
ELEMENTS = {
    "G02": (210, 140),  # highest at T0: first reference, cut at CUT_S
    "G05": (0, 40),
    "G09": (180, 100),
    "G13": (270, 100),
    "G17": (30, 0),
    "G21": (300, 20),
}
SAT_CLOCK_S = {"G02": 1.2e-4, "G05": -3.0e-4, "G09": 5e-5, "G13": 0.0, "G17": -7e-5, "G21": 2e-4}


class CircularOrbits:
    """Circular 55-degree orbits; satisfies the OrbitSource protocol."""

    def inertial_m(self, sat, t):
        raan, u0 = np.radians(ELEMENTS[sat])
        u = u0 + N_ORBIT * (np.atleast_1d(np.asarray(t, float)) - T0)
        inc = np.radians(55.0)
        x = R_ORBIT * np.cos(u)
        y = R_ORBIT * np.sin(u) * np.cos(inc)
        z = R_ORBIT * np.sin(u) * np.sin(inc)
        return np.stack(
            [np.cos(raan) * x - np.sin(raan) * y, np.sin(raan) * x + np.cos(raan) * y, z], -1
        )

    def positions_ecef_m(self, sat, t_gps_s):
        t = np.atleast_1d(np.asarray(t_gps_s, float))
        return _inertial_to_ecef(self.inertial_m(sat, t), t)

    def satellite_clock_s(self, sat, t_gps_s):
        return np.full(np.atleast_1d(np.asarray(t_gps_s)).shape, SAT_CLOCK_S[sat])


def _inertial_to_ecef(p, t):
    th = OMEGA_E_RAD_S * (t - T0)
    c, s = np.cos(th), np.sin(th)
    return np.stack([c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1], p[:, 2]], -1)


def true_range_m(orbit, sat, t_rx, rx_ecef):
    """Light-time range solved independently in the inertial frame (10 iterations)."""
    th = OMEGA_E_RAD_S * (t_rx - T0)
    c, s = np.cos(th), np.sin(th)
    rx_i = np.stack([c * rx_ecef[0] - s * rx_ecef[1], s * rx_ecef[0] + c * rx_ecef[1]], -1)
    rx_i = np.column_stack([rx_i, np.full(t_rx.size, rx_ecef[2])])
    tau = np.zeros_like(t_rx)
    for _ in range(10):
        tau = np.linalg.norm(orbit.inertial_m(sat, t_rx - tau) - rx_i, axis=1) / C
    return tau * C


def gauss_markov(rng, n, sigma, tau_s, dt=1.0):
    phi = np.exp(-dt / tau_s)
    w = rng.normal(0.0, sigma * np.sqrt(1 - phi**2), n)
    x = np.empty(n)
    x[0] = rng.normal(0.0, sigma)
    for k in range(1, n):
        x[k] = phi * x[k - 1] + w[k]
    return x


RX1 = geodetic_to_ecef(41.389, 2.112, 60.0)
RX2 = RX1 + enu_rotation(41.389, 2.112).T @ np.array([30.0, 22.0, 8.0])  # 38 m


def clock1(t):
    return 0.8e-3 + 2e-8 * (t - T0)


def clock2(t):
    # free-running clock with a 1 ms jump (code and phase jump together)
    return -1.3e-3 - 3e-8 * (t - T0) + 1e-3 * (t - T0 >= 2400)


def _header(pos, name):
    return ObsHeader(
        version=3.04,
        file_system="G",
        marker_name=name,
        receiver_type="",
        antenna_type="",
        approx_position_m=np.asarray(pos, float),
        antenna_delta_hen_m=np.zeros(3),
        interval_s=1.0,
        time_system="GPS",
        obs_types={"G": ("C1C", "L1C", "L2W")},
    )


def _obs(path, name, pos, t, values):
    lli = np.where(np.isfinite(values), 0, -1).astype(np.int8)
    block = SystemBlock("G", tuple(ELEMENTS), ("C1C", "L1C", "L2W"), values, lli, lli.copy())
    return Observations(path, _header(pos, name), t, np.zeros(t.size, np.int8), {"G": block})


def make_scenario(seed=7, undetected_slip=False, tag_offset2=None):
    """Two receivers, six satellites, 1 Hz for 1.5 h; returns obs1, obs2, orbit, truth.

    ``tag_offset2(t)``: receiver 2 tags its epochs this far (s) from the nominal second
    (a clock left to drift), its measurements taken at those tags.
    """
    rng = np.random.default_rng(seed)
    orbit = CircularOrbits()
    t = T0 + np.arange(DURATION_S, dtype=float)
    tags = [t, t + (tag_offset2(t) if tag_offset2 else 0.0)]
    sats = tuple(ELEMENTS)
    vals = [np.full((t.size, len(sats), 3), np.nan) for _ in range(2)]
    mp1 = {}  # L1 multipath per receiver and satellite, metres
    for r, (pos, clk) in enumerate(((RX1, clock1), (RX2, clock2))):
        dt = clk(tags[r])
        for k, s in enumerate(sats):
            rho = true_range_m(orbit, s, tags[r] - dt, pos)
            common = rho + C * (dt - SAT_CLOCK_S[s])
            m1 = gauss_markov(rng, t.size, 0.004, 30.0)
            m2 = gauss_markov(rng, t.size, 0.004, 30.0)
            n1, n2 = rng.integers(-(10**6), 10**6, 2)
            l1 = common + n1 * LAM1 + m1 + rng.normal(0, 3e-4, t.size)
            l2 = common + n2 * LAM2 + m2 + rng.normal(0, 3e-4, t.size)
            if undetected_slip and r == 1 and s == "G09":
                # a 9/7-cycle slip moves L1-L2 by 3 mm only: find_arcs cannot see it
                l1[4000:] += 9 * LAM1
                l2[4000:] += 7 * LAM2
            vals[r][:, k, 0] = common + rng.normal(0, 0.5, t.size)
            vals[r][:, k, 1] = l1 / LAM1
            vals[r][:, k, 2] = l2 / LAM2
            mp1[r, s] = m1
    for v in vals:
        v[CUT_S:, sats.index("G02"), :] = np.nan  # reference satellite lost
    obs1 = _obs("mem/RX1", "RX1", RX1, t, vals[0])
    obs2 = _obs("mem/RX2", "RX2", RX2, tags[1].copy(), vals[1])
    return obs1, obs2, orbit, mp1


@pytest.fixture(scope="module")
def scenario():
    return make_scenario()


def truth_of(arc, mp1):
    """True double-difference multipath / 2 over the arc's epochs, mean removed."""
    i, r = arc.sats.split("-")
    k = np.round(arc.t_gps_s - T0).astype(int)
    dd = 0.5 * ((mp1[0, i][k] - mp1[1, i][k]) - (mp1[0, r][k] - mp1[1, r][k]))
    return dd - dd.mean()


def arc_errors(series, mp1):
    out = []
    for a in series.arcs():
        truth = truth_of(a, mp1)
        err = a.value_m - truth
        rms_t = np.sqrt(np.mean(truth**2))
        out.append((a.sats, np.corrcoef(a.value_m, truth)[0, 1], np.sqrt(np.mean(err**2)) / rms_t))
    return out


def test_synthetic_recovers_dd_multipath(scenario):
    obs1, obs2, orbit, mp1 = scenario
    da = isolate_dual_antenna(obs1, obs2, orbit)
    assert da.method == "DA" and da.scaling == 0.5 and da.signals == ("L1C",)
    assert da.interval_s == 1.0 and da.cutoff_hz is None
    errs = arc_errors(da, mp1)
    for sats, corr, rel in errs:
        print(f"{sats}: correlation {corr:.4f}, RMS error {100 * rel:.1f} % of truth RMS")
        assert corr >= 0.9 and rel <= 0.2, sats
    # every satellite pair in both reference periods: 5 + 4 arcs
    assert da.n_arcs == 9
    for a in da.arcs():
        assert abs(a.value_m.mean()) < 1e-9  # ambiguity removed
        assert a.duration_s >= 600
    assert da.meta["baseline_m"] == pytest.approx(np.linalg.norm(RX1 - RX2))
    assert da.meta["markers"] == ("RX1", "RX2")
    clk = da.meta["receiver_clock"]
    assert clk["codes"] == ("C1C", "C1C") and clk["satellite_clock"]
    assert clk["median_offset_s"][0] == pytest.approx(np.median(clock1(obs1.t_gps_s)), abs=1e-6)


def test_elevation_is_lower_of_pair(scenario):
    obs1, obs2, orbit, _ = scenario
    da = isolate_dual_antenna(obs1, obs2, orbit)
    a = da.arc(0)
    i, r = a.sats.split("-")
    el_i = azimuth_elevation(RX1, orbit.positions_ecef_m(i, a.t_gps_s))[1]
    el_r = azimuth_elevation(RX1, orbit.positions_ecef_m(r, a.t_gps_s))[1]
    np.testing.assert_allclose(a.elevation_deg, np.minimum(el_i, el_r), atol=0.01)


def test_re_reference_when_reference_arc_ends(scenario):
    obs1, obs2, orbit, _ = scenario
    da = isolate_dual_antenna(obs1, obs2, orbit)
    periods = da.meta["reference_periods"]
    assert len(periods) == 2
    assert periods[0] == {"sat": "G02", "start_gps_s": T0, "stop_gps_s": T0 + CUT_S - 1}
    # the new reference is the highest satellite at the first epoch without G02
    t_cut = np.array([T0 + CUT_S])
    el = {s: azimuth_elevation(RX1, orbit.positions_ecef_m(s, t_cut))[1][0] for s in ELEMENTS}
    el.pop("G02")
    assert periods[1]["sat"] == max(el, key=el.get)
    assert periods[1]["start_gps_s"] == T0 + CUT_S
    assert periods[1]["stop_gps_s"] == T0 + DURATION_S - 1
    refs = {a.sats.split("-")[1] for a in da.arcs() if a.t_gps_s[0] < T0 + CUT_S}
    assert refs == {"G02"}
    assert not any("G02" in a.sats for a in da.arcs() if a.t_gps_s[-1] >= T0 + CUT_S)


def test_receiver_clock_estimate_is_needed(scenario, monkeypatch):
    """Ms-level receiver clocks: small error with the estimate, large without."""
    obs1, obs2, orbit, mp1 = scenario
    with_clock = max(rel for _, _, rel in arc_errors(isolate_dual_antenna(obs1, obs2, orbit), mp1))

    def no_clock(obs, orbit, sats, code, rho, tau):
        return np.zeros(obs.t_gps_s.size), "none", 0

    monkeypatch.setattr(da_mod, "estimate_receiver_clock", no_clock)
    without = isolate_dual_antenna(obs1, obs2, orbit)
    worst = max(rel for _, _, rel in arc_errors(without, mp1))
    print(f"worst RMS error / truth RMS: {with_clock:.3f} with clock estimate, {worst:.1f} without")
    assert with_clock <= 0.2
    assert worst > 5.0


def test_undetected_slip_splits_dd_arc():
    obs1, obs2, orbit, mp1 = make_scenario(seed=11, undetected_slip=True)
    da = isolate_dual_antenna(obs1, obs2, orbit)
    assert da.meta["n_dd_jump_splits"] >= 1
    g09 = [a for a in da.arcs() if a.sats.startswith("G09-")]
    assert any(a.t_gps_s[-1] == T0 + 3999 for a in g09)
    assert any(a.t_gps_s[0] == T0 + 4000 for a in g09)
    for _, corr, rel in arc_errors(da, mp1):
        assert corr >= 0.9 and rel <= 0.2


def test_without_slip_signal(scenario):
    obs1, obs2, orbit, mp1 = scenario
    da = isolate_dual_antenna(obs1, obs2, orbit, slip_signal=None)
    assert da.n_arcs == 9
    assert "no second signal" in da.meta["slip_detection"]
    assert all(corr >= 0.9 and rel <= 0.2 for _, corr, rel in arc_errors(da, mp1))


def test_short_arcs_dropped_and_counted(scenario):
    obs1, obs2, orbit, _ = scenario
    da = isolate_dual_antenna(obs1, obs2, orbit, min_length_s=2800.0)
    # G02 is tracked for 2700 s only: no SD arc, one reference period
    assert all("G02" not in s for s in da.arc_sats)
    assert len(da.meta["reference_periods"]) == 1
    with pytest.raises(NoDataError, match="no single-difference arc of at least 6000 s"):
        isolate_dual_antenna(obs1, obs2, orbit, min_length_s=6000.0)


# --------------------------------------------------------------------------- bad input


def test_same_file_twice(scenario):
    obs1, _, orbit, _ = scenario
    with pytest.raises(
        InputError, match=r"same observation file given twice \(mem/RX1 and mem/RX1"
    ):
        isolate_dual_antenna(obs1, obs1, orbit)


def test_identical_positions(scenario):
    obs1, obs2, orbit, _ = scenario
    with pytest.raises(InputError, match="identical antenna positions for mem/RX1 and mem/RX2"):
        isolate_dual_antenna(obs1, obs2, orbit, receiver2_xyz_m=RX1)


def test_files_from_different_days(scenario):
    obs1, obs2, orbit, _ = scenario
    next_day = replace(obs2, t_gps_s=obs2.t_gps_s + 86400.0)
    with pytest.raises(
        InputError,
        match=r"no common epochs \(files from different days\): mem/RX1 spans 2021-03-17 "
        r".* GPST, mem/RX2 spans 2021-03-18 .* GPST",
    ):
        isolate_dual_antenna(obs1, next_day, orbit)


def test_epochs_matched_within_the_tolerance(scenario):
    obs1, obs2, orbit, mp1 = scenario
    shifted = replace(obs2, t_gps_s=obs2.t_gps_s + 4e-4)
    da = isolate_dual_antenna(obs1, shifted, orbit)
    assert da.meta["n_common_epochs"] == DURATION_S
    off = replace(obs2, t_gps_s=obs2.t_gps_s + 0.5)
    with pytest.raises(InputError, match="no common epochs: mem/RX1 spans"):
        isolate_dual_antenna(obs1, off, orbit)


def test_epochs_of_a_drifting_receiver_clock_are_matched():
    """Epochs tagged up to 12 ms from the nominal second (RTKLIB's GSI pair of 2005: +5 and
    -4 ms within an hour) are the same measurement epochs: matched, the geometry taken at
    each receiver's own time, and the double-difference multipath recovered as well."""
    obs1, obs2, orbit, mp1 = make_scenario(tag_offset2=lambda t: 3e-3 + 1.7e-6 * (t - T0))
    assert np.ptp(obs2.t_gps_s - obs1.t_gps_s) > 8e-3
    da = isolate_dual_antenna(obs1, obs2, orbit)
    assert da.meta["n_common_epochs"] == DURATION_S
    for sats, corr, rel in arc_errors(da, mp1):
        assert corr >= 0.9 and rel <= 0.2, sats


def test_not_a_short_baseline(scenario):
    obs1, obs2, orbit, _ = scenario
    far = RX1 + np.array([30e3, 0.0, 0.0])
    with pytest.raises(
        InputError, match=r"not a short baseline: mem/RX1 and mem/RX2 are 30\.000 km"
    ):
        isolate_dual_antenna(obs1, obs2, orbit, receiver2_xyz_m=far)


def test_no_common_satellites(scenario):
    obs1, obs2, orbit, _ = scenario
    b = obs2.blocks["G"]
    other = replace(b, sats=tuple(f"G{30 + k}" for k in range(len(b.sats))))
    obs_other = replace(obs2, blocks={"G": other})
    with pytest.raises(
        InputError, match=r"no common satellites .* mem/RX1 has G02 .*, mem/RX2 has G30"
    ):
        isolate_dual_antenna(obs1, obs_other, orbit)


def test_missing_signal(scenario):
    obs1, obs2, orbit, _ = scenario
    with pytest.raises(
        InputError,
        match=r"signal 'L5X' missing from mem/RX1 and mem/RX2 \(system G\); "
        r"mem/RX1 has C1C L1C L2W; mem/RX2 has C1C L1C L2W",
    ):
        isolate_dual_antenna(obs1, obs2, orbit, signal="L5X")
    b = obs2.blocks["G"]
    l1_only = replace(
        b, codes=("C1C", "L1C"), values=b.values[:, :, :2], lli=b.lli[:, :, :2], ssi=b.ssi[:, :, :2]
    )
    obs_l1 = replace(obs2, blocks={"G": l1_only})
    with pytest.raises(InputError, match=r"slip_signal 'L2W' missing from mem/RX2 \(system G\)"):
        isolate_dual_antenna(obs1, obs_l1, orbit)
    # without a slip signal the L1-only file is usable
    assert isolate_dual_antenna(obs1, obs_l1, orbit, slip_signal=None).n_arcs == 9


def test_missing_system(scenario):
    obs1, obs2, orbit, _ = scenario
    with pytest.raises(InputError, match=r"no E observations in mem/RX1 .* mem/RX1 and mem/RX2"):
        isolate_dual_antenna(obs1, obs2, orbit, system="E")


# --------------------------------------------------------------------------- real data


@pytest.mark.realdata
def test_upc_double_differences():
    obs1 = read_obs(shared_file(UPC1_OBS))
    obs2 = read_obs(shared_file(UPC2_OBS))
    nav = read_orbit(shared_file(UPC_NAV))
    t0 = time.perf_counter()
    da = isolate_dual_antenna(obs1, obs2, nav)
    elapsed = time.perf_counter() - t0
    print(f"\nUPC1-UPC2 ({da.meta['baseline_m']:.2f} m): {da.n_arcs} DD arcs in {elapsed:.2f} s")
    assert da.method == "DA" and da.scaling == 0.5
    assert da.meta["markers"] == ("UPC1", "UPC2")
    assert 37.0 < da.meta["baseline_m"] < 39.0
    # receiver 2 has a 5 ms clock jump in this hour
    assert max(da.meta["receiver_clock"]["max_abs_offset_s"]) > 1e-3
    assert da.meta["n_dd_jump_splits"] == 0
    n_checked = 0
    for a in da.arcs():
        low = a.elevation_deg.min()
        print(
            f"  {a.sats}: {a.duration_s:5.0f} s, elevation {low:4.1f}-"
            f"{a.elevation_deg.max():4.1f} deg, RMS {1e3 * a.rms_m:.2f} mm"
        )
        if low > 15.0:
            assert a.rms_m <= 0.02, a.sats
            n_checked += 1
    assert n_checked >= 5
    assert elapsed < 2.0


def test_a_long_baseline_is_said_to_hold_atmosphere():
    from psdbound.isolation import long_baseline_note

    assert long_baseline_note(38.0) == "" and long_baseline_note(None) == ""
    note = long_baseline_note(3335.4)
    assert "3.3 km apart" in note and "differential ionosphere" in note
