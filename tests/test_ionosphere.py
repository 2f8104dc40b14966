"""Ionosphere cutoff selection (psdbound.ionosphere, issue #4).

Must-show: a synthetic sum of sinusoids of known amplitudes, replicated over
7 sidereal days like the simulated delays: the envelope lies on or above
every local maximum, f_c lands where the 40 dB line is crossed (within one
grid step), and equals the value the known amplitudes give. Then: the
exact grid-FFT Lomb-Scargle against astropy, the nominal constellation and
the YUMA almanac, slant-delay sanity (magnitude, elevation dependence,
line-of-sight vs thin shell, grid interpolation vs PyIRI evaluated at every
ray point), bad input with specific messages, a 2-worker Dask run with a
cache, and the command line (station; the 20-station map is marked slow).
"""

from __future__ import annotations

import argparse
import json
from functools import lru_cache

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_SP3, shared_file

from psdbound.errors import InputError, NoDataError
from psdbound.io.geometry import geodetic_to_ecef, satellite_azel
from psdbound.io.timescales import calendar_to_gps_s
from psdbound.ionosphere import (
    CHICAGO,
    FREQUENCIES_HZ,
    MAP_STATIONS,
    SIDEREAL_DAY_S,
    CutoffSettings,
    almanac_from_navigation,
    fit_envelope,
    frequency_grid,
    local_maxima,
    lomb_scargle,
    nearest_station,
    nominal_constellation,
    read_yuma,
    select_days,
    series_cutoff,
    simulate_slant_delay,
    station_cutoffs,
    to_one_sided_density,
    write_yuma,
)
from psdbound.ionosphere.iri import slant_tec_direct

DT_S = 12.0
N_DAY = int(np.ceil(SIDEREAL_DAY_S / DT_S))  # 7181 epochs in one sidereal day

LS_METHODS = [pytest.param("gridfft", id="gridfft"), pytest.param("astropy", id="astropy")]
ENV_METHODS = [pytest.param("quantreg", id="quantreg"), pytest.param("linprog", id="linprog")]


# --------------------------------------------------------------------------- synthetic


def synthetic_series(seed: int, alpha: float = 1.0, noise_m: float = 1e-7):
    """Sinusoids at harmonics m / P (m = 1 .. ~3300), amplitude A0 / m^alpha, + tiny noise.

    Returns times (s), values (m), harmonic numbers and amplitudes.
    """
    rng = np.random.default_rng(seed)
    t = DT_S * np.arange(N_DAY)
    m = np.unique(np.round(np.geomspace(1, 3300, 60)).astype(int))
    amp = 1.0 / m**alpha
    phase = rng.uniform(0, 2 * np.pi, m.size)
    y = (amp[:, None] * np.cos(2 * np.pi * m[:, None] * t[None, :] / SIDEREAL_DAY_S
                                + phase[:, None])).sum(axis=0)  # fmt: skip
    y += rng.normal(0.0, noise_m, t.size)
    return t, y, m, amp


@pytest.mark.parametrize("env_method", ENV_METHODS)
@pytest.mark.parametrize("ls_method", LS_METHODS)
@pytest.mark.parametrize("seed", [1, 2])
def test_synthetic_sinusoids_envelope_and_40db_crossing(seed, ls_method, env_method):
    t, y, m, amp = synthetic_series(seed)
    r = series_cutoff(
        t, y, ls_method=ls_method, envelope_method=env_method, reference="psd", keep_spectrum=True
    )
    f, p = r.frequency_hz, r.psd_m2_hz
    # the periodogram peak is the m = 1 line, with the LS "psd" height N A^2 / 4 (one-sided x 2 dt)
    n_total = 7 * N_DAY
    assert r.peak_hz == pytest.approx(1 / SIDEREAL_DAY_S, rel=1e-3)
    assert r.peak_psd_m2_hz == pytest.approx(2 * DT_S * n_total * amp[0] ** 2 / 4, rel=1e-3)
    # envelope on or above every local maximum
    i = local_maxima(p)
    assert i.size > 1000
    assert np.all(r.envelope(f[i]) >= p[i] * (1 - 1e-9))
    # f_c where the 40 dB line is crossed, within one grid step
    thr = r.peak_psd_m2_hz / 1e4
    assert r.threshold_m2_hz == pytest.approx(thr)
    env = r.envelope(f)
    j = np.searchsorted(f, r.f_c_hz) - 1
    assert f[j] <= r.f_c_hz <= f[j + 1]
    assert env[j] >= thr * (1 - 1e-9) and env[j + 1] < thr
    assert np.all(env[j + 1 :] < thr)  # and stays below
    assert r.envelope(r.f_c_hz) == pytest.approx(thr, rel=1e-6)
    # known amplitudes: line power ~ m^-2, 40 dB below the m = 1 line at m = 100
    assert r.f_c_hz == pytest.approx(100 / SIDEREAL_DAY_S, rel=0.08)
    assert r.reached


