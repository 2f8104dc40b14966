"""Simulator truths on demand: --multipath specs, scenario TOML files, the truth PSD model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from psdbound.arcs import find_arcs
from psdbound.common.options import OptionError
from psdbound.errors import InputError
from psdbound.io import read_obs, read_orbit
from psdbound.isolation import isolate_dual_frequency
from psdbound.simulate import (
    IonoDisturbance,
    MultipathModel,
    Reflection,
    Scenario,
    compare_to_truth,
    preset,
    simulate,
    truth_model,
)
from psdbound.spectra import GaussMarkovWhiteNoise
from psdbound.stationarity import ElevationMapping

FC = 9.55e-4


# ------------------------------------------------------------------ --multipath specs
@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            "sigma_gm_m=0.004,tau_s=120,sigma_wn_m=0.002,mapping=1,12,10",
            dict(sigma_gm_m=0.004, tau_s=120.0, sigma_wn_m=0.002, a=1.0, b=12.0, c_deg=10.0),
        ),
        ("tau_s=300", dict(tau_s=300.0)),
        (" sigma_wn_m = 0 , b=20 ", dict(sigma_wn_m=0.0, b=20.0)),
        ("mapping=2, 5, 20,tau_s=1e3", dict(a=2.0, b=5.0, c_deg=20.0, tau_s=1000.0)),
        ("c_deg=90,sigma_gm_m=0.05,tau_s=86400", dict(c_deg=90.0, sigma_gm_m=0.05, tau_s=86400.0)),
    ],
)
def test_spec_sets_the_given_keys_only(text, expected):
    base = MultipathModel(sigma_gm_m=0.001, tau_s=45.0, sigma_wn_m=0.0003, a=1.5, b=3.0, c_deg=12.0)
    got = MultipathModel.from_spec(text, base=base)
    for key in ("sigma_gm_m", "tau_s", "sigma_wn_m", "a", "b", "c_deg"):
        assert getattr(got, key) == expected.get(key, getattr(base, key)), key
    assert isinstance(got.tau_s, float)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("", "--multipath is empty; expected comma-separated key=value items"),
        ("   ", "--multipath is empty"),
        ("sigma_gm_m", "--multipath: item 'sigma_gm_m' has no '='"),
        ("tau_s=30,,b=2", "--multipath: item '' has no '='"),
        ("tau=30", "--multipath: unknown key 'tau'; expected any of sigma_gm_m, tau_s"),
        ("sigma_gm_m=abc", "--multipath sigma_gm_m must be a number from 0 to 0.05 m, got 'abc'"),
        ("sigma_gm_m=", "--multipath sigma_gm_m must be a number from 0 to 0.05 m, got ''"),
        ("sigma_gm_m=nan", "--multipath sigma_gm_m must be a number from 0 to 0.05 m, got nan"),
        ("sigma_gm_m=0.2", "got 0.2 (carrier multipath cannot exceed a quarter wavelength"),
        ("sigma_wn_m=0.06", "--multipath sigma_wn_m must be a number from 0 to 0.05 m, got 0.06"),
        ("sigma_wn_m=-0.001", "--multipath sigma_wn_m must be a number from 0 to 0.05 m"),
        ("tau_s=0", "--multipath tau_s must be a number > 0 and <= 86400 s, got 0"),
        ("tau_s=90000", "--multipath tau_s must be a number > 0 and <= 86400 s, got 90000"),
        ("tau_s=inf", "--multipath tau_s must be a number > 0 and <= 86400 s, got inf"),
        ("mapping=1,12", "--multipath mapping must be three numbers a,b,c (c in degrees)"),
        (
            "mapping=1,12,10,5",
            "--multipath mapping must be three numbers a,b,c (c in degrees), got '1,12,10,5'",
        ),
        ("mapping=0,12,10", "--multipath mapping a must be a number > 0 and <= 1000, got 0"),
        ("mapping=1,-1,10", "--multipath mapping b must be a number from 0 to 10000, got -1"),
        ("mapping=1,12,95", "--multipath mapping c_deg must be a number > 0 and <= 90 deg"),
        ("mapping=1,x,10", "--multipath mapping b must be a number from 0 to 10000, got 'x'"),
        ("a=2,mapping=1,12,10", "--multipath: a given twice"),
        ("tau_s=30,tau_s=40", "--multipath: tau_s given twice"),
    ],
)
def test_bad_spec_names_the_option_and_what_is_expected(text, message):
    with pytest.raises(InputError) as info:
        MultipathModel.from_spec(text)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_spec_errors_are_option_errors_relabelled():
    with pytest.raises(OptionError) as info:
        MultipathModel.from_spec("tau_s=-5", label="[truth] multipath")
    assert info.value.name == "tau_s" and str(info.value).startswith("[truth] multipath tau_s")


def test_library_checks_the_same_limits():
    with pytest.raises(OptionError, match="sigma_gm_m must be a number from 0 to 0.05 m, got 0.1"):
        MultipathModel(sigma_gm_m=0.1)
    with pytest.raises(OptionError, match="tau_s must be a number > 0"):
        MultipathModel(tau_s=0.0)
    with pytest.raises(OptionError, match="receiver_noise_m must be a number from 0 to 0.05 m"):
        preset("short").replace(receiver_noise_m=0.08)
    with pytest.raises(InputError, match="latitude"):  # the historical message is kept
        preset("short").replace(lat_deg=95.0)
    assert MultipathModel(tau_s=40).tau_s == 40.0  # integers become floats


def test_presets_are_unchanged_by_the_schema():
    """The demo's cache key is its digest: checking the fields must not change it."""
    assert preset("demo").digest() == (
        "002d85f6ca5ea9646156d032b720c017b7f8196426d178ab88c1cd17379c41ae"
    )


