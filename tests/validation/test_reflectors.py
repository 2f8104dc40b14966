"""Ground-reflector heights and amplitude ratios from SNR (validation.reflectors, .snr_arc)."""

from __future__ import annotations

import json
import math
from dataclasses import replace

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, shared_file

from psdbound.errors import InputError
from psdbound.io import ObsHeader, read_obs, read_orbit
from psdbound.io.geometry import enu_rotation, satellite_azel
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import wavelength_m
from psdbound.validation.reflectors import ReflectorHeights, reflector_heights
from psdbound.validation.snr_arc import (
    DEFAULT_ELEVATION_RANGE_DEG,
    ArcHeight,
    amplitude_ratio,
    arc_height,
)

L1_M = wavelength_m("G01", "S1C")
L2_M = wavelength_m("G01", "S2W")
ESBC_XYZ_M = np.array([3582105.2910, 532589.7313, 5232754.8054])
ZIMM_OBS = "zimm0020.21o.gz"
ZIMM_NAV = "brdc0020.21n.gz"

# a satellite pass: sin(e) = sin(70 deg) sin(w t), 5 -> 25 deg in ~50 min (GPS-like rates)
PASS_RATE_RAD_S = 1.19e-4
PASS_MAX_EL_DEG = 70.0


# --------------------------------------------------------------------------- synthetic SNR


def pass_elevation_deg(t_s: np.ndarray) -> np.ndarray:
    """Elevation of a whole pass (rising then setting) at times since rise, degrees."""
    s = np.sin(np.radians(PASS_MAX_EL_DEG)) * np.sin(PASS_RATE_RAD_S * t_s)
    return np.degrees(np.arcsin(np.clip(s, -1.0, 1.0)))


def rising_track_deg(dt_s: float) -> np.ndarray:
    """Elevations of the rising part of a pass between 4 and 26 deg, sampled every dt_s."""
    e = pass_elevation_deg(np.arange(0.0, 2.2 * 3600.0, dt_s))
    return e[(e >= 4.0) & (e <= 26.0)]


def snr_dbhz(e_deg, h_m, alpha, lam_m, rng, *, noise_db=0.3, phase_rad=0.7):
    """SNR of a direct signal with an antenna-gain trend plus one specular ground reflection.

    Linear SNR ``A_d^2 |1 + alpha exp(i psi)|^2``, ``psi = 4 pi h sin(e) / lambda + phase``;
    the direct SNR rises from ~36 dB-Hz at the horizon to ~48 dB-Hz at 25 deg.
    """
    e = np.asarray(e_deg, dtype=float)
    direct_db = 36.0 + 14.0 * (1.0 - np.exp(-(e - 2.0) / 10.0))
    psi = 4.0 * np.pi * h_m * np.sin(np.radians(e)) / lam_m + phase_rad
    interference = 1.0 + alpha**2 + 2.0 * alpha * np.cos(psi)
    return direct_db + 10.0 * np.log10(interference) + rng.normal(0.0, noise_db, e.size)


@pytest.mark.parametrize("dt_s", [30.0, 1.0])
@pytest.mark.parametrize("h_m", [1.0, 2.5, 5.0])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_recovers_height_and_alpha(dt_s, h_m, seed):
    rng = np.random.default_rng(seed)
    alpha = (0.1, 0.2, 0.3)[seed]
    e = rising_track_deg(dt_s)
    if seed == 1:
        e = e[::-1]  # a setting arc
    snr = snr_dbhz(e, h_m, alpha, L1_M, rng, phase_rad=rng.uniform(0.0, 2.0 * np.pi))
    r = arc_height(e, snr, wavelength_m=L1_M)
    assert isinstance(r, ArcHeight)
    assert r.accepted, r.reason
    assert r.reason == ""
    assert abs(r.height_m - h_m) < 0.02, (r.height_m, h_m)
    assert abs(r.alpha / alpha - 1.0) < 0.25, (r.alpha, alpha)
    assert r.n_points == np.count_nonzero((e >= 5.0) & (e <= 25.0))
    assert r.peak_to_noise > 3.0 and r.peak_amplitude > 6.0


