"""Orbit coverage: a navigation/SP3 file that does not match the observations says why."""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, ESBC_SP3, GRAS_OBS, shared_file
from orbit_samples import T2020, T2022, geometric_observations, nominal

from psdbound.arcs import find_arcs
from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError, NoDataError
from psdbound.io import Navigation, PreciseOrbit, orbit_coverage, read_obs, read_orbit
from psdbound.isolation import isolate_dual_frequency

FC = 9.55e-4


def sp3_from(nav, t_gps_s, path="orbit.sp3"):
    """A PreciseOrbit sampled from broadcast positions at the given epochs."""
    sats = nav.satellites
    xyz = np.stack([nav.positions_ecef_m(s, t_gps_s) for s in sats], axis=1)
    return PreciseOrbit(
        path=Path(path),
        t_gps_s=np.asarray(t_gps_s, float),
        sats=sats,
        xyz_m=xyz,
        clock_s=np.zeros(xyz.shape[:2]),
        time_system="GPS",
    )


# ------------------------------------------------------------------ synthetic


def test_matching_orbit_covers_everything():
    nav = nominal("GE")
    obs = geometric_observations(nav)
    cov = orbit_coverage(nav, obs)
    assert cov.kind == "navigation file" and cov.orbit_systems == ("E", "G")
    for system in "GE":
        sc = cov.systems[system]
        assert sc.observed and sc.covered == sc.observed and not sc.missing
        assert cov.problem(system) == ""
        cov.require(system)
    assert cov.warnings() == ()
    with warnings.catch_warnings():
        warnings.simplefilter("error", PsdboundWarning)
        arcs = find_arcs(obs, system="G", orbit=nav, min_length_s=600, elevation_mask_deg=10)
    assert len(arcs) > 3 and arcs.warnings == () and arcs.coverage is not None
    assert "GPS (G): 12 of 12 observed satellites with a position" in cov.summary()


def test_navigation_of_another_year():
    obs = geometric_observations(nominal("GE", t0=T2022), t0=T2022, path="GRAS.rnx")
    nav = nominal("GE", path="ESBC_nav.rnx")  # 2020-06-25
    with pytest.raises(InputError) as err:
        find_arcs(obs, system="G", orbit=nav, min_length_s=600)
    msg = str(err.value)
    assert msg.startswith("ESBC_nav.rnx: the navigation file covers 2020-06-25 ")
    assert "(GPS (G) ephemeris reference times, each used up to 4 h away)" in msg
    assert "the observations of GRAS.rnx run from 2022-11-11 17:00 to 18:59 GPS time" in msg
    assert msg.endswith(
        "use a navigation file of the observation day (2022-11-11, day of year 315)"
    )
    assert "second frequency" not in msg
    cov = orbit_coverage(nav, obs)
    assert cov.systems["E"].outside == cov.systems["E"].observed and not cov.systems["E"].usable
    assert "observations outside the file's time span" in cov.summary()


def test_navigation_without_the_observed_system():
    obs = geometric_observations(nominal("GE"))
    nav = nominal("G", path="gps_only.rnx")
    with pytest.raises(InputError) as err:
        find_arcs(obs, system="E", orbit=nav, min_length_s=600)
    assert str(err.value) == (
        "gps_only.rnx: the navigation file has no Galileo (E) ephemerides (it has GPS (G)); "
        "observed systems: G, E: give a navigation file with Galileo (E) ephemerides or "
        "choose another system"
    )
    # GPS itself is fine with that file
    assert len(find_arcs(obs, system="G", orbit=nav, min_length_s=600)) > 3


def test_sp3_that_ends_before_the_observations():
    nav = nominal("G", t0=T2020 - 86400.0, hours=30.0)
    obs = geometric_observations(nav, systems="G", path="obs.rnx")  # 06:00-08:00
    day_before = T2020 - 6 * 3600 - 86400.0 + 900.0 * np.arange(96)  # 2020-06-24
    sp3 = sp3_from(nav, day_before, path="old.sp3")
    with pytest.raises(InputError) as err:
        find_arcs(obs, system="G", orbit=sp3, min_length_s=600)
    msg = str(err.value)
    assert msg.startswith("old.sp3: the SP3 file covers 2020-06-24 00:00 to 2020-06-24 23:45 GPS")
    assert "use an SP3 file of the observation day (2020-06-25, day of year 177)" in msg


