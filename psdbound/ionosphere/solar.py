"""Solar activity of a date: the monthly mean F10.7 shipped with the package.

The cutoff map has one layer per solar activity level (a solar-minimum and a
solar-maximum year); the policy places the data's date between them by its
F10.7. ``data/f107_monthly.json`` holds the monthly mean observed 10.7 cm
flux (Penticton, sfu) from NOAA SWPC's observed solar-cycle indices, October
2004 to September 2024. Outside that span there is no value
(:func:`monthly_f107` returns None) and the caller decides (the policy takes
the solar-maximum layer, the conservative choice for the residual
criterion, whose cutoff grows with the delay).
"""

from __future__ import annotations

import datetime as _dt
import functools
import json
from importlib import resources
from typing import Any

from psdbound.errors import InputError

__all__ = ["F107_FILE", "annual_f107", "f107_of", "f107_table", "monthly_f107"]

#: Package data file of the monthly F10.7 table.
F107_FILE = "data/f107_monthly.json"


@functools.lru_cache(maxsize=1)
def f107_table() -> dict[str, Any]:
    """Return the shipped monthly F10.7 table (``first_month``, ``values_sfu``, provenance)."""
    text = resources.files("psdbound.ionosphere").joinpath(F107_FILE).read_text()
    return json.loads(text)


def _index(year: int, month: int) -> int:
    table = f107_table()
    y0, m0 = (int(v) for v in table["first_month"].split("-"))
    return (year - y0) * 12 + (month - m0)


def monthly_f107(year: int, month: int) -> float | None:
    """Monthly mean F10.7 of a month, sfu, or None outside the table.

    Parameters
    ----------
    year : int
        Year.
    month : int
        Month, 1-12.

    Returns
    -------
    float or None
    """
    if not 1 <= month <= 12:
        raise InputError(f"month {month} is not 1-12")
    i = _index(year, month)
    values = f107_table()["values_sfu"]
    return float(values[i]) if 0 <= i < len(values) else None


def annual_f107(year: int) -> float | None:
    """Mean of the monthly F10.7 of a year that the table holds, sfu (None if none).

    Parameters
    ----------
    year : int
        Year.

    Returns
    -------
    float or None
        Mean over the months of ``year`` in the table (all 12 inside the
        table's span; fewer at its ends).
    """
    vals = [v for m in range(1, 13) if (v := monthly_f107(year, m)) is not None]
    return sum(vals) / len(vals) if vals else None


def f107_of(date: _dt.date | None, year: int | None) -> tuple[float | None, str]:
    """F10.7 of a date (its month) or, without one, of a year (annual mean).

    Parameters
    ----------
    date : datetime.date or None
        Day of the data.
    year : int or None
        Year of the data (used when ``date`` is None).

    Returns
    -------
    f107_sfu : float or None
        None when the table does not cover it.
    label : str
        What the value is (``"monthly mean 2020-06"``, ``"annual mean 2020"``).
    """
    if date is not None:
        return monthly_f107(date.year, date.month), f"monthly mean {date:%Y-%m}"
    if year is not None:
        return annual_f107(year), f"annual mean {year}"
    return None, "no date"
