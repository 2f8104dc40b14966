"""Stations: the worldwide cutoff map's, position checks and nearest-station lookup.

The 20 stations of the thesis's appendix C (table C.1, docs/method/cutoff.rst,
step 7), plus the thesis's Chicago rooftop site (not part of the map);
:func:`validate_station` checks a position for every entry point,
:func:`nearest_station` finds the map station nearest a receiver.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from psdbound.errors import InputError

__all__ = [
    "CHICAGO",
    "MAP_STATIONS",
    "Station",
    "great_circle_deg",
    "nearest_station",
    "validate_station",
]


class Station(NamedTuple):
    """A named station position (geodetic degrees)."""

    name: str
    lat_deg: float
    lon_deg: float


#: The thesis's 20 reference stations (table C.1).
MAP_STATIONS: tuple[Station, ...] = (
    Station("LC4K", 26.91, 80.96),
    Station("CEDU", -31.87, 133.81),
    Station("DGAR", -7.27, 72.37),
    Station("PALM", -64.78, -64.05),
    Station("MAJU", 7.12, 171.36),
    Station("NRIL", 69.36, 88.36),
    Station("CAS1", -66.28, 110.52),
    Station("REUN", -21.21, 55.57),
    Station("ZAMB", -15.43, 28.31),
    Station("ISPA", -27.12, -109.34),
    Station("STK2", 43.53, 141.84),
    Station("DAV1", -68.58, 77.97),
    Station("KOKV", 22.13, -159.66),
    Station("YKRO", 6.87, -5.24),
    Station("UFPR", -25.45, -49.23),
    Station("LAMA", 53.89, 20.67),
    Station("SASK", 52.20, -106.40),
    Station("PIE1", 34.30, -108.12),
    Station("LAUT", -17.61, 177.45),
    Station("LMMF", 14.59, -61.00),
)

#: The thesis's rooftop site in Chicago (section 4.1).
CHICAGO = Station("CHICAGO", 41.84, -87.63)


def validate_station(lat_deg: float, lon_deg: float) -> tuple[float, float]:
    """Check a station position; return latitude and longitude in (-180, 180].

    Parameters
    ----------
    lat_deg, lon_deg : float
        Geodetic latitude and longitude, degrees.

    Returns
    -------
    tuple of float
        ``(lat_deg, lon_deg)`` with the longitude wrapped to (-180, 180].

    Raises
    ------
    InputError
        If the latitude is outside [-90, 90], the longitude outside
        [-180, 360], or either is not a finite number.
    """
    try:
        lat, lon = float(lat_deg), float(lon_deg)
    except (TypeError, ValueError):
        raise InputError(f"station position ({lat_deg!r}, {lon_deg!r}) is not numeric") from None
    if not np.isfinite(lat) or not -90.0 <= lat <= 90.0:
        raise InputError(f"latitude {lat_deg} deg is out of range: expected -90 to 90 degrees")
    if not np.isfinite(lon) or not -180.0 <= lon <= 360.0:
        raise InputError(f"longitude {lon_deg} deg is out of range: expected -180 to 360 degrees")
    lon = (lon + 180.0) % 360.0 - 180.0
    if lon == -180.0:
        lon = 180.0
    return lat, lon


def great_circle_deg(lat1_deg: float, lon1_deg: float, lat2_deg, lon2_deg):  # noqa: ANN001, ANN201
    """Great-circle central angle between points, degrees (haversine; arrays broadcast)."""
    p1, p2 = np.radians(lat1_deg), np.radians(lat2_deg)
    dl = np.radians(np.asarray(lon2_deg) - lon1_deg)
    a = np.sin((p2 - p1) / 2.0) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2.0) ** 2
    return np.degrees(2.0 * np.arcsin(np.sqrt(np.clip(a, 0.0, 1.0))))


def nearest_station(
    lat_deg: float, lon_deg: float, stations: Sequence[Station] = MAP_STATIONS
) -> tuple[Station, float]:
    """Find the station nearest a position (great circle on a sphere).

    Parameters
    ----------
    lat_deg, lon_deg : float
        Position, degrees.
    stations : sequence of Station, default the 20 map stations
        Candidates.

    Returns
    -------
    station : Station
        Nearest station.
    distance_deg : float
        Central angle to it, degrees (times ~111.2 km for kilometres).

    Raises
    ------
    InputError
        For a latitude outside [-90, 90] or an empty station list.
    """
    lat, lon = validate_station(lat_deg, lon_deg)
    if not stations:
        raise InputError("no station to choose from")
    d = great_circle_deg(lat, lon, [s.lat_deg for s in stations], [s.lon_deg for s in stations])
    j = int(np.argmin(d))
    return stations[j], float(d[j])