def test_synthetic_steeper_spectrum_moves_cutoff_down():
    t, y, *_ = synthetic_series(3, alpha=2.0)
    r = series_cutoff(t, y, reference="psd")
    # line power ~ m^-4: 40 dB below the fundamental at m = 10
    assert r.f_c_hz == pytest.approx(10 / SIDEREAL_DAY_S, rel=0.15)


def test_relative_criterion_is_scale_invariant_and_absolute_is_not():
    t, y, *_ = synthetic_series(4)
    a = series_cutoff(t, y)
    b = series_cutoff(t, 10.0 * y)
    assert b.f_c_hz == pytest.approx(a.f_c_hz, rel=1e-9)
    va = series_cutoff(t, y, criterion="absolute", variance_m2=1e-4)
    vb = series_cutoff(t, 10.0 * y, criterion="absolute", variance_m2=1e-4)
    assert vb.f_c_hz > va.f_c_hz
    # the residual above f_c is the allowance
    assert va.residual_m2 == pytest.approx(1e-4, rel=1e-6)


def test_one_day_window_starts_in_a_gap_and_drops_short_arcs():
    from psdbound.ionosphere import one_day_series

    t = DT_S * np.arange(int((SIDEREAL_DAY_S + 12 * 3600) / DT_S))
    phase = np.mod(t, SIDEREAL_DAY_S) / 3600.0
    visible = (phase >= 22.0) | (phase < 3.0) | ((phase >= 10.0) & (phase < 10.2))
    y = np.where(visible, 1.0 + t / 1e5, np.nan)
    tw, yw = one_day_series(t, y)
    assert 3.0 <= tw[0] / 3600.0 and tw[-1] - tw[0] < SIDEREAL_DAY_S
    # one arc, the pass across midnight, unbroken; the 12-min arc is dropped
    assert np.all(np.diff(tw) == DT_S)
    assert tw[-1] - tw[0] == pytest.approx(SIDEREAL_DAY_S - 19 * 3600.0, abs=2 * DT_S)
    np.testing.assert_array_equal(yw, 1.0 + tw / 1e5)
    t_all, y_all = one_day_series(t, y, min_arc_s=0)
    assert t_all.size == tw.size + int(0.2 * 3600 / DT_S)


# --------------------------------------------------------------------------- envelope


@pytest.mark.parametrize("method", ["quantreg", "linprog"])
@pytest.mark.parametrize("degree", [2, 3, 5])
def test_envelope_covers_all_local_maxima_of_random_spectra(method, degree):
    rng = np.random.default_rng(10 + degree)
    f = np.linspace(1e-5, 4e-2, 5000)
    p = 1e3 * (f / 1e-5) ** -1.7 * rng.exponential(1.0, f.size)
    env = fit_envelope(f, p, degree=degree, method=method)
    i = local_maxima(p)
    assert np.all(env(f[i]) >= p[i] * (1 - 1e-9))
    assert env.shift_dex >= 0
    assert env.n_fitted < env.n_maxima
    # close: the envelope is no more than ~1 decade above the highest maxima locally
    assert np.median(env.log10(f[i]) - np.log10(p[i])) < 1.5