@pytest.mark.parametrize("h_m", [1.5, 4.0])
def test_recovers_height_on_l2(h_m):
    rng = np.random.default_rng(7)
    e = rising_track_deg(30.0)
    r = arc_height(e, snr_dbhz(e, h_m, 0.15, L2_M, rng), wavelength_m=L2_M)
    assert r.accepted, r.reason
    assert abs(r.height_m - h_m) < 0.02


@pytest.mark.parametrize("dt_s", [30.0, 1.0])
def test_pure_noise_arcs_are_rejected_with_a_reason(dt_s):
    e = rising_track_deg(dt_s)
    results = [
        arc_height(
            e, snr_dbhz(e, 1.0, 0.0, L1_M, np.random.default_rng(100 + k)), wavelength_m=L1_M
        )
        for k in range(40)
    ]
    for r in results:
        assert not r.accepted
        assert "peak amplitude" in r.reason or "peak-to-noise" in r.reason, r.reason
        assert DEFAULT_ELEVATION_RANGE_DEG[0] <= r.elevation_min_deg  # still analysed
        assert math.isfinite(r.height_m)


def test_joint_refinement_removes_the_low_height_bias():
    e = rising_track_deg(30.0)
    plain, joint = [], []
    for phase in np.linspace(0.0, 2.0 * np.pi, 12, endpoint=False):
        snr = snr_dbhz(e, 1.0, 0.2, L1_M, np.random.default_rng(0), noise_db=0.0, phase_rad=phase)
        plain.append(arc_height(e, snr, wavelength_m=L1_M, joint_refinement=False).height_m - 1.0)
        joint.append(arc_height(e, snr, wavelength_m=L1_M).height_m - 1.0)
    assert np.max(np.abs(joint)) < 0.006
    assert np.max(np.abs(plain)) > 2.0 * np.max(np.abs(joint))


@pytest.mark.parametrize("alpha", [0.05, 0.3, 0.6])
def test_amplitude_ratio_is_exact_without_noise(alpha):
    e = np.linspace(5.0, 25.0, 400)
    snr = snr_dbhz(e, 3.0, alpha, L1_M, np.random.default_rng(0), noise_db=0.0)
    assert amplitude_ratio(e, snr, 2.0 * 3.0 / L1_M) == pytest.approx(alpha, rel=0.02)
    assert math.isnan(amplitude_ratio(e[:4], snr[:4], 1.0))


def test_outliers_are_left_out():
    rng = np.random.default_rng(3)
    e = rising_track_deg(30.0)
    snr = snr_dbhz(e, 2.5, 0.2, L1_M, rng)
    snr[[20, 60]] += 18.0  # tracking glitches
    r = arc_height(e, snr, wavelength_m=L1_M)
    assert r.n_outliers == 2
    assert r.accepted and abs(r.height_m - 2.5) < 0.02
    assert abs(r.alpha / 0.2 - 1.0) < 0.25


def test_short_and_partial_arcs_are_rejected_with_reasons():
    rng = np.random.default_rng(4)
    e = rising_track_deg(30.0)
    low = e[e <= 15.0]
    r = arc_height(low, snr_dbhz(low, 2.5, 0.2, L1_M, rng), wavelength_m=L1_M)
    assert not r.accepted and "elevation coverage" in r.reason
    r = arc_height(e[::6], snr_dbhz(e[::6], 2.5, 0.2, L1_M, rng), wavelength_m=L1_M)
    assert not r.accepted and "too few points" in r.reason
    r = arc_height(e[:3], snr_dbhz(e[:3], 2.5, 0.2, L1_M, rng), wavelength_m=L1_M)
    assert not r.accepted and math.isnan(r.height_m) and r.reason
    r = arc_height([], [], wavelength_m=L1_M)
    assert not r.accepted and r.n_points == 0 and r.reason


def test_peak_below_the_search_range_is_flagged_at_the_edge():
    e = rising_track_deg(30.0)
    snr = snr_dbhz(e, 0.15, 0.3, L1_M, np.random.default_rng(5), noise_db=0.05)
    r = arc_height(e, snr, wavelength_m=L1_M, poly_order=1)
    assert not r.accepted and "edge of the height search range" in r.reason


