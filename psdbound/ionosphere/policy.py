"""Which high-pass cutoff a fit uses: given, from the shipped map, or computed.

:func:`choose_cutoff` is the one place that decides; the fit pipeline and the
campaign call it with the receiver position and the data's year.

Sources
-------
``"given"``
    The user's ``f_c_hz``.
``"map"``
    The recommended cutoff of the nearest station of the shipped 2020 map
    (``psdbound/ionosphere/data/cutoff_map_2020.json``).
``"computed"``
    :func:`~psdbound.ionosphere.station_cutoffs` at the receiver for the
    data's year (PyIRI, nominal GPS, the first Monday of each month).
``"auto"``
    ``"given"`` when ``f_c_hz`` is set, else the thesis's Chicago 2020
    maximum :data:`THESIS_CUTOFF_HZ` with a warning that quotes the map.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from importlib import resources
from typing import Any

from psdbound.errors import InputError

__all__ = [
    "CUTOFF_SOURCES",
    "THESIS_CUTOFF_HZ",
    "CutoffChoice",
    "CutoffOptions",
    "choose_cutoff",
    "cutoff_computed",
    "cutoff_from_map",
]

#: The thesis's recommended cutoff for Chicago 2020 (maximum over the year), Hz.
THESIS_CUTOFF_HZ = 9.55e-4

CUTOFF_SOURCES = ("auto", "given", "map", "computed")

_MAP_FILE = "data/cutoff_map_2020.json"


@dataclass(frozen=True)
class CutoffOptions:
    """How to choose the ionosphere high-pass cutoff.

    Parameters
    ----------
    f_c_hz : float or None
        A given cutoff, Hz.
    source : {"auto", "given", "map", "computed"}
        See the module docstring.
    """

    f_c_hz: float | None = None
    source: str = "auto"


@dataclass(frozen=True)
class CutoffChoice:
    """The cutoff a fit uses and why.

    Attributes
    ----------
    f_c_hz : float
        Cutoff frequency, Hz.
    source : str
        Human-readable source (e.g. ``"map (nearest station SASK)"``).
    info : dict
        Details of the source (map station and distance, computed summary).
    warnings : tuple of str
        Warnings for the user (e.g. the thesis default was used).
    """

    f_c_hz: float
    source: str
    info: dict[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


def cutoff_from_map(lat_deg: float, lon_deg: float) -> tuple[float, dict[str, Any]]:
    """Recommended cutoff of the nearest station of the shipped 2020 cutoff map.

    Parameters
    ----------
    lat_deg, lon_deg : float
        Receiver position, degrees.

    Returns
    -------
    f_c_hz : float
        The nearest station's recommended (maximum) cutoff, Hz.
    info : dict
        Station, its distance (deg of arc), the map's days and settings.
    """
    from psdbound.ionosphere.stations import MAP_STATIONS, nearest_station

    text = resources.files("psdbound.ionosphere").joinpath(_MAP_FILE)
    table = json.loads(text.read_text())
    station, dist_deg = nearest_station(lat_deg, lon_deg, MAP_STATIONS)
    row = next(r for r in table["stations"] if r["name"] == station.name)
    return float(row["recommended_f_c_hz"]), {
        "station": station.name,
        "station_distance_deg": float(dist_deg),
        "map": f"psdbound/ionosphere/{_MAP_FILE}",
        "map_days": table["days"],
        "map_note": table["note"],
    }


def cutoff_computed(lat_deg: float, lon_deg: float, year: int) -> tuple[float, dict[str, Any]]:
    """Compute the cutoff at a position (PyIRI, nominal GPS, first Monday of each month).

    Parameters
    ----------
    lat_deg, lon_deg : float
        Receiver position, degrees.
    year : int
        Year of the data.

    Returns
    -------
    f_c_hz : float
        Recommended (maximum over the days) cutoff, Hz.
    info : dict
        ``{"computed": summary}`` with the station summary.
    """
    from psdbound.ionosphere.batch import select_days, station_cutoffs

    res = station_cutoffs(lat_deg, lon_deg, select_days(year), name="receiver", workers=2)
    summ = res.summary()
    return float(summ["recommended_f_c_hz"]), {"computed": summ}


def choose_cutoff(
    options: CutoffOptions,
    *,
    lat_deg: float | None,
    lon_deg: float | None,
    year: int,
) -> CutoffChoice:
    """Choose the cutoff for a receiver position and year.

    Parameters
    ----------
    options : CutoffOptions
        Given cutoff and source.
    lat_deg, lon_deg : float or None
        Receiver position, degrees (None when unknown).
    year : int
        Year of the data (for ``source="computed"``).

    Returns
    -------
    CutoffChoice

    Raises
    ------
    InputError
        Unknown source, ``"given"`` without a cutoff, ``"map"`` or
        ``"computed"`` without a position.
    """
    src = options.source
    if src not in CUTOFF_SOURCES:
        raise InputError(
            f"unknown cutoff source {src!r}; use {', '.join(CUTOFF_SOURCES)}"
        )
    if src == "auto":
        src = "given" if options.f_c_hz is not None else "default"
    if src == "given":
        if options.f_c_hz is None:
            raise InputError("cutoff source 'given' needs --cutoff-hz")
        return CutoffChoice(float(options.f_c_hz), "given")
    have_pos = lat_deg is not None and lon_deg is not None
    if src in ("map", "computed") and not have_pos:
        raise InputError(f"cutoff source {src!r} needs a receiver position")
    if src == "map":
        f_c, info = cutoff_from_map(lat_deg, lon_deg)
        return CutoffChoice(f_c, f"map (nearest station {info['station']})", info)
    if src == "computed":
        f_c, info = cutoff_computed(lat_deg, lon_deg, year)
        return CutoffChoice(f_c, f"computed (PyIRI, {year})", info)
    note = ""
    if have_pos:
        f_map, info = cutoff_from_map(lat_deg, lon_deg)
        note = (
            f"; the 2020 cutoff map gives {f_map:.3g} Hz (nearest station {info['station']}), "
            "about 10x higher because Lomb-Scargle leakage of the satellite passes sets its "
            "40 dB point - use --cutoff-source map to apply it"
        )
    warning = f"no cutoff given: used the thesis's Chicago 2020 value {THESIS_CUTOFF_HZ:g} Hz{note}"
    return CutoffChoice(
        THESIS_CUTOFF_HZ, "default (thesis Chicago 2020 maximum)", {}, (warning,)
    )