def test_local_maxima_definition():
    assert local_maxima([0, 1, 0, 2, 2, 1, 3]).tolist() == [1, 3]
    assert local_maxima([1, 2]).size == 0


def test_envelope_bad_input():
    with pytest.raises(InputError, match="unknown envelope method"):
        fit_envelope(np.arange(1, 10.0), np.ones(9), method="spline")
    with pytest.raises(InputError, match="local maxima"):
        fit_envelope(np.arange(1, 10.0), np.arange(1, 10.0))


# --------------------------------------------------------------------------- Lomb-Scargle


@pytest.mark.parametrize("copies", [1, 7])
def test_gridfft_matches_astropy_exact(copies):
    rng = np.random.default_rng(20 + copies)
    keep = np.zeros(N_DAY, dtype=bool)
    for start, length in ((100, 1500), (3000, 2200), (6000, 900)):
        keep[start : start + length] = True
    t = 1.26e9 + DT_S * np.flatnonzero(keep)
    y = np.cumsum(rng.normal(0, 0.01, t.size)) + np.sin(t / 5000.0)
    f = frequency_grid(DT_S, copies * SIDEREAL_DAY_S)
    sub = np.unique(np.linspace(0, f.size - 1, 300).astype(int))
    ours = lomb_scargle(t, y, f, method="gridfft", copies=copies)[sub]
    exact = lomb_scargle(t, y, f[sub], method="astropy", copies=copies, astropy_method="cython")
    np.testing.assert_allclose(ours, exact, rtol=1e-7)
    # auto picks the grid method here and falls back to astropy for irregular times
    np.testing.assert_allclose(lomb_scargle(t, y, f, copies=copies)[sub], ours, rtol=1e-12)
    jitter = t + rng.uniform(-1, 1, t.size)
    a = lomb_scargle(jitter, y, f[sub], copies=copies)
    assert np.all(np.isfinite(a))


def test_frequency_grid_and_density_scaling():
    f = frequency_grid(DT_S, 7 * SIDEREAL_DAY_S)
    assert f[0] == pytest.approx(1 / (7 * SIDEREAL_DAY_S), rel=1e-4)
    assert f[-1] < 0.99 / (2 * DT_S) + 1e-12 and f[-1] > 0.98 / (2 * DT_S)
    # white noise: the one-sided density integrates to the variance
    rng = np.random.default_rng(5)
    t = DT_S * np.arange(N_DAY)
    y = rng.normal(0, 0.3, t.size)
    fg = frequency_grid(DT_S, SIDEREAL_DAY_S, nyquist_fraction=1.0)
    s = to_one_sided_density(lomb_scargle(t, y, fg), DT_S)
    assert np.sum(s) * (fg[1] - fg[0]) == pytest.approx(np.var(y), rel=0.02)


def test_lomb_scargle_bad_input():
    t = DT_S * np.arange(50000.0)
    with pytest.raises(InputError, match="copies would overlap"):
        lomb_scargle(t, np.ones(t.size), [1e-3, 2e-3], copies=7)
    with pytest.raises(InputError, match="at least 3 samples"):
        lomb_scargle([0.0, 12.0], [1.0, 2.0], [1e-3])
    with pytest.raises(InputError, match="finite"):
        lomb_scargle([0.0, 12.0, 24.0], [1.0, np.nan, 2.0], [1e-3])


# --------------------------------------------------------------------------- orbits


def test_nominal_constellation_geometry():
    gps = nominal_constellation("G")
    assert len(gps.satellites) == 24 and gps.satellites[0] == "G01"
    t = 1.26e9 + np.array([0.0, SIDEREAL_DAY_S / 2, SIDEREAL_DAY_S])
    for sat in ("G01", "G13", "G24"):
        r = gps.positions_ecef_m(sat, t)
        np.testing.assert_allclose(np.linalg.norm(r, axis=1), 26_559.7e3, rtol=1e-12)
        assert gps.period_s(sat) == pytest.approx(SIDEREAL_DAY_S / 2)
        np.testing.assert_allclose(r[2], r[0], atol=1e-3)  # ECEF repeat after a sidereal day
    gal = nominal_constellation("E")
    assert len(gal.satellites) == 24
    r = gal.positions_ecef_m("E07", t)
    np.testing.assert_allclose(np.linalg.norm(r, axis=1), 29_600e3, rtol=1e-12)
    assert gal.period_s("E07") / 3600 == pytest.approx(14.079, abs=1e-3)
    both = nominal_constellation("GE")
    assert len(both.satellites) == 48
    assert np.all(np.isnan(gps.positions_ecef_m("G31", t)))
    with pytest.raises(ValueError, match="no nominal constellation"):
        nominal_constellation("R")