# ------------------------------------------------------------------ TOML
def _rich_scenario(tmp_path):
    return preset("demo").replace(
        name="toml-trip",
        duration_s=5400.0,
        interval_s=30.0,
        systems="GE",
        nav_path=str(tmp_path / "nav.rnx"),
        dual_antenna=False,
        receiver_noise_m=0.0007,
        baseline_enu_m=(1.5, -2.0, 0.25),
        seed=12345,
        multipath=MultipathModel(
            sigma_gm_m=0.0042,
            tau_s=123.5,
            sigma_wn_m=1.5e-3,
            a=1.0,
            b=12.0,
            c_deg=10.0,
            reflections=(Reflection("wall", 25.0, 0.3), Reflection("ground", 1.5, 0.1)),
        ),
        disturbances=(IonoDisturbance(600.0, 1200.0, 0.8, ("G05", "E11")),),
    )


def test_toml_round_trip(tmp_path):
    sc = _rich_scenario(tmp_path)
    p = tmp_path / "scenario.toml"
    p.write_text(sc.to_toml())
    back = Scenario.from_toml(p)
    assert back == sc
    assert back.digest() == sc.digest()
    assert Scenario.from_toml(p, base=preset("short")) == sc  # every field is written


def test_toml_layers_onto_the_base(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text(
        'duration_s = 3600\nnav_path = "brdc.rnx"\n\n[multipath]\ntau_s = 120\n'
        "mapping = [1, 12, 10]\n"
    )
    sc = Scenario.from_toml(p, base=preset("short"))
    short = preset("short")
    assert sc.duration_s == 3600.0 and sc.seed == short.seed and sc.name == short.name
    assert sc.multipath == MultipathModel(
        sigma_gm_m=short.multipath.sigma_gm_m,
        tau_s=120.0,
        sigma_wn_m=short.multipath.sigma_wn_m,
        a=1.0,
        b=12.0,
        c_deg=10.0,
    )
    assert sc.nav_path == str(tmp_path / "brdc.rnx")  # relative to the file


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("durations = 5\n", "unknown key 'durations'; expected one of name, lat_deg"),
        ("[multipath]\ntau = 5\n", "unknown key 'tau' in [multipath]"),
        ("[multipath]\ntau_s = 0\n", "[multipath] tau_s must be a number > 0 and <= 86400 s"),
        ("[multipath]\nsigma_gm_m = 0.2\n", "quarter wavelength"),
        ("[multipath]\nsigma_wn_m = 'x'\n", "[multipath] sigma_wn_m must be a number"),
        ("[multipath]\nmapping = [1, 2]\n", "[multipath] mapping must be three numbers"),
        ("[multipath]\nmapping = [1, 2, 0]\n", "[multipath] mapping c_deg must be a number > 0"),
        ("[multipath]\na = 2\nmapping = [1, 2, 3]\n", "[multipath] sets a twice"),
        ("multipath = 3\n", "multipath must be a table"),
        ("interval_s = -1\n", "interval_s must be a number > 0 and <= 3600 s, got -1"),
        ("seed = 1.5\n", "seed must be an integer"),
        ("dual_antenna = 1\n", "dual_antenna must be true or false, got 1"),
        ("baseline_enu_m = [1, 2]\n", "baseline_enu_m must be three numbers"),
        ("start_gps = '2020-13-01T00:00:00'\n", "start_gps must be an ISO date-time"),
        ("systems = 'R'\n", "systems must be 'G', 'E' or 'GE'"),
        ("lat_deg = 100\n", "latitude must be within [-90, 90] deg"),
        ("duration_s = 3e6\n", "more than 2e6 epochs"),
        ("[[disturbances]]\nstart_s = 1\n", "[[disturbances]] item 1 lacks duration_s"),
        (
            "[[disturbances]]\nstart_s = 1\nduration_s = 60\nroti_tecu_min = 0\n",
            "[[disturbances]] item 1 roti_tecu_min must be a number > 0",
        ),
        (
            "[[multipath.reflections]]\nkind = 'roof'\ndistance_m = 1\nalpha = 0.1\n",
            "[[multipath.reflections]] item 1 kind must be 'ground' or 'wall'",
        ),
        (
            "[[multipath.reflections]]\nkind = 'wall'\ndistance_m = 1\nalpha = 0.1\nh = 2\n",
            "unknown key 'h' in [[multipath.reflections]] item 1",
        ),
        ("x = [\n", "not valid TOML"),
    ],
)
def test_toml_errors_name_the_file_and_key(tmp_path, text, message):
    p = tmp_path / "bad.toml"
    p.write_text(text)
    with pytest.raises(InputError) as info:
        Scenario.from_toml(p)
    assert str(info.value).startswith(f"{p}: "), str(info.value)
    assert message in str(info.value)