def test_coarse_sampling_limits_the_search():
    e = rising_track_deg(300.0)
    snr = snr_dbhz(e, 5.0, 0.2, L1_M, np.random.default_rng(6))
    r = arc_height(e, snr, wavelength_m=L1_M, height_range_m=(3.0, 8.0), min_points=5)
    assert not r.accepted and "sampling too coarse" in r.reason


def test_arc_height_rejects_bad_settings():
    e = rising_track_deg(30.0)
    snr = snr_dbhz(e, 2.0, 0.2, L1_M, np.random.default_rng(0))
    with pytest.raises(InputError, match="wavelength"):
        arc_height(e, snr, wavelength_m=0.0)
    with pytest.raises(InputError, match="height range"):
        arc_height(e, snr, wavelength_m=L1_M, height_range_m=(5.0, 1.0))
    with pytest.raises(InputError, match="elevation range"):
        arc_height(e, snr, wavelength_m=L1_M, elevation_range_deg=(30.0, 10.0))
    with pytest.raises(InputError, match="expected equal"):
        arc_height(e, snr[:-1], wavelength_m=L1_M)
    with pytest.raises(InputError, match="poly_order"):
        arc_height(e, snr, wavelength_m=L1_M, poly_order=12)


# --------------------------------------------------------------------------- whole files


class TrackOrbit:
    """An orbit whose satellites follow given azimuth/elevation tracks seen from one receiver."""

    def __init__(self, rx_xyz_m, t_gps_s, tracks):
        self.rx = np.asarray(rx_xyz_m, dtype=float)
        self.t = np.asarray(t_gps_s, dtype=float)
        self.tracks = tracks  # sat -> (azimuth_deg, elevation_deg) at self.t
        from psdbound.io.geometry import ecef_to_geodetic

        lat, lon, _ = ecef_to_geodetic(self.rx)
        self.rot = enu_rotation(lat, lon)

    def positions_ecef_m(self, sat, t_gps_s):
        t = np.atleast_1d(np.asarray(t_gps_s, dtype=float))
        if sat not in self.tracks:
            return np.full((t.size, 3), np.nan)
        az, el = (np.radians(np.interp(t, self.t, a)) for a in self.tracks[sat])
        enu = np.stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)], axis=-1)
        return self.rx + 2.2e7 * enu @ self.rot


def synthetic_station(*, h_m=2.0, alpha=0.2, codes=("S1C", "S2W"), approx=True, seed=0):
    """GPS observations (30 s, 14 h) of two passes seen over a reflector ``h_m`` below."""
    rng = np.random.default_rng(seed)
    t0 = 1.2771e9
    t_rel = np.arange(0.0, 14 * 3600.0, 30.0)
    sats = ("G01", "G02", "G03")
    starts = {"G01": 600.0, "G02": 5 * 3600.0, "G03": 0.0}
    tracks, values = {}, np.full((t_rel.size, len(sats), len(codes)), np.nan)
    for i, sat in enumerate(sats):
        el = pass_elevation_deg(t_rel - starts[sat])
        el = np.where(t_rel >= starts[sat], el, -10.0)
        el[t_rel - starts[sat] > np.pi / PASS_RATE_RAD_S] = -10.0
        az = (40.0 + 60.0 * i + 0.004 * t_rel) % 360.0
        tracks[sat] = (az, el)
        for k, code in enumerate(codes):
            if code.startswith("S"):
                lam = wavelength_m(sat, code)
                values[:, i, k] = np.where(el > 0, snr_dbhz(el, h_m, alpha, lam, rng), np.nan)
            else:
                values[:, i, k] = 2.2e7
    values[:, 2, :] = np.nan  # G03 has no observations at all
    gap = (t_rel > starts["G02"] + 1800.0) & (t_rel < starts["G02"] + 2400.0)
    values[gap, 1, :] = np.nan  # a 10-minute gap inside G02's rising arc
    header = ObsHeader(
        version=3.04,
        file_system="G",
        marker_name="SYN",
        receiver_type="SYNTH",
        antenna_type="NONE",
        approx_position_m=ESBC_XYZ_M if approx else None,
        antenna_delta_hen_m=np.zeros(3),
        interval_s=30.0,
        time_system="GPS",
        obs_types={"G": tuple(codes)},
    )
    lli = np.full(values.shape, -1, np.int8)
    block = SystemBlock("G", sats, tuple(codes), values, lli, lli.copy())
    obs = Observations("synthetic", header, t0 + t_rel, np.zeros(t_rel.size, np.int8), {"G": block})
    return obs, TrackOrbit(ESBC_XYZ_M, t0 + t_rel, tracks)