def test_nominal_constellation_visibility_at_chicago():
    gps = nominal_constellation("G")
    rx = geodetic_to_ecef(CHICAGO.lat_deg, CHICAGO.lon_deg, 0.0)
    t = float(calendar_to_gps_s(2020, 1, 6, 0, 0, 0)) + 300.0 * np.arange(288)
    el = np.array([satellite_azel(gps, s, t, rx)[1] for s in gps.satellites])
    in_view = (el >= 10.0).sum(axis=0)
    assert 4 <= in_view.min() and in_view.max() <= 12
    assert 6 <= in_view.mean() <= 10


def test_yuma_round_trip(tmp_path):
    gps = nominal_constellation("G")
    from psdbound.ionosphere.almanac import Almanac

    toa = 1.26e9
    n = 4
    alm = Almanac(
        sats=("G01", "G02", "G03", "G04"),
        toa_gps_s=np.full(n, toa),
        e=np.array([0.01, 0.0, 0.005, 0.02]),
        sqrt_a=np.full(n, 5153.6),
        i0_rad=np.full(n, 0.96),
        omega_dot_rad_s=np.full(n, -8e-9),
        omega0_rad=np.array([0.1, 1.2, -2.0, 3.0]),
        omega_rad=np.array([0.5, 0.0, -1.0, 2.0]),
        m0_rad=np.array([0.0, 1.0, 2.0, -3.0]),
        af0_s=np.zeros(n),
        af1=np.zeros(n),
        health=np.array([0, 0, 0, 63]),
    )
    p = write_yuma(alm, tmp_path / "a.yuma")
    back = read_yuma(p, near_gps_s=toa)
    assert back.satellites == ("G01", "G02", "G03")  # G04 unhealthy
    tt = toa + np.linspace(-86400, 86400, 7)
    for s in back.satellites:
        np.testing.assert_allclose(back.positions_ecef_m(s, tt), alm.positions_ecef_m(s, tt),
                                   atol=0.5)  # fmt: skip
        assert np.all(np.abs(np.linalg.norm(back.positions_ecef_m(s, tt), axis=1) - 5153.6**2)
                      < 0.03 * 5153.6**2)  # fmt: skip
    assert gps.satellites  # nominal and almanac objects share the OrbitSource surface
    bad = tmp_path / "bad.yuma"
    bad.write_text("******** Week 109 almanac for PRN-01 ********\nID: 01\nHealth: zero\n")
    with pytest.raises(InputError, match="line 3.*'Health'"):
        read_yuma(bad)


@pytest.mark.realdata
def test_almanac_from_broadcast_matches_sp3_within_a_few_km():
    from psdbound.io import read_orbit

    nav = read_orbit(shared_file(ESBC_NAV))
    sp3 = read_orbit(shared_file(ESBC_SP3))
    t0 = float(calendar_to_gps_s(2020, 6, 25, 12, 0, 0))
    alm = almanac_from_navigation(nav, t0)
    assert len(alm.satellites) >= 30
    t = t0 + np.linspace(-11, 11, 23) * 3600
    errs = []
    for s in alm.satellites:
        d = np.linalg.norm(alm.positions_ecef_m(s, t) - sp3.positions_ecef_m(s, t), axis=1)
        if np.any(np.isfinite(d)):
            errs.append(np.nanmax(d))
    assert np.max(errs) < 5e3


# --------------------------------------------------------------------------- slant delay


