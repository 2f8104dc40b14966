"""psdbound.bound_series: what it accepts, what it refuses (one line naming the item), its f_min."""

from __future__ import annotations

import numpy as np
import pytest

import psdbound
from psdbound.errors import InputError
from psdbound.spectra import estimate_psd
from psdbound.spectra.bands import resolved_from_hz
from psdbound.spectra.series import split_stretches

RNG_SEED = 11


def _white(n: int, seed: int = RNG_SEED) -> np.ndarray:
    return np.random.default_rng(seed).normal(0.0, 0.002, n)


@pytest.mark.parametrize(
    ("series", "match"),
    [
        ([np.r_[_white(300), np.inf, _white(300)]], r"series 0: infinite value at index 300"),
        ([_white(300), _white(300) + 1j * _white(300)], r"series 1: .*complex"),
        ([np.array(["a"] * 100)], r"series 0: samples must be real numbers"),
        ([np.zeros((3, 100)) + _white(100)], r"series 0: must be 1-D"),
        ([], r"no stretch of at least 64"),
        ([np.full(300, np.nan)], r"no stretch of at least 64"),
        ([_white(30)], r"1 stretch\(es\) shorter than 64 samples left out \(30 samples\)"),
    ],
)
def test_bad_series_are_named(series: list, match: str) -> None:
    with pytest.raises(InputError, match=match):
        psdbound.bound_series(series, 1.0)


@pytest.mark.parametrize("dt_s", [0.0, -1.0, np.nan, np.inf])
def test_bad_sampling_interval_is_named(dt_s: float) -> None:
    with pytest.raises(InputError, match="sampling interval"):
        psdbound.bound_series([_white(300)], dt_s)


def test_nan_gaps_split_and_short_pieces_are_reported() -> None:
    x = np.r_[_white(200, 1), np.nan, _white(40, 2), np.nan, np.nan, _white(150, 3)]
    stretches, notes = split_stretches(x, min_samples=64)
    assert [s.size for s in stretches] == [200, 150]
    assert len(notes) == 1 and "40 samples" in notes[0]


def test_masked_samples_are_gaps_not_data() -> None:
    # np.asarray keeps a masked sample's value: a glitch masked by the user
    # (here 1 km) must split the stretch as NaN does, one series or several
    x = _white(400, 4)
    x[190:210] = 1e3
    mask = np.zeros(x.size, dtype=bool)
    mask[190:210] = True
    one = np.ma.masked_array(x, mask=mask)
    for given in (one, [one, one], np.ma.stack([one, one])):
        stretches, _ = split_stretches(given, min_samples=64)
        assert [s.size for s in stretches] == [190, 190] * (1 if given is one else 2)
        assert max(float(np.max(np.abs(s))) for s in stretches) < 1.0
    res = psdbound.bound_series([one, one, one], 1.0)
    assert len(res.psds) == 6
    assert res.bound.sigma_gm_m + res.bound.sigma_wn_m < 1.0


def test_two_dimensional_array_is_one_window_per_row() -> None:
    rows = np.stack([_white(256, seed) for seed in range(4)])
    stretches, _ = split_stretches(rows, min_samples=64)
    assert len(stretches) == 4
    np.testing.assert_array_equal(stretches[2], rows[2])


@pytest.mark.parametrize(
    ("estimator", "options"),
    [
        ("multitaper", {}),
        ("welch", {}),
        ("blackman-tukey", {}),  # the thesis's full-length lags: nu_0 about 1.14
        ("blackman-tukey", {"max_lag_fraction": 0.1}),
    ],
)
def test_f_min_is_clear_of_the_emptied_zero_frequency(estimator: str, options: dict) -> None:
    """Every estimator is stated from at least 1 / T plus half its bandwidth (T = 600 s)."""
    x = _white(600)
    psd = estimate_psd(x, 1.0, method=estimator, **options)
    bandwidth_hz = float(np.median(np.atleast_1d(psd.dof))) / (2.0 * 600.0)
    if estimator == "multitaper":
        bandwidth_hz = 2.0 * float(psd.params["bandwidth_hz"])
    assert resolved_from_hz(psd) >= 1.0 / 600.0 + 0.5 * bandwidth_hz - 1e-12
    res = psdbound.bound_series(
        [x] + [_white(600, s) for s in range(5)],
        1.0,
        estimator=estimator,
        estimator_options=options,
    )
    assert res.f_min_hz >= 1.0 / 600.0


@pytest.mark.parametrize(
    ("options", "match"),
    [
        ({"clusters": [0.5] * 6}, "clusters must be integer labels"),
        ({"clusters": ["a"] * 6}, "clusters must be integer labels"),
        ({"cluster_correlation": 0.5}, "cluster_correlation 0.5 needs clusters"),
        ({"f_min_hz": float("nan")}, "f_min_hz must be a number > 0 Hz, got nan"),
        ({"tau_max_s": float("nan")}, "tau_max_s must be a number > 0 s, got nan"),
        ({"deviation_model": "x"}, "choose from auto, level, tilt"),
    ],
)
def test_bad_options_are_named(options: dict, match: str) -> None:
    with pytest.raises(InputError, match=match):
        psdbound.bound_series([_white(300, s) for s in range(6)], 1.0, **options)


