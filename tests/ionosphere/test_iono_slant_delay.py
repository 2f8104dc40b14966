"""Slant ionospheric delays (PyIRI): magnitude, geometry, grid against direct PyIRI, bad input."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from psdbound.errors import InputError, NoDataError
from psdbound.ionosphere import CHICAGO, FREQUENCIES_HZ, simulate_slant_delay
from psdbound.ionosphere.slant import slant_tec_direct

DT_S = 12.0


@lru_cache(maxsize=4)
def chicago_day(method: str = "line-of-sight", stride: int = 5, satellites=None):
    return simulate_slant_delay(
        CHICAGO.lat_deg,
        CHICAGO.lon_deg,
        "2020-01-06",
        method=method,
        ray_stride=stride,
        satellites=satellites,
    )


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
            CHICAGO.lat_deg,
            CHICAGO.lon_deg,
            "2020-01-06",
            sd.t_gps_s[k],
            sd.elevation_deg[j, k],
            sd.azimuth_deg[j, k],
        )
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
        CHICAGO.lat_deg,
        CHICAGO.lon_deg,
        "2020-01-06",
        satellites=sats,
        frequency_hz=FREQUENCIES_HZ["L2"],
    )
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