@lru_cache(maxsize=4)
def chicago_day(method: str = "line-of-sight", stride: int = 5, satellites=None):
    return simulate_slant_delay(
        CHICAGO.lat_deg, CHICAGO.lon_deg, "2020-01-06", method=method, ray_stride=stride,
        satellites=satellites,
    )  # fmt: skip


def test_slant_delay_magnitude_and_elevation_dependence():
    sd = chicago_day()
    d, el = sd.delay_m, sd.elevation_deg
    ok = np.isfinite(d)
    assert 20 <= len(sd.sats) <= 24
    assert np.all(el[ok] >= 10.0) and np.all(np.isnan(d[el < 10.0]))
    assert 0.05 < np.nanmin(d) and np.nanmax(d) < 30.0  # metre level at L1
    assert 0.2 < np.nanmedian(d) < 5.0 and np.nanmax(d) > 1.0
    # larger at low elevation: compare each pass's low and high elevation samples
    low = np.nanmedian(np.where(el < 20, d, np.nan))
    high = np.nanmedian(np.where(el > 60, d, np.nan))
    assert low > 1.5 * high
    assert sd.info["orbit_source"] == "nominal:G:24"
    t, y = sd.series(sd.sats[0])
    assert np.all(np.diff(t) >= DT_S - 1e-6) and np.all(np.isfinite(y))


def test_line_of_sight_and_thin_shell_agree_at_high_elevation():
    los = chicago_day()
    shell = chicago_day("thin-shell")
    assert shell.info["shell_height_km"] == 350.0
    ratio = shell.delay_m / los.delay_m
    hi = los.elevation_deg > 50
    assert np.nanmedian(np.abs(ratio[hi] - 1)) < 0.05
    assert np.nanmax(np.abs(ratio[hi] - 1)) < 0.3


def test_grid_interpolation_matches_pyiri_along_the_ray():
    sd = chicago_day()
    k_tecu = 40.3e16 / FREQUENCIES_HZ["L1"] ** 2
    rng = np.random.default_rng(7)
    js, ks = np.nonzero(np.isfinite(sd.delay_m))
    for i in rng.choice(js.size, 4, replace=False):
        j, k = js[i], ks[i]
        direct = slant_tec_direct(
            CHICAGO.lat_deg, CHICAGO.lon_deg, "2020-01-06", sd.t_gps_s[k],
            sd.elevation_deg[j, k], sd.azimuth_deg[j, k],
        )  # fmt: skip
        assert sd.delay_m[j, k] / k_tecu == pytest.approx(direct, rel=0.02)


def test_ray_stride_spline_is_transparent():
    sats = ("G01", "G05")
    a = chicago_day(stride=5, satellites=sats)
    b = chicago_day(stride=1, satellites=sats)
    assert np.nanmax(np.abs(a.delay_m - b.delay_m)) < 1e-3  # below a millimetre


def test_delay_scales_with_frequency():
    sats = ("G01",)
    l1 = chicago_day(satellites=sats)
    l2 = simulate_slant_delay(
        CHICAGO.lat_deg, CHICAGO.lon_deg, "2020-01-06", satellites=sats,
        frequency_hz=FREQUENCIES_HZ["L2"],
    )  # fmt: skip
    ratio = (FREQUENCIES_HZ["L1"] / FREQUENCIES_HZ["L2"]) ** 2
    np.testing.assert_allclose(l2.delay_m, l1.delay_m * ratio, rtol=1e-9)


# --------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("kwargs", "error", "message"),
    [
        ({"lat_deg": 95.0}, InputError, r"latitude 95\.0 deg is out of range: expected -90 to 90"),
        ({"lon_deg": 400.0}, InputError, "longitude 400.0 deg is out of range"),
        (
            {"date": "1975-01-01"},
            InputError,
            "outside the supported range 1980-01-06 to 2030-12-31",
        ),
        ({"date": "2031-06-01"}, InputError, "outside the supported range"),
        ({"date": "2020-02-30"}, InputError, "'2020-02-30' is not a valid calendar date"),
        ({"f107_sfu": 10.0}, InputError, "F10.7 = 10.0 sfu is outside the plausible range"),
        ({"method": "ray"}, InputError, "unknown slant method 'ray'"),
        ({"elevation_mask_deg": 90.0}, InputError, "elevation mask 90.0 deg is out of range"),
        (
            {"elevation_mask_deg": 89.9},
            NoDataError,
            r"no satellite rises above the 89\.9 deg elevation mask at 41\.84 -87\.63 on "
            r"2020-01-06",
        ),
    ],
)
def test_bad_input_specific_messages(kwargs, error, message):
    args = {"lat_deg": 41.84, "lon_deg": -87.63, "date": "2020-01-06", **kwargs}
    with pytest.raises(error, match=message):
        simulate_slant_delay(args.pop("lat_deg"), args.pop("lon_deg"), args.pop("date"), **args)


