"""The cutoff a fit uses (issue #16): the shipped world map by default, interpolated.

Must-show: ``auto`` without a cutoff takes the map at the receiver's
position and date (the source names the cell and the solar flux), the
thesis constant only on request; the map is sound (both layers, the grid and
the 20 stations, its provenance, small) and interpolates as documented.
"""

from __future__ import annotations

import datetime as dt
from importlib import resources

import numpy as np
import pytest

from psdbound.errors import InputError
from psdbound.ionosphere import (
    MAP_STATIONS,
    THESIS_CUTOFF_HZ,
    CutoffOptions,
    choose_cutoff,
    cutoff_from_map,
    interpolate_map,
    load_map,
)
from psdbound.ionosphere.solar import annual_f107, monthly_f107
from psdbound.ionosphere.worldmap import MAP_FILE, grid_sites, map_validation

ESBC = (55.58, 12.63)  # ESBC00DNK, Espergaerde (Denmark)
NYA1 = (78.93, 11.87)  # NYA100NOR, Ny-Alesund (Svalbard)


@pytest.fixture(scope="module")
def doc():
    return load_map()


def test_shipped_map_is_sound(doc):
    path = resources.files("psdbound.ionosphere").joinpath(MAP_FILE)
    assert len(path.read_bytes()) < 1_000_000
    assert doc["pyiri_version"] and doc["created_utc"] and doc["psdbound_version"]
    assert doc["criterion"]["name"] == "residual" and doc["criterion"]["margin_db"] == 40.0
    names = [la["name"] for la in doc["layers"]]
    assert names == ["solar-min", "solar-max"]
    f107 = [la["f107_sfu"] for la in doc["layers"]]
    assert f107[0] == pytest.approx(annual_f107(2020), abs=0.01)
    assert f107[1] == pytest.approx(annual_f107(2024), abs=0.01)
    lat, lon = doc["grid"]["lat_deg"], doc["grid"]["lon_deg"]
    assert len(lat) * len(lon) == len(
        grid_sites(doc["grid"]["lat_step_deg"], doc["grid"]["lon_step_deg"])
    )
    for layer in doc["layers"]:
        assert [s["name"] for s in layer["stations"]] == [s.name for s in MAP_STATIONS]
        g = np.array(layer["grid"]["recommended_f_c_hz"], dtype=float)
        assert g.shape == (len(lat), len(lon)) and np.all(np.isfinite(g))
        # every cutoff leaves at least the verdict's factor 4 below the 30 s Nyquist frequency
        assert 1e-4 < g.min() and g.max() < (1 / 60) / 4
        assert len(layer["days"]) == 4
    # solar maximum raises the cutoff (more ionosphere left by the same filter)
    smin = np.array(doc["layers"][0]["grid"]["recommended_f_c_hz"], dtype=float)
    smax = np.array(doc["layers"][1]["grid"]["recommended_f_c_hz"], dtype=float)
    assert np.median(smax / smin) > 1.05
    assert map_validation(doc) == doc["validation"]


def test_interpolation_on_the_grid(doc):
    lat, lon = doc["grid"]["lat_deg"], doc["grid"]["lon_deg"]
    layer = doc["layers"][0]
    node = layer["grid"]["recommended_f_c_hz"][2][1]
    f107 = layer["f107_sfu"]
    assert interpolate_map(doc, lat[2], lon[1], f107)[0] == pytest.approx(node)
    # periodic in longitude, clamped in latitude
    a = interpolate_map(doc, 10.0, 179.9, f107)[0]
    b = interpolate_map(doc, 10.0, -180.1, f107)[0]
    assert a == pytest.approx(b, rel=1e-9)
    assert interpolate_map(doc, 89.9, 0.0, f107)[0] == pytest.approx(
        interpolate_map(doc, lat[-1], 0.0, f107)[0]
    )
    # linear in F10.7 between the layers, clamped below, extrapolated above
    lo = interpolate_map(doc, 45.0, 10.0, doc["layers"][0]["f107_sfu"])[0]
    hi = interpolate_map(doc, 45.0, 10.0, doc["layers"][1]["f107_sfu"])[0]
    mid = 0.5 * (doc["layers"][0]["f107_sfu"] + doc["layers"][1]["f107_sfu"])
    f, info = interpolate_map(doc, 45.0, 10.0, mid)
    assert f == pytest.approx(0.5 * (lo + hi)) and info["solar"] == "interpolated"
    assert interpolate_map(doc, 45.0, 10.0, 60.0)[1]["solar"] == "clamped"
    assert interpolate_map(doc, 45.0, 10.0, 60.0)[0] == pytest.approx(lo)
    assert interpolate_map(doc, 45.0, 10.0, 250.0)[1]["solar"] == "extrapolated"
    big = choose_cutoff(CutoffOptions(), lat_deg=45.0, lon_deg=10.0, year=2024, date="2024-08-05")
    assert any("extrapolated linearly" in w for w in big.warnings)  # August 2024: 246 sfu