def test_missing_toml_file(tmp_path):
    with pytest.raises(InputError, match="scenario file not found"):
        Scenario.from_toml(tmp_path / "nope.toml")


# ------------------------------------------------------------------ the truth model
def test_truth_model_of_the_demo():
    t = truth_model(preset("demo"))
    assert isinstance(t, GaussMarkovWhiteNoise)
    assert (t.sigma_gm_m, t.tau_s, t.dt_s) == (0.003, 30.0, 1.0)
    assert t.sigma_wn_m == pytest.approx(math.hypot(0.001, 0.0005), rel=1e-6)
    assert t.total_variance_m2 == pytest.approx(0.003**2 + 0.001**2 + 0.0005**2, rel=1e-6)


def test_truth_model_scales_the_unmapped_receiver_noise():
    sc = preset("short").replace(
        interval_s=30.0,
        receiver_noise_m=0.002,
        multipath=MultipathModel(sigma_gm_m=0.004, tau_s=300.0, sigma_wn_m=0.0, a=2.0, b=0.0),
    )
    t = truth_model(sc)
    assert t.sigma_wn_m == pytest.approx(0.001) and t.dt_s == 30.0 and t.tau_s == 300.0


def test_truth_model_refuses_reflections():
    mp = MultipathModel(reflections=(Reflection("wall", 5.0, 0.2),))
    sc = preset("short").replace(multipath=mp)
    with pytest.raises(InputError, match="reflections"):
        truth_model(sc)


def test_compare_to_truth():
    truth = GaussMarkovWhiteNoise(0.003, 30.0, 0.001, 1.0)
    same = compare_to_truth(truth, truth, 1e-3)
    assert same.covered and same.min_psd_ratio == pytest.approx(1.0)
    assert same.variance_ratio == pytest.approx(1.0) and same.band_hz == (1e-3, 0.5)
    low = compare_to_truth(GaussMarkovWhiteNoise(0.003, 30.0, 0.0009, 1.0), truth, 1e-3)
    assert not low.covered and low.f_at_min_hz == pytest.approx(0.5)
    big = compare_to_truth(GaussMarkovWhiteNoise(0.004, 60.0, 0.002, 1.0), truth, 1e-3)
    assert big.covered and big.tau_ratio == 2.0 and big.variance_ratio > 1.0
    with pytest.raises(InputError, match="sampling"):
        compare_to_truth(GaussMarkovWhiteNoise(0.003, 30.0, 0.001, 30.0), truth, 1e-3)
    with pytest.raises(InputError, match="band"):
        compare_to_truth(truth, truth, 0.6)


def test_mapped_df_series_has_the_truth_variance(tmp_path):
    """The pipeline's isolation + true mapping give the truth model's variance (loosely).

    The high-pass filter at f_c removes the GM power below f_c (about 11 % of
    it for tau = 30 s), and the receiver noise is below its zenith value at
    lower elevations: the ratio is expected a little under 1.
    """
    mp = MultipathModel.from_spec("sigma_gm_m=0.004,tau_s=30,sigma_wn_m=0.002,mapping=1,12,10")
    sc = preset("short").replace(multipath=mp, dual_antenna=False, duration_s=7200.0, seed=11)
    res = simulate(sc, tmp_path)
    arcs = find_arcs(
        read_obs(res.obs_paths[0]),
        ("L1C", "L2W"),
        orbit=read_orbit(res.nav_path),
        elevation_mask_deg=10.0,
    )
    series = isolate_dual_frequency(arcs, FC)
    mapped = ElevationMapping(mp.a, mp.b, mp.c_deg).apply(series.value_m, series.elevation_deg)
    truth = truth_model(sc)
    ratio = float(np.var(mapped)) / truth.total_variance_m2
    print(f"{series.n_arcs} arcs, {mapped.size} samples: variance ratio data/truth {ratio:.3f}")
    assert series.n_arcs >= 4
    assert 0.75 <= ratio <= 1.25


def test_same_spec_and_seed_same_truth(tmp_path):
    mp = MultipathModel.from_spec("sigma_gm_m=0.005,tau_s=90,mapping=1,15,12")
    sc = preset("short").replace(multipath=mp, dual_antenna=False, duration_s=600.0, seed=99)
    a, b = simulate(sc, tmp_path / "a"), simulate(sc, tmp_path / "b")
    np.testing.assert_array_equal(a.truth_m, b.truth_m)
    c = simulate(sc.replace(seed=100), tmp_path / "c")
    assert not np.array_equal(np.nan_to_num(a.truth_m), np.nan_to_num(c.truth_m))