def test_orbit_file_not_covering_the_day():
    from psdbound.ionosphere.almanac import Almanac

    class Empty:
        satellites = ("G01",)
        path = "empty.nav"

        def positions_ecef_m(self, sat, t):
            return np.full((np.atleast_1d(t).size, 3), np.nan)

    assert not isinstance(Empty(), Almanac)
    with pytest.raises(NoDataError, match="gives no satellite position on 2020-01-06"):
        simulate_slant_delay(41.84, -87.63, "2020-01-06", orbit=Empty())


def test_day_selection():
    days = select_days(2020)
    assert [d.isoformat() for d in days[:3]] == ["2020-01-06", "2020-02-03", "2020-03-02"]
    assert all(d.weekday() == 0 and d.day <= 7 for d in days) and len(days) == 12
    assert [d.isoformat() for d in select_days(2020, "2020-05-04, 2021-01-04")] == [
        "2020-05-04",
        "2021-01-04",
    ]
    with pytest.raises(InputError, match="outside the supported range"):
        select_days(2040)
    with pytest.raises(InputError, match="not a valid calendar date"):
        select_days(2020, "mondays")


def test_stations_and_nearest_lookup():
    assert len(MAP_STATIONS) == 20
    st, d = nearest_station(41.84, -87.63)
    assert st.name == "SASK"  # Saskatoon is nearer Chicago than Pie Town
    st, d = nearest_station(-66.0, 111.0)
    assert st.name == "CAS1" and d < 1.0
    with pytest.raises(InputError, match="latitude 95"):
        nearest_station(95.0, 0.0)


# --------------------------------------------------------------------------- batch / Dask


def test_dask_two_workers_and_cache(tmp_path):
    settings = CutoffSettings(grid_size=15, ut_step_h=1.0)
    kw = {
        "satellites": ("G01", "G02"),
        "settings": settings,
        "workers": 2,
        "cache_dir": tmp_path / "cache",
    }
    days = ["2020-01-06", "2020-07-06"]
    first = station_cutoffs(41.84, -87.63, days, name="CHI", **kw)
    assert first.from_cache == [False, False]
    assert len(first.rows) == 4 and {r["sat"] for r in first.rows} == {"G01", "G02"}
    s = first.summary()
    assert s["recommended_f_c_hz"] == s["max_f_c_hz"] == max(first.f_c_hz)
    assert s["min_f_c_hz"] <= s["mean_f_c_hz"] <= s["max_f_c_hz"]
    assert len(list((tmp_path / "cache").glob("*.json"))) == 2
    second = station_cutoffs(41.84, -87.63, days, name="CHI", **kw)
    assert second.from_cache == [True, True]
    assert [r["f_c_hz"] for r in second.rows] == [r["f_c_hz"] for r in first.rows]
    assert second.series_by_date["2020-01-06"]["sats"] == ["G01", "G02"]
    # any change of input is a different cache entry
    third = station_cutoffs(
        41.84, -87.63, days[:1], name="CHI", **{**kw, "workers": 0,
        "settings": CutoffSettings(grid_size=15, ut_step_h=1.0, drop_db=30.0)},
    )  # fmt: skip
    assert third.from_cache == [False]
    assert third.rows[0]["f_c_hz"] < first.rows[0]["f_c_hz"]