def test_auto_uses_the_map_at_the_position_and_date():
    esbc = choose_cutoff(
        CutoffOptions(), lat_deg=ESBC[0], lon_deg=ESBC[1], year=2020, date="2020-06-25"
    )
    lo, hi = esbc.info["cell"]["lat_deg"]
    assert esbc.source.startswith(f"map (cell {lo:g}..{hi:g} N") and lo <= ESBC[0] <= hi
    assert "F10.7 70 sfu" in esbc.source and "nearest reference station LAMA" in esbc.source
    assert esbc.info["f107_source"] == "monthly mean 2020-06"
    assert esbc.info["station"] == "LAMA"
    assert 2e-4 < esbc.f_c_hz < 4e-3 and esbc.f_c_hz != THESIS_CUTOFF_HZ
    assert esbc.info["map_pyiri_version"] and esbc.info["cell"]["corner_f_c_hz"]
    nya = choose_cutoff(
        CutoffOptions(), lat_deg=NYA1[0], lon_deg=NYA1[1], year=2024, date=dt.date(2024, 5, 3)
    )
    assert nya.info["f107_sfu"] == pytest.approx(monthly_f107(2024, 5))
    assert nya.source.startswith("map (cell ") and not nya.warnings  # 188 sfu: 1.6 % above
    assert nya.info["solar"] == "extrapolated"
    # the same place at solar maximum needs a higher cutoff than at solar minimum
    quiet = choose_cutoff(CutoffOptions(), lat_deg=NYA1[0], lon_deg=NYA1[1], year=2020)
    assert nya.f_c_hz > quiet.f_c_hz
    # without a date the year's mean flux is used
    assert quiet.info["f107_source"] == "annual mean 2020"


def test_sources_given_thesis_and_fallbacks():
    given = choose_cutoff(CutoffOptions(f_c_hz=2e-3), lat_deg=1.0, lon_deg=2.0, year=2020)
    assert (given.f_c_hz, given.source) == (2e-3, "given")
    thesis = choose_cutoff(CutoffOptions(source="thesis"), lat_deg=1.0, lon_deg=2.0, year=2020)
    assert thesis.f_c_hz == THESIS_CUTOFF_HZ == 9.55e-4 and thesis.source.startswith("thesis")
    nopos = choose_cutoff(CutoffOptions(), lat_deg=None, lon_deg=None, year=2020)
    assert nopos.f_c_hz == THESIS_CUTOFF_HZ and "no receiver position" in nopos.warnings[0]
    old = choose_cutoff(CutoffOptions(), lat_deg=41.84, lon_deg=-87.63, year=1999)
    assert old.info["solar"] == "conservative" and "no solar flux" in old.warnings[0]
    with pytest.raises(InputError, match="needs a receiver position"):
        choose_cutoff(CutoffOptions(source="map"), lat_deg=None, lon_deg=None, year=2020)
    with pytest.raises(InputError, match="unknown cutoff source"):
        choose_cutoff(CutoffOptions(source="nearest"), lat_deg=1.0, lon_deg=2.0, year=2020)
    with pytest.raises(InputError, match="needs --cutoff-hz"):
        choose_cutoff(CutoffOptions(source="given"), lat_deg=1.0, lon_deg=2.0, year=2020)


def test_band_warning_and_other_margins():
    c = choose_cutoff(CutoffOptions(), lat_deg=41.84, lon_deg=-87.63, year=2020, interval_s=30.0)
    assert not c.warnings
    tight = choose_cutoff(
        CutoffOptions(margin_db=50.0), lat_deg=-10.0, lon_deg=0.0, year=2024, interval_s=120.0
    )
    assert any("too little band" in w for w in tight.warnings)
    # 2 mm at 40 dB is 34 dB below 1 mm: between the map's 30 and 40 dB cutoffs
    f40, _ = cutoff_from_map(41.84, -87.63, year=2020)
    f30, _ = cutoff_from_map(41.84, -87.63, year=2020, margin_db=30.0)
    f2mm, _ = cutoff_from_map(41.84, -87.63, year=2020, mp_sigma_m=2e-3)
    assert f30 < f2mm < f40
    with pytest.raises(InputError, match="computed"):
        cutoff_from_map(41.84, -87.63, year=2020, margin_db=70.0)