def test_track_orbit_reproduces_its_elevations():
    obs, orbit = synthetic_station()
    az, el = orbit.tracks["G01"]
    az2, el2 = satellite_azel(orbit, "G01", obs.t_gps_s, ESBC_XYZ_M)
    up = el > 0
    np.testing.assert_allclose(el2[up], el[up], atol=1e-3)


def test_reflector_heights_on_a_synthetic_station():
    obs, orbit = synthetic_station(h_m=2.0, alpha=0.2)
    r = reflector_heights(obs, orbit)
    assert isinstance(r, ReflectorHeights)
    # G01: one rising and one setting arc; G02: the gap splits its rising arc in two
    assert r.n_arcs == 5
    assert sorted(zip(r.sat.tolist(), r.rising.tolist(), strict=True)) == [
        ("G01", False),
        ("G01", True),
        ("G02", False),
        ("G02", True),
        ("G02", True),
    ]
    assert r.n_accepted == 3
    assert not np.any(r.accepted[(r.sat == "G02") & r.rising])
    assert all("elevation coverage" in s for s in r.reason[(r.sat == "G02") & r.rising])
    assert abs(r.median_height_m - 2.0) < 0.02
    assert r.height_spread_m < 0.02
    assert abs(r.median_alpha / 0.2 - 1.0) < 0.25
    assert r.no_result_reason == ""
    assert np.all(r.code == "S1C") and np.allclose(r.wavelength_m, L1_M)
    assert np.all(r.t_end_gps_s > r.t_start_gps_s)
    assert np.all((r.azimuth_deg >= 0.0) & (r.azimuth_deg < 360.0))
    assert np.all(r.elevation_min_deg >= 5.0) and np.all(r.elevation_max_deg <= 25.0)
    text = r.summary()
    assert "3 of 5 arcs accepted" in text and "median height 2.0" in text
    d = json.loads(json.dumps(r.to_dict()))
    assert d["n_accepted"] == 3 and len(d["arcs"]) == 5
    assert d["arcs"][0]["sat"] in ("G01", "G02")
    rising = r.select(r.rising)
    assert rising.n_arcs == 3 and rising.n_accepted == 1


def test_l2_and_rinex2_names():
    obs, orbit = synthetic_station(h_m=3.0, codes=("S1", "S2"))
    for signal in ("S2", "S2W"):
        r = reflector_heights(obs, orbit, signal=signal, systems="G")
        assert np.all(r.code == "S2")
        assert np.allclose(r.wavelength_m, L2_M)
        assert abs(r.median_height_m - 3.0) < 0.02
    obs3, orbit3 = synthetic_station(h_m=3.0)
    assert np.all(reflector_heights(obs3, orbit3, signal="S1").code == "S1C")


def test_no_accepted_arc_gives_nan_with_a_reason():
    obs, orbit = synthetic_station(alpha=0.0)
    r = reflector_heights(obs, orbit)
    assert r.n_arcs == 5 and r.n_accepted == 0
    assert math.isnan(r.median_height_m) and math.isnan(r.height_spread_m)
    assert math.isnan(r.median_alpha)
    assert r.no_result_reason.startswith("no arc passed quality control")
    assert "no height" in r.summary()
    d = json.loads(json.dumps(r.to_dict()))
    assert d["median_height_m"] is None and d["no_result_reason"]


def test_no_arc_at_all_and_skipped_satellites():
    obs, orbit = synthetic_station()
    orbit.tracks.pop("G01")
    r = reflector_heights(obs, orbit, elevation_range_deg=(80.0, 85.0))
    assert r.n_arcs == 0 and math.isnan(r.median_height_m)
    assert "no S1C arc" in r.no_result_reason
    assert any(s.startswith("G01") and "orbit" in s for s in r.skipped)
    assert json.dumps(r.to_dict())