def test_dask_scheduler_address(tmp_path):
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster:
        res = station_cutoffs(
            41.84, -87.63, ["2020-01-06"], satellites=("G07",), scheduler=cluster.scheduler_address,
            settings=CutoffSettings(grid_size=11, ut_step_h=2.0), use_cache=False,
            cache_dir=tmp_path,
        )  # fmt: skip
        assert [r["sat"] for r in res.rows] == ["G07"]
        assert res.from_cache == [False]
    assert not list(tmp_path.iterdir())  # use_cache=False writes nothing


def test_station_run_no_satellite_above_mask(tmp_path):
    with pytest.raises(NoDataError, match="no satellite rises above the 89.9 deg"):
        station_cutoffs(
            41.84, -87.63, ["2020-01-06"], workers=0, cache_dir=tmp_path,
            settings=CutoffSettings(elevation_mask_deg=89.9),
        )  # fmt: skip


# --------------------------------------------------------------------------- command line


def cli(argv):
    from psdbound.cli.cutoff import add_parser

    parser = argparse.ArgumentParser(prog="psdbound")
    sub = parser.add_subparsers(dest="command")
    add_parser(sub)
    args = parser.parse_args(argv)
    return args.func(args)


def test_cli_station_writes_table_json_and_figures(tmp_path, capsys):
    out = tmp_path / "out"
    code = cli([
        "cutoff", "--lat", "41.84", "--lon", "-87.63", "--days", "2020-01-06", "--workers", "0",
        "--name", "CHICAGO", "--out", str(out), "--cache-dir", str(tmp_path / "c"),
    ])  # fmt: skip
    assert code == 0
    printed = capsys.readouterr().out
    assert "recommended f_c =" in printed
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        "cutoff_CHICAGO.csv",
        "cutoff_CHICAGO.json",
        "cutoff_CHICAGO_envelopes.png",
        "cutoff_CHICAGO_psd.png",
    ]
    data = json.loads((out / "cutoff_CHICAGO.json").read_text())
    assert data["orbit_source"] == "nominal:G:24"
    assert data["settings"]["f107_sfu"] == 70.0
    assert data["summary"]["n_series"] == len(data["rows"]) >= 20
    lines = (out / "cutoff_CHICAGO.csv").read_text().splitlines()
    assert lines[0].startswith("date,sat,f_c_hz,tau_c_min")
    assert len(lines) == 1 + data["summary"]["n_series"]
    assert (out / "cutoff_CHICAGO_psd.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--lat", "95", "--lon", "0"], "latitude 95.0 deg is out of range"),
        (["--lat", "41"], "--lat and --lon go together"),
        (["--lat", "41", "--lon", "0", "--days", "1979-12-31"], "outside the supported range"),
        (["--lat", "41", "--lon", "0", "--frequency", "L9"], "unknown carrier 'L9'"),
        ([], "give --lat and --lon for a station, or --map"),
    ],
)
def test_cli_bad_input(tmp_path, argv, message):
    with pytest.raises(InputError, match=message):
        cli(["cutoff", "--workers", "0", "--out", str(tmp_path), *argv])


@pytest.mark.slow
def test_cli_map_of_20_stations_through_dask(tmp_path, capsys):
    out = tmp_path / "map"
    code = cli([
        "cutoff", "--map", "--days", "2020-01-06", "--workers", "2", "--out", str(out),
        "--cache-dir", str(tmp_path / "c"), "--lat", "41.84", "--lon", "-87.63",
    ])  # fmt: skip
    assert code == 0
    printed = capsys.readouterr().out
    assert "nearest station to (41.84, -87.63): SASK" in printed
    lines = (out / "cutoff_map.csv").read_text().splitlines()
    assert len(lines) == 21 and lines[0].startswith("name,lat_deg,lon_deg")
    data = json.loads((out / "cutoff_map.json").read_text())
    assert [s["name"] for s in data["stations"]] == [s.name for s in MAP_STATIONS]
    assert all(s["n_series"] > 10 and s["recommended_f_c_hz"] > 0 for s in data["stations"])
    assert (out / "cutoff_map.png").read_bytes()[:4] == b"\x89PNG"