def test_sp3_covering_part_of_the_span_warns():
    nav = nominal("G", hours=3.0)
    obs = geometric_observations(nav, systems="G")  # 06:00-07:59:30
    sp3 = sp3_from(nav, T2020 - 3600.0 + 900.0 * np.arange(9))  # 05:00-07:00
    with pytest.warns(PsdboundWarning, match="lie outside and get no position"):
        arcs = find_arcs(obs, system="G", orbit=sp3, min_length_s=600)
    assert len(arcs) > 0
    (w,) = arcs.warnings  # satellites that rise after 07:00 are not "without ephemerides"
    assert "119 of the 240 observation epochs (49.6 %) lie outside" in w
    assert w.endswith(" observed only then")
    for a in arcs:
        assert a.t_gps_s[-1] <= T2020 + 3600.0


def test_some_satellites_without_ephemerides_warn():
    full = nominal("G")
    obs = geometric_observations(full, systems="G")
    eph = full.ephemerides["G"]
    gone = obs.blocks["G"].sats[:2]
    nav = Navigation(
        path=Path("partial.rnx"),
        version=3.04,
        leap_seconds=None,
        ephemerides={"G": eph.select(~np.isin(eph.sat, gone))},
    )
    with pytest.warns(PsdboundWarning) as rec:
        arcs = find_arcs(obs, system="G", orbit=nav, min_length_s=600)
    expected = (
        f"partial.rnx: the navigation file gives no usable GPS (G) position for 2 of the "
        f"{len(obs.blocks['G'].sats)} observed satellites ({gone[0]} {gone[1]}): their epochs "
        "without a position get no elevation and are left out of the arcs"
    )
    assert arcs.warnings == (expected,)
    assert expected in [str(w.message) for w in rec]
    assert {a.sat for a in arcs}.isdisjoint(gone) and len(arcs) > 3
    cov = orbit_coverage(nav, obs, "G")
    assert cov.systems["G"].missing == tuple(sorted(gone))
    assert f"none for {gone[0]} {gone[1]}" in cov.summary()


def test_second_frequency_message_only_when_true():
    nav = nominal("G")
    obs = geometric_observations(nav, systems="G", drop_code="L2W")
    arcs = find_arcs(obs, system="G", orbit=nav, min_length_s=600)
    assert arcs.tracked == () and arcs.phase_counts[1] == 0
    with pytest.raises(NoDataError, match="L2W .G. at the same epochs: the second frequency"):
        isolate_dual_frequency(arcs, FC)


def test_below_the_mask_is_not_a_missing_frequency():
    nav = nominal("G")
    obs = geometric_observations(nav, systems="G")
    arcs = find_arcs(obs, system="G", orbit=nav, min_length_s=600, elevation_mask_deg=89.9)
    assert len(arcs) == 0 and len(arcs.below_mask) == len(arcs.tracked) > 0
    with pytest.raises(NoDataError) as err:
        isolate_dual_frequency(arcs, FC)
    assert "above the elevation mask of 89.9 deg at any epoch" in str(err.value)
    assert "second frequency" not in str(err.value)


def test_generic_orbit_source_without_metadata():
    nav = nominal("G")
    obs = geometric_observations(nav, systems="G")

    class Bare:
        def positions_ecef_m(self, sat, t):
            return nav.positions_ecef_m(sat, t) + np.nan

    cov = orbit_coverage(Bare(), obs)
    assert cov.kind == "orbit" and cov.orbit_systems is None
    assert "gets a position from the orbit at its observation epochs" in cov.problem("G")
    with pytest.raises(InputError, match="none of the 12 GPS .G. satellites observed"):
        find_arcs(obs, system="G", orbit=Bare(), min_length_s=600)


# ------------------------------------------------------------------ real data


@pytest.mark.realdata
def test_gras_with_the_esbc_navigation_file_of_2020():
    obs = read_obs(shared_file(GRAS_OBS), systems="G")
    nav = read_orbit(shared_file(ESBC_NAV))
    with pytest.raises(InputError) as err:
        find_arcs(obs, system="G", orbit=nav)
    msg = str(err.value)
    assert msg.startswith(f"{shared_file(ESBC_NAV)}: the navigation file covers 2020-06-2")
    assert f"the observations of {GRAS_OBS} run from 2022-11-11 17:00 to 17:14 GPS time" in msg
    assert msg.endswith("(2022-11-11, day of year 315)")


