"""A minimum window the spectral test cannot use: an error naming the option, early."""

from __future__ import annotations

import pytest

import psdbound
from psdbound.errors import InputError


def test_too_short_min_window_names_the_option_and_the_remedy():
    # the demo is sampled at 1 s: the spectral test needs 68 samples = 67 s
    with pytest.raises(
        InputError,
        match=r"--min-window-s .*= 30 s is shorter than the spectral "
        r"stationarity test needs at 1 s sampling \(68 samples = 67 s\): give "
        r"--min-window-s 67 or more, or --stationarity thesis",
    ):
        psdbound.fit(min_window_s=30.0)


def test_thesis_test_accepts_a_short_min_window():
    res = psdbound.fit(min_window_s=30.0, test="thesis", windows="slide", rule="envelope")
    assert res.document["windows"]["count"] > 0
    assert not any("minimum window raised" in w for w in res.warnings)