def test_sampling_interval_must_be_a_number() -> None:
    with pytest.raises(InputError, match="sampling interval dt_s must be a number > 0 s, got '1'"):
        psdbound.bound_series([_white(300)], "1")  # type: ignore[arg-type]
    labels = psdbound.bound_series(
        [_white(300, s) for s in range(6)], np.float32(1.0), clusters=[0.0, 1.0] * 3
    )
    assert labels.verdict in ("bounded", "not-bounded")


def test_a_given_f_min_below_the_resolved_frequency_is_raised_with_a_note() -> None:
    x = [_white(600, s) for s in range(8)]
    res = psdbound.bound_series(x, 1.0, f_min_hz=1e-5)
    assert res.f_min_hz > 1.0 / 600.0
    assert any("f_min_hz 1e-05 Hz lies below" in n for n in res.notes)
    assert "f_min_hz" not in " ".join(psdbound.bound_series(x, 1.0).notes)
    above = psdbound.bound_series(x, 1.0, f_min_hz=0.02)
    assert above.f_min_hz == pytest.approx(0.02) and not above.notes


def test_windows_that_do_not_resolve_the_lowest_stated_frequency_are_noted():
    # f_min comes from the longest window; a short window of another shape is not seen
    # below its own resolution (the slowuneq class of benchmarks/bound_coverage.py)
    lengths = (900, 1800, 3600, 3600)
    windows = [_white(n, seed) for seed, n in enumerate(lengths)]
    res = psdbound.bound_series(windows, 1.0)
    resolved = [resolved_from_hz(p) for p in res.psds]
    assert res.f_min_hz == pytest.approx(min(resolved))
    (note,) = [n for n in res.notes if "windows resolve only from" in n]
    assert note.startswith("2 of 4 windows resolve only from 0.005556 Hz")
    assert f"give f_min_hz={max(resolved):.4g}" in note
    again = psdbound.bound_series(windows, 1.0, f_min_hz=max(resolved))
    assert again.f_min_hz == pytest.approx(max(resolved))
    assert not [n for n in again.notes if "windows resolve only from" in n]
    same = psdbound.bound_series([_white(1800, seed) for seed in range(4)], 1.0)
    assert not [n for n in same.notes if "windows resolve only from" in n]


@pytest.mark.parametrize(
    ("series", "options", "words"),
    [
        (None, {}, "series must be a 1-D array or a list of 1-D arrays"),
        (3.0, {}, "series must be a 1-D array or a list of 1-D arrays"),
        ({"a": np.zeros(100)}, {}, "got dict"),
        ([1.0, np.zeros(100)], {}, "series mixes numbers and arrays"),
        ("white", {"confidence_level": "0.9"}, "confidence_level must be a number > 0 and < 1"),
        ("white", {"coverage": None}, "coverage must be a number"),
        ("white", {"min_samples": 64.5}, "min_samples must be an integer >= 16"),
        ("white", {"bands_per_decade": 2.5}, "bands_per_decade must be an integer"),
        ("white", {"estimator_options": "x"}, "estimator_options must be a dict"),
        ("white", {"tau_max_s": 0.3}, "tau_max_s 0.3 s is below the shortest time constant"),
        ("white", {"estimator_options": {"k": 2.5}}, "options.k must be an integer"),
        ("white", {"estimator_options": {"adaptive": "x"}}, "options.adaptive must be true"),
        ("white", {"estimator_options": {"foo": 1}}, "names of multitaper options"),
        ("white", {"estimator": "nope"}, "estimator must be one of"),
    ],
)
def test_bad_containers_and_option_types_are_input_errors(series, options, words):
    """Issue-27 library entry: every bad input is an InputError that says what is expected."""
    if isinstance(series, str):
        series = [_white(512, seed) for seed in range(4)]
    with pytest.raises(InputError, match=words):
        psdbound.bound_series(series, 1.0, **options)


def test_a_float32_interval_and_a_generator_give_the_same_bound():
    xs = [_white(512, seed) for seed in range(6)]
    a = psdbound.bound_series(xs, 1.0)
    b = psdbound.bound_series(iter(xs), np.float32(1.0))
    assert (a.bound.sigma_gm_m, a.bound.tau_s) == (b.bound.sigma_gm_m, b.bound.tau_s)


def test_a_removed_mean_is_said():
    """Each stretch's mean is removed before its spectrum: a bias is not bounded, and says so."""
    xs = [_white(512, seed) for seed in range(6)]
    plain = psdbound.bound_series(xs, 1.0)
    biased = psdbound.bound_series([x + 1.0 for x in xs], 1.0)
    assert biased.bound.sigma_gm_m == pytest.approx(plain.bound.sigma_gm_m, rel=1e-9)
    assert not any("mean" in n for n in plain.notes)
    assert any("not that bias" in n for n in biased.notes)
