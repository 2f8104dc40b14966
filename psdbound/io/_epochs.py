"""Epoch dates of RINEX observation data sections: range checks, labels, display.

RINEX writes the seconds of an epoch with seven decimals, and some receivers
write an epoch on the full second as ``29.9999999`` (or ``59.9999999``, the
minute then carries over). An epoch label is a float64 count of GPS seconds
(about 1e9 s), whose resolution is 1.2e-7 to 2.4e-7 s, coarser than the
seventh decimal: the seconds are rounded to :data:`EPOCH_RESOLUTION_S`
before the label is formed, so that ``29.9999999`` denotes the same instant
as ``30.0000000`` whatever the date, and a date is displayed with its minute,
hour and day carried over.
"""

from __future__ import annotations

import numpy as np

from psdbound.io.timescales import calendar_to_gps_s

#: Years accepted in epochs (4-digit; RINEX 2 two-digit years map to 1980-2079).
YEAR_RANGE = (1980, 2099)
#: Resolution of an epoch label, s: the seconds of an epoch are rounded to it.
EPOCH_RESOLUTION_S = 1e-6
_DECIMALS = 6


def full_year(y: int | float) -> int:
    """The four-digit year of a RINEX year field (two digits: 1980-2079)."""
    y = int(y)
    if 0 <= y < 100:
        return y + 2000 if y < 80 else y + 1900
    return y


def fmt_date(d: tuple | np.ndarray) -> str:
    """``yyyy-mm-dd hh:mm:ss.sss`` of an epoch's fields, the seconds rounded and carried over.

    Parameters
    ----------
    d : sequence of 6 numbers
        Year, month, day, hour, minute, second (as read; in range).

    Returns
    -------
    str
        The date the fields denote, e.g. ``2010-03-18 00:01:00.000`` for
        minute 0 and seconds ``59.9999999``.
    """
    y, mo, dd, h, mi, s = (float(v) for v in d)
    day = np.datetime64(f"{full_year(y):04d}-{int(mo):02d}-{int(dd):02d}", "ms")
    t = day + np.timedelta64(int(h) * 3600 + int(mi) * 60, "s")
    t = t + np.timedelta64(round(s * 1e3), "ms")
    return str(t).replace("T", " ")


def check_dates(dates: np.ndarray, time_system: str, version3: bool) -> int | None:
    """Index of the first epoch with a calendar field out of range (None if all are fine).

    Parameters
    ----------
    dates : ndarray of float64, shape (n_epoch, 6)
        Year, month, day, hour, minute, second of every epoch.
    time_system : str
        The header's time system (UTC and GLO epochs may hold a leap second).
    version3 : bool
        Four-digit years (RINEX 3); else two-digit years.

    Returns
    -------
    int or None
    """
    y, mo, d, h, mi, s = dates.T
    if not version3:
        y = np.where(y < 80, y + 2000, np.where(y < 100, y + 1900, -1))
    sec_max = 61.0 if time_system in ("UTC", "GLO") else 60.0
    bad = (y < YEAR_RANGE[0]) | (y > YEAR_RANGE[1]) | (mo < 1) | (mo > 12) | (d < 1)
    bad |= (h < 0) | (h > 23) | (mi < 0) | (mi > 59) | ~(s >= 0) | ~(s < sec_max)
    ok_month = ~bad
    months = (np.where(ok_month, y, 1970) - 1970) * 12 + np.where(ok_month, mo, 1) - 1
    start = months.astype("datetime64[M]")
    length = ((start + 1).astype("datetime64[D]") - start.astype("datetime64[D]")).astype(int)
    bad |= d > length
    return int(np.argmax(bad)) if bad.any() else None


def date_labels(dates: np.ndarray) -> np.ndarray:
    """Calendar labels (seconds in the file's time scale) of checked epoch dates.

    The seconds are rounded to :data:`EPOCH_RESOLUTION_S` first (``59.9999999``
    is the next minute).

    Parameters
    ----------
    dates : ndarray of float64, shape (n_epoch, 6)
        Year, month, day, hour, minute, second, in range (:func:`check_dates`).

    Returns
    -------
    ndarray of float64, shape (n_epoch,)
    """
    fields = (dates[:, c].astype(np.int64) for c in range(5))
    return calendar_to_gps_s(*fields, np.round(dates[:, 5], _DECIMALS))
