"""GPS seconds, calendar labels and leap seconds."""

from __future__ import annotations

import numpy as np
import pytest

from psdbound.io.timescales import (
    calendar_to_gps_s,
    gps_s_to_datetime64,
    gps_week_sow_to_gps_s,
    utc_to_gps_s,
)


def test_gps_epoch_and_week():
    assert calendar_to_gps_s(1980, 1, 6, 0, 0, 0.0) == 0.0
    # 2020-06-25 is GPS week 2111, Thursday (day 4)
    assert calendar_to_gps_s(2020, 6, 25, 0, 0, 0.0) == gps_week_sow_to_gps_s(2111, 4 * 86400)
    assert calendar_to_gps_s(20, 6, 25, 12, 30, 15.5) == calendar_to_gps_s(
        2020, 6, 25, 12, 30, 15.5
    )
    assert calendar_to_gps_s(99, 12, 31, 0, 0, 0) == calendar_to_gps_s(1999, 12, 31, 0, 0, 0)


@pytest.mark.parametrize(
    ("date", "leap"),
    [((2010, 3, 18), 15), ((2020, 6, 25), 18), ((2016, 12, 31), 17), ((2017, 1, 1), 18)],
)
def test_utc_to_gps_leap_seconds(date, leap):
    lab = calendar_to_gps_s(*date, 0, 0, 0.0)
    assert utc_to_gps_s(lab)[0] - lab == leap


def test_labels_round_trip():
    t = np.array([0.0, 1277078400.0, 1277078430.5])
    lab = gps_s_to_datetime64(t)
    assert str(lab[1]) == "2020-06-25T00:00:00.000000000"
    back = (lab - np.datetime64("1980-01-06T00:00:00", "ns")) / np.timedelta64(1, "s")
    np.testing.assert_array_equal(back, t)


def test_utc_to_gps_agrees_with_astropy_on_every_day_since_1981():
    """ERFA's table, read directly, gives astropy.time's GPS-UTC offset on every UTC day."""
    from astropy.time import Time

    days = np.arange(
        calendar_to_gps_s(1981, 1, 1, 0, 0, 0.0), calendar_to_gps_s(2025, 1, 1, 0, 0, 0.0), 86400.0
    )[::7]
    ours = utc_to_gps_s(days) - days
    labels = gps_s_to_datetime64(days).astype("datetime64[s]").astype(str)
    theirs = np.round(Time(list(labels), format="isot", scale="utc").gps - days)
    np.testing.assert_array_equal(ours, theirs)


def test_utc_after_the_table_warns_and_keeps_the_last_offset():
    from psdbound.common.notices import PsdboundWarning

    lab = calendar_to_gps_s(2060, 1, 1, 0, 0, 0.0)
    with pytest.warns(PsdboundWarning, match="later than the leap seconds known"):
        off = utc_to_gps_s(lab)[0] - lab
    assert off >= 18