@pytest.mark.realdata
def test_gras_with_the_esbc_sp3_of_2020():
    obs = read_obs(shared_file(GRAS_OBS), systems="R")
    sp3 = read_orbit(shared_file(ESBC_SP3))
    with pytest.raises(
        InputError,
        match=r"the SP3 file covers 2020-06-25 00:00 to 2020-06-25 "
        r"23:45 GPS time; .* use an SP3 file of the observation day",
    ):
        find_arcs(obs, system="R", orbit=sp3)


@pytest.mark.realdata
def test_esbc_with_its_own_orbits():
    obs = read_obs(shared_file(ESBC_OBS), systems="GRC")
    nav = read_orbit(shared_file(ESBC_NAV))
    cov = orbit_coverage(nav, obs)
    assert cov.systems["G"].covered == cov.systems["G"].observed
    assert cov.systems["R"].covered == cov.systems["R"].observed  # GLONASS records now read
    # BeiDou GEO C05 has no broadcast model: a warning, not an error
    (w,) = cov.warnings("C")
    assert "(C05)" in w and "BeiDou GEO satellite C05" in w
    sp3 = read_orbit(shared_file(ESBC_SP3))
    cov = orbit_coverage(sp3, obs, "G")
    assert cov.problem("G") == ""
    assert any("lie outside" in w for w in cov.warnings("G"))  # the SP3 ends at 23:45
    assert "the SP3 file has no BeiDou (C) orbits" in orbit_coverage(sp3, obs, "C").problem("C")


def test_no_observed_satellite_in_the_records():
    full = nominal("G")
    obs = geometric_observations(full, systems="G")
    eph = full.ephemerides["G"]
    others = Navigation(
        Path("others.rnx"), 3.04, None, {"G": eph.select(~np.isin(eph.sat, obs.blocks["G"].sats))}
    )
    with pytest.raises(InputError) as err:
        find_arcs(obs, system="G", orbit=others, min_length_s=600)
    msg = str(err.value)
    assert msg.startswith("others.rnx: none of the 12 GPS (G) satellites observed in synthetic.rnx")
    assert "has a usable ephemeris in the navigation file at its observation epochs" in msg
    assert "the file's GPS (G) ephemerides run from 2020-06-25 " in msg
    sick = Navigation(Path("sick.rnx"), 3.04, None, {"G": eph.select(eph.health >= 0)})
    object.__setattr__(sick.ephemerides["G"], "health", np.ones(len(eph), np.int64))
    with pytest.raises(InputError, match="has a position: the navigation file has no healthy GPS"):
        find_arcs(obs, system="G", orbit=sick, min_length_s=600)


@pytest.mark.parametrize(
    ("which", "reason"),
    [
        ("l2", "the second frequency is missing"),
        ("l1", "the first frequency is missing"),
        ("both", "neither signal has a phase"),
        ("alternate", "each signal was tracked, but never together for two epochs"),
    ],
)
def test_empty_reason_names_the_missing_signal(which, reason):
    from samples import make_obs

    n = 100
    l1 = 2.2e7 + np.arange(n) * 100.0
    l2 = l1.copy()
    if which in ("l1", "both"):
        l1[:] = np.nan
    if which in ("l2", "both"):
        l2[:] = np.nan
    if which == "alternate":
        l1[::2] = np.nan
        l2[1::2] = np.nan
    arcs = find_arcs(make_obs(l1, l2), min_length_s=600)
    assert arcs.empty_reason() == (
        f"no satellite tracked both L1C and L2W (G) at the same epochs: {reason}"
    )
    with pytest.raises(NoDataError, match=reason):
        isolate_dual_frequency(arcs, FC)


@pytest.mark.parametrize(
    ("fraction", "text"),
    [(0.996, "99.6 %"), (0.5, "50 %"), (0.0004, "0.04 %"), (0.99996, "99.996 %")],
)
def test_a_partial_share_never_reads_0_or_100_percent(fraction, text):
    """A satellite with positions at most epochs is 'partial', never '100 %' (NYA1 C16)."""
    from psdbound.io.coverage import _share

    assert _share(fraction) == text
