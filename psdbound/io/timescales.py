"""Time scales used by the readers.

psdbound carries every epoch as **GPS seconds**: seconds elapsed in the GPS
time scale since 1980-01-06T00:00:00 GPS (float64, name suffix ``_gps_s``).
The GPS time scale has no leap seconds, so differences are true elapsed
seconds. Calendar labels in other scales are converted here:

* GPS and Galileo system time (GST) labels: GST is steered to GPS time and
  labelled identically by RINEX, so the label converts directly.
* UTC and GLONASS time (UTC + 3 h) labels: converted with ERFA's leap
  second table, the one astropy's time scales use (GPS - UTC = TAI - UTC -
  19 s).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import TAI_MINUS_GPS_S

__all__ = [
    "GPS_EPOCH",
    "SECONDS_PER_WEEK",
    "calendar_to_gps_s",
    "gps_s_to_datetime64",
    "utc_to_gps_s",
    "gps_week_sow_to_gps_s",
]

GPS_EPOCH = np.datetime64("1980-01-06T00:00:00", "ns")
SECONDS_PER_WEEK = 604800.0
_GPS_EPOCH_DAY = np.datetime64("1980-01-06", "D")


def calendar_to_gps_s(
    year: ArrayLike,
    month: ArrayLike,
    day: ArrayLike,
    hour: ArrayLike,
    minute: ArrayLike,
    second: ArrayLike,
) -> NDArray[np.float64]:
    """Convert calendar labels *in the GPS time scale* to GPS seconds.

    Parameters
    ----------
    year, month, day, hour, minute : array_like of int
        Calendar fields; two-digit years are mapped to 1980-2079.
    second : array_like of float
        Seconds of the minute.

    Returns
    -------
    ndarray of float64
        Seconds since 1980-01-06T00:00:00 GPS.
    """
    y = np.asarray(year, dtype=np.int64)
    y = np.where(y < 80, y + 2000, np.where(y < 100, y + 1900, y))
    m = np.asarray(month, dtype=np.int64)
    d = np.asarray(day, dtype=np.int64)
    months = (y - 1970) * 12 + (m - 1)
    days = months.astype("datetime64[M]").astype("datetime64[D]") + (d - 1)
    day_number = (days - _GPS_EPOCH_DAY).astype(np.int64)
    return (
        day_number * 86400.0
        + np.asarray(hour, dtype=np.float64) * 3600.0
        + np.asarray(minute, dtype=np.float64) * 60.0
        + np.asarray(second, dtype=np.float64)
    )


def gps_s_to_datetime64(t_gps_s: ArrayLike) -> NDArray[np.datetime64]:
    """Return GPS-time calendar labels (``datetime64[ns]``) of GPS seconds.

    The labels are in the GPS time scale (not UTC).
    """
    t = np.asarray(t_gps_s, dtype=np.float64)
    return GPS_EPOCH + np.round(t * 1e9).astype("timedelta64[ns]")


def utc_to_gps_s(t_utc_label_gps_s: ArrayLike) -> NDArray[np.float64]:
    """Convert UTC calendar labels (encoded as if GPS seconds) to GPS seconds.

    Parameters
    ----------
    t_utc_label_gps_s : array_like of float
        The output of :func:`calendar_to_gps_s` applied to UTC labels.

    Returns
    -------
    ndarray of float64
        True GPS seconds, i.e. the labels plus the GPS-UTC offset in force at
        each epoch: TAI-UTC from the leap-second table of ERFA (``erfa.dat``,
        the table astropy's time scales use) minus the constant TAI-GPS of
        19 s.

    Warns
    -----
    PsdboundWarning
        Epochs later than the table can vouch for (ERFA's "dubious year"):
        converted with the last known offset.
    """
    import warnings

    import erfa  # the leap seconds without astropy.time's 0.3 s import

    lab = np.atleast_1d(np.asarray(t_utc_label_gps_s, dtype=np.float64))
    # a leap second is inserted at the end of a UTC day, so the offset is that of the
    # day's start: look each distinct day up once (a navigation file has thousands of
    # epochs and one or two days)
    days, inverse = np.unique(np.floor(lab / 86400.0), return_inverse=True)
    ymd = gps_s_to_datetime64(days * 86400.0).astype("datetime64[D]")
    year = ymd.astype("datetime64[Y]").astype(int) + 1970
    month = ymd.astype("datetime64[M]").astype(int) % 12 + 1
    day = (ymd - ymd.astype("datetime64[M]")).astype(int) + 1
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        tai_utc_s = erfa.dat(year, month, day, 0.0)
    if caught:
        from psdbound.common.notices import warn

        warn(
            f"UTC epochs up to {str(ymd[-1])} are later than the leap seconds known to "
            "ERFA: converted with the last known GPS-UTC offset"
        )
    offset = np.atleast_1d(tai_utc_s - TAI_MINUS_GPS_S)[inverse.reshape(lab.shape)]
    return lab + np.round(offset)


def gps_week_sow_to_gps_s(week: ArrayLike, sow: ArrayLike) -> NDArray[np.float64]:
    """Convert a (continuous) GPS week number and seconds of week to GPS seconds."""
    return np.asarray(week, dtype=np.float64) * SECONDS_PER_WEEK + np.asarray(sow, dtype=np.float64)