def test_glonass_needs_its_frequency_channel():
    obs, orbit = synthetic_station()
    g = obs.blocks["G"]
    lam_r = wavelength_m("R01", "S1C", {"R01": 1})
    rng = np.random.default_rng(9)
    el = orbit.tracks["G01"][1]
    snr = np.where(el > 0, snr_dbhz(el, 2.0, 0.2, lam_r, rng), np.nan)[:, None, None]
    snr = np.repeat(snr, len(g.codes), axis=2)
    glo = SystemBlock("R", ("R01",), g.codes, snr, g.lli[:, :1], g.ssi[:, :1])
    orbit.tracks["R01"] = orbit.tracks["G01"]
    mixed = replace(obs, blocks={"G": g, "R": glo})
    r = reflector_heights(mixed, orbit, systems="R")
    assert r.n_arcs == 0 and len(r.skipped) == 1
    assert r.skipped[0].startswith("R01: no GLONASS frequency channel")
    header = replace(obs.header, glonass_channels={"R01": 1})
    r = reflector_heights(replace(mixed, header=header), orbit, systems="R")
    assert r.n_accepted == 2 and np.allclose(r.wavelength_m, lam_r)
    assert abs(r.median_height_m - 2.0) < 0.02


def test_bad_inputs_raise_input_error():
    obs, orbit = synthetic_station()
    with pytest.raises(InputError, match=r"'L1C' is not an SNR code.*S1C S2W"):
        reflector_heights(obs, orbit, signal="L1C")
    with pytest.raises(InputError, match=r"'S5X' is not in the file; SNR codes: G: S1C S2W"):
        reflector_heights(obs, orbit, signal="S5X")
    with pytest.raises(InputError, match=r"system 'E'"):
        reflector_heights(obs, orbit, systems="GE")
    no_snr, _ = synthetic_station(codes=("C1C",))
    with pytest.raises(InputError, match=r"'S1C': the file has no SNR observations"):
        reflector_heights(no_snr, orbit)
    no_pos, _ = synthetic_station(approx=False)
    with pytest.raises(InputError, match="APPROX POSITION"):
        reflector_heights(no_pos, orbit)
    r = reflector_heights(no_pos, orbit, receiver_xyz_m=ESBC_XYZ_M)
    assert r.n_accepted == 3
    with pytest.raises(InputError, match="mask"):
        r.select([True])


# --------------------------------------------------------------------------- real data


@pytest.fixture(scope="module")
def esbc():
    return read_obs(shared_file(ESBC_OBS), systems="GER"), read_orbit(shared_file(ESBC_NAV))


@pytest.fixture(scope="module")
def zimm():
    return read_obs(shared_file(ZIMM_OBS)), read_orbit(shared_file(ZIMM_NAV))


def check_physical(r: ReflectorHeights) -> None:
    """What any 24 h station file must give, whatever its surroundings."""
    assert r.n_arcs > 50
    assert r.n_accepted >= 1, r.summary()
    assert np.any(r.rising) and np.any(~r.rising)
    h1, h2 = r.height_range_m
    acc = r.select(r.accepted)
    assert np.all((acc.height_m >= h1) & (acc.height_m <= h2))
    assert np.all((acc.alpha > 0.0) & (acc.alpha <= 1.0))
    assert np.all(acc.reason == "") and np.all(r.reason[~r.accepted] != "")
    assert np.all(r.elevation_min_deg >= r.elevation_range_deg[0])
    assert np.all(r.elevation_max_deg <= r.elevation_range_deg[1])
    assert h1 <= r.median_height_m <= h2 and 0.0 <= r.height_spread_m < h2 - h1
    for sat in np.unique(r.sat):  # arcs of one satellite do not overlap
        one = r.select(r.sat == sat)
        order = np.argsort(one.t_start_gps_s)
        assert np.all(one.t_start_gps_s[order][1:] > one.t_end_gps_s[order][:-1])
    json.dumps(r.to_dict())


