"""Epoch seconds written just below a full second (``29.9999999``) denote the full second.

Some receivers write the epoch on the half minute as ``29.9999999`` and the
one on the minute as ``59.9999999``: the reader rounds the seconds to the
label resolution (1 microsecond), carrying the minute over, so such a file
reads like the one written with ``30.0000000`` and ``0.0000000``; a repeat of
an epoch written once each way is a repeat (it used to crash the reader).
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from samples import V2_TEXT, moving_observations

from psdbound.common.notices import PsdboundWarning
from psdbound.errors import InputError
from psdbound.io import read_obs
from psdbound.io._epochs import fmt_date
from psdbound.io.write import format_obs_v3


def _text() -> str:
    return format_obs_v3(moving_observations(seed=7))


def _write(tmp_path, text: str, name: str = "f.rnx"):
    p = tmp_path / name
    p.write_text(text)
    return p


def _line_of(text: str, pattern: str) -> int:
    return next(i for i, ln in enumerate(text.split("\n"), 1) if re.search(pattern, ln))


def test_fmt_date_carries_the_minute_hour_and_day_over():
    assert fmt_date((2010, 3, 18, 0, 0, 29.9999999)) == "2010-03-18 00:00:30.000"
    assert fmt_date((10, 3, 18, 0, 59, 59.9999999)) == "2010-03-18 01:00:00.000"
    assert fmt_date((2020, 12, 31, 23, 59, 59.9999999)) == "2021-01-01 00:00:00.000"


def test_rinex3_seconds_below_the_full_second_read_as_it(tmp_path):
    text = _text()
    odd = text.replace("> 2020 06 25 00 05 30.0000000", "> 2020 06 25 00 05 29.9999999")
    odd = odd.replace("> 2020 06 25 00 07  0.0000000", "> 2020 06 25 00 06 59.9999999")
    assert odd.count("9.9999999") == 2
    ref = read_obs(_write(tmp_path, text, "ref.rnx"))
    obs = read_obs(_write(tmp_path, odd))
    np.testing.assert_array_equal(obs.t_gps_s, ref.t_gps_s)
    np.testing.assert_array_equal(obs.blocks["G"].values, ref.blocks["G"].values)
    assert obs.interval_s == 30.0 and not obs.warnings


def test_rinex2_seconds_below_the_full_second_read_as_it(tmp_path):
    # in 2010 a label's float64 resolution (1.2e-7 s) tells 29.9999999 from 30: rounded
    text = V2_TEXT.replace(" 20  6 25  0", " 10  3 18  0").replace(
        "2020     6    25", "2010     3    18"
    )
    odd = text.replace(" 10  3 18  0  0 30.0000000", " 10  3 18  0  0 29.9999999")
    odd = odd.replace(" 10  3 18  0  1  0.0000000", " 10  3 18  0  0 59.9999999")
    assert odd.count("9.9999999") == 2
    ref = read_obs(_write(tmp_path, text, "ref.10o"))
    obs = read_obs(_write(tmp_path, odd, "f.10o"))
    np.testing.assert_array_equal(obs.t_gps_s, ref.t_gps_s)
    np.testing.assert_array_equal(obs.t_gps_s - obs.t_gps_s[0], [0.0, 30.0, 60.0])


def _repeat_as_29_9999999(text: str, change: bool = False) -> tuple[str, int]:
    """Write the epoch 00:05:30 twice, first as 29.9999999; return text and the repeat's line."""
    a = _line_of(text, r"^> 2020 06 25 00 05 30\.")
    lines = text.split("\n")
    rep = lines[a - 1 : a + 2]
    rep[0] = rep[0].replace("30.0000000", "29.9999999")
    if change:
        rep[1] = rep[1][:14] + ("1" if rep[1][14] != "1" else "2") + rep[1][15:]
    lines[a - 1 : a - 1] = rep
    return "\n".join(lines), a + 3


def test_repeat_written_once_as_29_9999999_is_dropped_with_a_warning(tmp_path):
    text = _text()
    odd, k = _repeat_as_29_9999999(text)
    with pytest.warns(
        PsdboundWarning,
        match=rf"f\.rnx, line {k}: 1 epoch\(s\) repeated .*"
        r"2020-06-25 00:05:30\.000",
    ):
        obs = read_obs(_write(tmp_path, odd))
    ref = read_obs(_write(tmp_path, text, "ref.rnx"))
    np.testing.assert_array_equal(obs.t_gps_s, ref.t_gps_s)
    np.testing.assert_array_equal(obs.blocks["G"].values, ref.blocks["G"].values)
    assert obs.blocks["G"].sats == ref.blocks["G"].sats


def test_repeat_written_once_as_29_9999999_with_other_data_is_refused(tmp_path):
    odd, k = _repeat_as_29_9999999(_text(), change=True)
    with pytest.raises(
        InputError,
        match=rf"f\.rnx, line {k}: epoch 2020-06-25 00:05:30\.000 "
        rf"appears twice with different data \(lines {k - 3} "
        rf"and {k}\)",
    ):
        read_obs(_write(tmp_path, odd))