def test_computed_source_simulates_the_date_flux(monkeypatch):
    """'computed' runs a station-year at the receiver with the F10.7 of the data's month."""
    import psdbound.ionosphere.batch as batch

    seen = {}

    class Fake:
        def summary(self):
            return {"recommended_f_c_hz": 1.23e-3, "n_series": 7}

    def fake(lat, lon, days, **kw):
        seen.update(lat=lat, lon=lon, n_days=len(days), settings=kw["settings"])
        return Fake()

    monkeypatch.setattr(batch, "station_cutoffs", fake)
    c = choose_cutoff(
        CutoffOptions(source="computed", margin_db=30.0),
        lat_deg=ESBC[0],
        lon_deg=ESBC[1],
        year=2020,
        date="2020-06-25",
    )
    assert c.f_c_hz == 1.23e-3 and c.source.startswith("computed (PyIRI, residual criterion, 2020")
    assert seen["n_days"] == 12 and seen["settings"].f107_sfu == pytest.approx(69.7)
    assert seen["settings"].margin_db == 30.0 and c.info["computed"]["n_series"] == 7


def test_the_cutoff_is_for_the_data_s_carriers():
    """The map is GPS L1/L2: applied to another pair it says so; 'computed' uses the pair."""
    from psdbound.constants import F_L1_HZ, F_L2_HZ, F_L5_HZ
    from psdbound.ionosphere import policy

    assert policy.iono_coefficient_ratio((F_L1_HZ, F_L2_HZ)) == pytest.approx(1.0)
    assert policy.iono_coefficient_ratio((F_L1_HZ, F_L5_HZ)) == pytest.approx(1.226, abs=1e-3)
    kw = dict(lat_deg=ESBC[0], lon_deg=ESBC[1], year=2020, date="2020-06-25")
    gps = choose_cutoff(CutoffOptions(), carriers_hz=(F_L1_HZ, F_L2_HZ), **kw)
    gal = choose_cutoff(CutoffOptions(), carriers_hz=(F_L1_HZ, F_L5_HZ), system="E", **kw)
    assert gal.f_c_hz == gps.f_c_hz and not gps.warnings
    assert any("computed for GPS L1/L2" in w and "1.23 times" in w for w in gal.warnings)


def test_a_computed_cutoff_simulates_the_data_s_carriers_and_constellation(monkeypatch):
    from psdbound.constants import F_L1_HZ, F_L5_HZ
    from psdbound.ionosphere import batch

    seen = {}

    class _Res:
        def summary(self):
            return {"recommended_f_c_hz": 2e-3}

    def fake(*args, settings, **kwargs):
        seen["settings"] = settings
        return _Res()

    monkeypatch.setattr(batch, "station_cutoffs", fake)
    got = choose_cutoff(
        CutoffOptions(source="computed"),
        lat_deg=ESBC[0],
        lon_deg=ESBC[1],
        year=2020,
        carriers_hz=(F_L1_HZ, F_L5_HZ),
        system="E",
    )
    s = seen["settings"]
    assert (s.frequency_hz, s.second_frequency_hz, s.systems) == (F_L1_HZ, F_L5_HZ, "E")
    assert "1575.42/1176.45 MHz, nominal E" in got.source and got.f_c_hz == 2e-3


def test_an_orbit_file_is_restricted_to_the_systems_asked_for():
    """cutoff --systems G with a Galileo-only navigation file: bad input, not Galileo silently."""
    from types import SimpleNamespace

    from psdbound.common.notices import PsdboundWarning
    from psdbound.ionosphere.workflow import _system_satellites

    gal = SimpleNamespace(satellites=["E01", "E02"])
    with pytest.raises(InputError, match="holds E only, not the systems asked for"):
        _system_satellites(gal, "G", "nav.rnx")
    mixed = SimpleNamespace(satellites=["E01", "G05", "G07"])
    with pytest.warns(PsdboundWarning, match="also holds E satellites, not analysed"):
        assert _system_satellites(mixed, "G", "nav.rnx") == ["G05", "G07"]
    assert _system_satellites(None, "G", None) is None