def paired_differences_m(a: ReflectorHeights, b: ReflectorHeights) -> np.ndarray:
    """Height differences of arcs accepted on both signals (same satellite, direction, time)."""
    out = []
    for i in np.flatnonzero(a.accepted):
        for j in np.flatnonzero(b.accepted):
            same = a.sat[i] == b.sat[j] and a.rising[i] == b.rising[j]
            overlap = min(a.t_end_gps_s[i], b.t_end_gps_s[j]) > max(
                a.t_start_gps_s[i], b.t_start_gps_s[j]
            )
            if same and overlap:
                out.append(a.height_m[i] - b.height_m[j])
    return np.array(out)


def test_esbc_reflector_heights(esbc):
    obs, nav = esbc
    r = reflector_heights(obs, nav, signal="S1C")
    print("\n" + r.summary())
    check_physical(r)
    for system in "GER":
        assert np.any(np.char.startswith(r.sat, system))


def test_esbc_l1_and_l2_agree_arc_by_arc(esbc):
    obs, nav = esbc
    l1 = reflector_heights(obs, nav, signal="S1C", systems="G")
    l2 = reflector_heights(obs, nav, signal="S2W", systems="G")
    check_physical(l2)
    d = paired_differences_m(l1, l2)
    print(f"\nESBC GPS L1-L2: {d.size} arcs, median {np.median(d):+.3f} m")
    # the reflector height does not depend on the carrier: arcs seen on both agree
    assert d.size >= 5
    assert abs(np.median(d)) < 0.10


def test_zimm_rinex2_reflector_heights(zimm):
    obs, nav = zimm
    r1 = reflector_heights(obs, nav, signal="S1")
    print("\n" + r1.summary())
    check_physical(r1)
    assert np.all(r1.code == "S1") and np.allclose(r1.wavelength_m, L1_M)
    r2 = reflector_heights(obs, nav, signal="S2")
    print(r2.summary())
    assert np.all(r2.code == "S2") and np.allclose(r2.wavelength_m, L2_M)
    if r2.n_accepted == 0:
        assert math.isnan(r2.median_height_m) and r2.no_result_reason
    d = paired_differences_m(r1, r2)
    if d.size >= 5:  # only where both signals see the same reflection
        assert abs(np.median(d)) < 0.10


@pytest.mark.parametrize("n", [40, 300])
def test_snr_periodogram_equals_astropys_exact_method(n):
    """scipy's floating-mean sum is astropy's "psd" power (cython method), and its fit."""
    from astropy.timeseries import LombScargle

    from psdbound.validation import snr_arc

    rng = np.random.default_rng(n)
    x = np.sort(rng.uniform(0.1, 0.45, n))
    y = 2.0 + 0.3 * np.sin(2 * np.pi * 21.0 * x + 1.0) + rng.normal(0.0, 0.2, n)
    freq = np.linspace(2.0, 80.0, 400)
    ls = LombScargle(x, y, normalization="psd")
    np.testing.assert_allclose(
        snr_arc._ls_power(x, y, freq), ls.power(freq, method="cython"), rtol=1e-9, atol=1e-12
    )
    theta = ls.model_parameters(21.0)
    assert snr_arc._sinusoid_amplitude(x, y, 21.0) == pytest.approx(
        np.hypot(theta[-2], theta[-1]), rel=1e-9
    )


def test_snr_periodogram_large_arcs_use_astropys_fast_method():
    """Above the size limit, the O(N log N) approximation agrees with the exact sum."""
    from astropy.timeseries import LombScargle

    from psdbound.validation import snr_arc

    rng = np.random.default_rng(7)
    x = np.sort(rng.uniform(0.1, 0.45, 3000))
    y = np.sin(2 * np.pi * 30.0 * x) + rng.normal(0.0, 0.5, x.size)
    freq = np.linspace(2.0, 80.0, 200)
    assert x.size * freq.size > snr_arc._FAST_ABOVE
    exact = LombScargle(x, y, normalization="psd").power(freq, method="cython")
    np.testing.assert_allclose(
        snr_arc._ls_power(x, y, freq), exact, rtol=0.02, atol=1e-3 * exact.max()
    )
