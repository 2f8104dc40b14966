"""Cutoff settings built in one place: from a mapping, and handed to each stage."""

from __future__ import annotations

import inspect

import pytest

from psdbound.errors import InputError
from psdbound.ionosphere import (
    FREQUENCIES_HZ,
    SETTING_OPTIONS,
    CutoffSettings,
    residual_cutoffs,
    series_cutoff,
    simulate_slant_delay,
)
from psdbound.isolation import HighPass


def test_from_mapping_only_given_options_change():
    s = CutoffSettings.from_mapping(
        {"carrier": "L1-L2", "systems": "ge", "drop_db": 30.0, "degree": None}
    )
    assert s.frequency_hz == FREQUENCIES_HZ["L1"]
    assert s.second_frequency_hz == FREQUENCIES_HZ["L2"]
    assert s.systems == "GE" and s.drop_db == 30.0 and s.degree == CutoffSettings().degree
    assert CutoffSettings.from_mapping({}) == CutoffSettings()
    assert CutoffSettings.from_mapping({"carrier": "1500"}).frequency_hz == 1500e6
    back = CutoffSettings.from_mapping(s.to_dict())
    assert back == s and isinstance(back.alt_range_km, tuple)
    assert "carrier" in SETTING_OPTIONS and "f107_sfu" in SETTING_OPTIONS


@pytest.mark.parametrize(
    ("options", "message"),
    [
        ({"f107": 70.0}, "unknown cutoff setting"),
        ({"carrier": "L9"}, "unknown carrier 'L9'"),
        ({"carrier": "L1-E1"}, "same frequency"),
        ({"f107_sfu": 10.0}, "outside the plausible range"),
        ({"systems": "R"}, "expected one or more of G, E"),
    ],
)
def test_from_mapping_bad_options(options, message):
    with pytest.raises(InputError, match=message):
        CutoffSettings.from_mapping(options)


def test_stage_options_are_the_stage_keywords():
    s = CutoffSettings()
    sim = inspect.signature(simulate_slant_delay).parameters
    ser = inspect.signature(series_cutoff).parameters
    assert set(s.simulation_options()) <= set(sim)
    assert set(s.series_options()) <= set(ser)
    assert s.series_options()["dt_s"] == s.sampling_s
    assert s.simulation_options()["grid_size"] == 11
    res = inspect.signature(residual_cutoffs).parameters
    assert set(s.residual_options()) <= set(res)


def test_defaults_and_the_legacy_settings():
    s = CutoffSettings()
    assert s.criterion == "residual" and s.sampling_s == 30.0
    assert s.second_frequency_hz == FREQUENCIES_HZ["L2"] and s.residual_scale == pytest.approx(
        2**-0.5
    )
    assert s.thresholds_m()[0] == pytest.approx(1e-5) and s.margins_db()[0] == 40.0
    assert s.highpass() == HighPass()
    old = CutoffSettings.legacy()
    assert (old.criterion, old.sampling_s, old.grid_size, old.second_frequency_hz) == (
        "relative",
        12.0,
        21,
        None,
    )
    assert old.residual_scale == 1.0 and old.series_options()["criterion"] == "relative"
    assert CutoffSettings.legacy(drop_db=30.0).drop_db == 30.0
    with pytest.raises(InputError, match="criterion"):
        CutoffSettings.from_mapping({"criterion": "median"})
    with pytest.raises(InputError, match="mp_sigma_m"):
        CutoffSettings.from_mapping({"mp_sigma_m": 0.0})


def test_galileo_alone_defaults_to_its_own_carriers():
    """--systems E analysed Galileo at GPS L1/L2 (Galileo has no L2)."""
    from psdbound.ionosphere.names import FREQUENCIES_HZ

    gal = CutoffSettings.from_mapping({"systems": "e"})
    assert (gal.frequency_hz, gal.second_frequency_hz) == (
        FREQUENCIES_HZ["E1"],
        FREQUENCIES_HZ["E5a"],
    )
    both = CutoffSettings.from_mapping({"systems": "GE"})
    assert both.second_frequency_hz == FREQUENCIES_HZ["L2"]  # mixed: GPS's pair, as given
    given = CutoffSettings.from_mapping({"systems": "E", "carrier": "L1-E5b"})
    assert given.second_frequency_hz == FREQUENCIES_HZ["E5b"]


def test_nominal_systems_are_the_nominal_constellations():
    """NOMINAL_SYSTEMS names exactly the systems psdbound.io.nominal builds."""
    from psdbound.io.nominal import nominal_elements
    from psdbound.ionosphere.names import NOMINAL_SYSTEMS

    assert [nominal_elements(s).system for s in NOMINAL_SYSTEMS] == list(NOMINAL_SYSTEMS)
    for other in "RCJSI":
        with pytest.raises(ValueError, match="no nominal constellation"):
            nominal_elements(other)
