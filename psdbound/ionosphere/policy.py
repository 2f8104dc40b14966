"""Which high-pass cutoff a fit uses: from the map, computed, given, or the thesis's.

:func:`choose_cutoff` is the one place that decides; the fit pipeline and the
campaign call it with the receiver position and the data's year (and, when
known, date).

Sources
-------
``"auto"`` (default)
    ``"given"`` when ``f_c_hz`` is set, else ``"map"`` when the position is
    known, else the thesis's constant with a warning.
``"map"``
    The shipped cutoff map (``psdbound/ionosphere/data/cutoff_map.json``,
    :mod:`~psdbound.ionosphere.worldmap`): bilinear in position on its
    grid, linear in the F10.7 of the data's month (or year) between its
    solar-minimum and solar-maximum layers. ``CutoffChoice.source`` names
    the grid cell and the flux; ``info`` holds the corner values, the
    layers' values, the nearest reference station and the map's
    provenance.
``"computed"``
    :func:`~psdbound.ionosphere.station_cutoffs` at the receiver, the
    data's year (the first Monday of each month, the thesis's days) and the
    F10.7 of its month or year (about 10 s on 2 cores).
``"given"``
    The user's ``f_c_hz``.
``"thesis"``
    The thesis's Chicago 2020 maximum :data:`THESIS_CUTOFF_HZ`, only on
    request.

The map and the computation use the residual criterion
(:mod:`~psdbound.ionosphere.residual`): the ionosphere the fit's
high-pass leaves is ``margin_db`` (40 dB) below ``mp_sigma_m`` (1 mm). A
different margin or reference is read from the margins the map records
(20-50 dB below 1 mm, interpolated in log f_c), or computed. When the
sampling interval of the data is given, a cutoff leaving less than a factor
4 below Nyquist is warned about (the verdict's band rule).
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import math
from dataclasses import dataclass, field
from typing import Any

from psdbound.constants import F_L1_HZ, F_L2_HZ
from psdbound.errors import InputError
from psdbound.ionosphere.names import (
    DEFAULT_MARGIN_DB,
    DEFAULT_MP_SIGMA_M,
    NOMINAL_SYSTEMS,
    THESIS_CHICAGO_2020_HZ,
)

__all__ = [
    "CUTOFF_SOURCES",
    "EXTRAPOLATION_WARNING",
    "MIN_BAND_RATIO",
    "THESIS_CUTOFF_HZ",
    "CutoffChoice",
    "CutoffOptions",
    "choose_cutoff",
    "cutoff_computed",
    "cutoff_from_map",
    "iono_coefficient_ratio",
]

#: The thesis's recommended cutoff for Chicago 2020 (maximum over the year), Hz.
THESIS_CUTOFF_HZ = THESIS_CHICAGO_2020_HZ["max"]

CUTOFF_SOURCES = ("auto", "given", "map", "computed", "thesis")

#: Nyquist / f_c below which the band left for the bound is too narrow (the verdict's rule).
MIN_BAND_RATIO = 4.0
#: F10.7 above this multiple of the map's solar-maximum layer is warned about.
EXTRAPOLATION_WARNING = 1.2


@dataclass(frozen=True)
class CutoffOptions:
    """How to choose the ionosphere high-pass cutoff.

    Parameters
    ----------
    f_c_hz : float or None
        A given cutoff, Hz.
    source : {"auto", "given", "map", "computed", "thesis"}
        See the module docstring.
    mp_sigma_m : float, default 1e-3
        Reference multipath sigma of the residual criterion (per carrier,
        the bound's units), m.
    margin_db : float, default 40
        How far below ``mp_sigma_m`` the residual ionosphere must stay, dB.
    """

    f_c_hz: float | None = None
    source: str = "auto"
    mp_sigma_m: float = DEFAULT_MP_SIGMA_M
    margin_db: float = DEFAULT_MARGIN_DB


@dataclass(frozen=True)
class CutoffChoice:
    """The cutoff a fit uses and why.

    Attributes
    ----------
    f_c_hz : float
        Cutoff frequency, Hz.
    source : str
        Human-readable source (e.g. ``"map (cell 40..60 N, -120..-60 E; ...)"``).
    info : dict
        Details of the source (map cell, corners, layers, provenance; or the
        computed summary).
    warnings : tuple of str
        Warnings for the user.
    """

    f_c_hz: float
    source: str
    info: dict[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


def _as_date(date: _dt.date | str | None) -> _dt.date | None:
    if date is None or isinstance(date, _dt.date):
        return date.date() if isinstance(date, _dt.datetime) else date
    try:
        return _dt.date.fromisoformat(str(date)[:10])
    except ValueError:
        raise InputError(f"date {date!r} is not YYYY-MM-DD") from None


def _map_margin_db(mp_sigma_m: float, margin_db: float) -> float:
    """Margin below the map's 1 mm reference equivalent to (mp_sigma_m, margin_db), dB."""
    if not mp_sigma_m > 0:
        raise InputError(f"mp_sigma_m = {mp_sigma_m} m must be positive")
    return margin_db - 20.0 * math.log10(mp_sigma_m / DEFAULT_MP_SIGMA_M)


def _at_margin(
    doc: dict[str, Any], lat: float, lon: float, f107: float, margin: float
) -> tuple[float, dict[str, Any]]:
    """Interpolated cutoff at a margin below the map's reference (log f_c linear in dB)."""
    from psdbound.ionosphere.worldmap import interpolate_map

    if abs(margin - doc["criterion"]["margin_db"]) < 1e-9:
        return interpolate_map(doc, lat, lon, f107)
    recorded = sorted(float(m) for m in doc["layers"][0]["grid"]["by_margin_hz"])
    if not recorded[0] <= margin <= recorded[-1]:
        raise InputError(
            f"the map records margins {recorded[0]:g}-{recorded[-1]:g} dB below "
            f"{1e3 * DEFAULT_MP_SIGMA_M:g} mm; {margin:.1f} dB is outside: use the "
            "'computed' cutoff source"
        )
    k = max(i for i, m in enumerate(recorded) if m <= margin)
    k = min(k, len(recorded) - 2)
    m0, m1 = recorded[k], recorded[k + 1]
    f0, info = interpolate_map(doc, lat, lon, f107, margin_db=m0)
    f1, _ = interpolate_map(doc, lat, lon, f107, margin_db=m1)
    w = (margin - m0) / (m1 - m0)
    return float(math.exp((1 - w) * math.log(f0) + w * math.log(f1))), info


def cutoff_from_map(
    lat_deg: float,
    lon_deg: float,
    *,
    year: int | None = None,
    date: _dt.date | str | None = None,
    mp_sigma_m: float = DEFAULT_MP_SIGMA_M,
    margin_db: float = DEFAULT_MARGIN_DB,
    path: str | None = None,
) -> tuple[float, dict[str, Any]]:
    """Cutoff from the cutoff map at a position and the solar flux of a date or year.

    Parameters
    ----------
    lat_deg, lon_deg : float
        Receiver position, degrees.
    year : int, optional
        Year of the data (its annual mean F10.7 when no date is given).
    date : datetime.date or str, optional
        Day of the data (its month's F10.7).
    mp_sigma_m, margin_db : float
        Residual criterion (see :class:`CutoffOptions`).
    path : str, optional
        A map file instead of the shipped one.

    Returns
    -------
    f_c_hz : float
        Interpolated cutoff, Hz.
    info : dict
        ``map`` (file), ``map_created``, ``map_pyiri_version``,
        ``criterion``, ``cell`` (bounds and corner values), ``layers``,
        ``f107_sfu`` and ``f107_source``, ``solar`` (interpolated, clamped,
        extrapolated or conservative), the nearest reference ``station``,
        its ``station_distance_deg`` and ``station_f_c_hz``, and
        ``warnings`` (list).
    """
    from psdbound.ionosphere.solar import f107_of
    from psdbound.ionosphere.stations import validate_station
    from psdbound.ionosphere.worldmap import MAP_FILE, load_map, nearest_map_station

    lat, lon = validate_station(lat_deg, lon_deg)
    doc = load_map(path)
    warnings = []
    f107, label = f107_of(_as_date(date), year)
    conservative = f107 is None
    if conservative:
        f107 = max(layer["f107_sfu"] for layer in doc["layers"])
        label = f"no F10.7 for {label} in the shipped table: the solar-maximum layer"
        warnings.append(
            f"cutoff map: no solar flux known for the data's date ({year}); used the "
            "solar-maximum layer (the larger, conservative cutoff)"
        )
    margin = _map_margin_db(mp_sigma_m, margin_db)
    f_c, info = _at_margin(doc, lat, lon, f107, margin)
    top = max(la["f107_sfu"] for la in doc["layers"])
    if info["solar"] == "extrapolated" and f107 > EXTRAPOLATION_WARNING * top:
        warnings.append(
            f"cutoff map: F10.7 {f107:.0f} sfu is above the map's solar-maximum layer "
            f"({top:.0f} sfu) by more than {100 * (EXTRAPOLATION_WARNING - 1):.0f} %: cutoff "
            "extrapolated linearly in F10.7"
        )
    out = {
        "map": path or f"psdbound/ionosphere/{MAP_FILE}",
        "map_created": doc["created_utc"],
        "map_pyiri_version": doc["pyiri_version"],
        "criterion": {**doc["criterion"], "mp_sigma_m": mp_sigma_m, "margin_db": margin_db},
        **info,
        "f107_source": label,
        "solar": "conservative" if conservative else info["solar"],
        **nearest_map_station(doc, lat, lon),
        "by_margin": _map_by_margin(doc, lat, lon, f107),
        "warnings": warnings,
    }
    return f_c, out


def _map_by_margin(
    doc: dict[str, Any], lat: float, lon: float, f107: float
) -> list[dict[str, float]]:
    """Return the map's cutoff at every recorded margin below its 1 mm reference.

    Each entry: ``margin_db`` (dB below the reference), ``threshold_m`` (the
    residual RMS that margin allows, m) and ``f_c_hz`` (interpolated at the
    receiver as the chosen cutoff is, Hz).
    """
    from psdbound.ionosphere.worldmap import interpolate_map

    out = []
    for m in sorted(float(k) for k in doc["layers"][0]["grid"]["by_margin_hz"]):
        f_c, _ = interpolate_map(doc, lat, lon, f107, margin_db=m)
        out.append(
            {
                "margin_db": m,
                "threshold_m": DEFAULT_MP_SIGMA_M * 10 ** (-m / 20.0),
                "f_c_hz": float(f_c),
            }
        )
    return out


def cutoff_computed(
    lat_deg: float,
    lon_deg: float,
    year: int,
    *,
    date: _dt.date | str | None = None,
    mp_sigma_m: float = DEFAULT_MP_SIGMA_M,
    margin_db: float = DEFAULT_MARGIN_DB,
    workers: int = 2,
    carriers_hz: tuple[float, float] | None = None,
    system: str = "G",
) -> tuple[float, dict[str, Any]]:
    """Compute the cutoff at a position (PyIRI, nominal constellation, first Monday of a month).

    Parameters
    ----------
    lat_deg, lon_deg : float
        Receiver position, degrees.
    year : int
        Year of the data.
    date : datetime.date or str, optional
        Day of the data: its month's F10.7 is simulated (else the year's
        mean; else the solar-maximum 185 sfu).
    mp_sigma_m, margin_db : float
        Residual criterion (see :class:`CutoffOptions`).
    workers : int, default 2
        Local Dask workers.
    carriers_hz : (float, float), optional
        The data's two carrier frequencies, Hz (default GPS L1/L2): the
        residual ionosphere of the isolated series scales with their
        ionosphere coefficient.
    system : str, default "G"
        The data's system: its nominal constellation (``"G"`` or ``"E"``;
        another system is simulated with GPS's, and ``info`` says so).

    Returns
    -------
    f_c_hz : float
        Recommended (maximum over the series) cutoff, Hz.
    info : dict
        ``{"computed": summary, "f107_sfu": ..., "f107_source": ...,
        "carriers_hz": ..., "constellation": ...}``.
    """
    from psdbound.ionosphere.batch import select_days, station_cutoffs
    from psdbound.ionosphere.settings import CutoffSettings
    from psdbound.ionosphere.solar import annual_f107, f107_of

    f107, label = f107_of(_as_date(date), year)
    if f107 is None:
        f107, label = float(annual_f107(2024) or 185.0), f"no F10.7 for {year}: solar maximum"
    fa, fb = carriers_hz or (F_L1_HZ, F_L2_HZ)
    constellation = system if system in NOMINAL_SYSTEMS else NOMINAL_SYSTEMS[0]
    settings = dataclasses.replace(
        CutoffSettings(),
        f107_sfu=float(f107),
        mp_sigma_m=mp_sigma_m,
        margin_db=margin_db,
        frequency_hz=float(fa),
        second_frequency_hz=float(fb),
        systems=constellation,
    )
    res = station_cutoffs(
        lat_deg,
        lon_deg,
        select_days(year),
        name="receiver",
        settings=settings,
        workers=workers,
        keep_series=False,
    )
    summ = res.summary()
    return float(summ["recommended_f_c_hz"]), {
        "computed": summ,
        "f107_sfu": float(f107),
        "f107_source": label,
        "carriers_hz": [float(fa), float(fb)],
        "constellation": f"nominal {constellation}"
        + ("" if constellation == system else f" (no nominal constellation of {system})"),
    }


def iono_coefficient_ratio(carriers_hz: tuple[float, float]) -> float:
    """Return how much more ionosphere a carrier pair's isolated series holds than GPS L1/L2's.

    The dual-frequency series ``(L_a - L_b) / sqrt(2)`` (phases in metres)
    holds the ionosphere times ``|1/f_b^2 - 1/f_a^2|``
    (:func:`psdbound.ionosphere.slant.delay_factor`); the ratio of that
    coefficient to L1/L2's (1 for GPS L1/L2, 1.23 for E1/E5a or L1/L5).

    Parameters
    ----------
    carriers_hz : (float, float)
        The two carrier frequencies, Hz.

    Returns
    -------
    float
        Dimensionless.
    """
    from psdbound.ionosphere.slant import delay_factor

    return delay_factor(*carriers_hz) / delay_factor(F_L1_HZ, F_L2_HZ)


def _carrier_warning(carriers_hz: tuple[float, float] | None, source: str) -> list[str]:
    """Say when the cutoff map (GPS L1/L2) is applied to another carrier pair."""
    if carriers_hz is None:
        return []
    k = iono_coefficient_ratio(carriers_hz)
    if abs(k - 1.0) < 1e-3:
        return []
    return [
        f"the cutoff {source} was computed for GPS L1/L2; the data's carriers "
        f"({carriers_hz[0] / 1e6:.2f}/{carriers_hz[1] / 1e6:.2f} MHz) put {k:.2f} times as much "
        "ionosphere into the isolated series, so its residual-ionosphere criterion was not "
        "checked for them: --cutoff-source computed computes the cutoff for these carriers"
    ]


def _band_warning(f_c_hz: float, interval_s: float | None) -> list[str]:
    if interval_s is None or interval_s <= 0:
        return []
    nyq = 0.5 / interval_s
    if nyq / f_c_hz >= MIN_BAND_RATIO:
        return []
    return [
        f"cutoff {f_c_hz:.3g} Hz leaves only a factor {nyq / f_c_hz:.2f} below the Nyquist "
        f"frequency {nyq:.3g} Hz of {interval_s:g} s data (need {MIN_BAND_RATIO:g}): too "
        "little band for the bound"
    ]


def choose_cutoff(
    options: CutoffOptions,
    *,
    lat_deg: float | None,
    lon_deg: float | None,
    year: int,
    date: _dt.date | str | None = None,
    interval_s: float | None = None,
    carriers_hz: tuple[float, float] | None = None,
    system: str = "G",
) -> CutoffChoice:
    """Choose the cutoff for a receiver position and date.

    Parameters
    ----------
    options : CutoffOptions
        Given cutoff, source and residual criterion.
    lat_deg, lon_deg : float or None
        Receiver position, degrees (None when unknown).
    year : int
        Year of the data.
    date : datetime.date or str, optional
        Day of the data (the map and the computation then use its month's
        solar flux; else the year's).
    interval_s : float, optional
        Sampling interval of the data, s: a cutoff leaving less than a
        factor :data:`MIN_BAND_RATIO` below Nyquist is warned about.
    carriers_hz : (float, float), optional
        The data's carrier frequencies, Hz (None: GPS L1/L2). ``"computed"``
        uses them; the map (GPS L1/L2) says when they differ.
    system : str, default "G"
        The data's satellite system (``"computed"``: its nominal constellation).

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
        raise InputError(f"unknown cutoff source {src!r}; use {', '.join(CUTOFF_SOURCES)}")
    have_pos = lat_deg is not None and lon_deg is not None
    warnings: list[str] = []
    if src == "auto":
        if options.f_c_hz is not None:
            src = "given"
        elif have_pos:
            src = "map"
        else:
            src = "thesis"
            warnings.append(
                "no receiver position: the cutoff map cannot be used; used the thesis's "
                f"Chicago 2020 value {THESIS_CUTOFF_HZ:g} Hz"
            )
    if src == "given":
        if options.f_c_hz is None:
            raise InputError("cutoff source 'given' needs --cutoff-hz")
        choice = CutoffChoice(float(options.f_c_hz), "given")
    elif src == "thesis":
        choice = CutoffChoice(
            THESIS_CUTOFF_HZ,
            "thesis (Chicago 2020 maximum, eq. 4.2)",
            {"thesis_chicago_2020_hz": dict(THESIS_CHICAGO_2020_HZ)},
        )
    elif not have_pos:
        raise InputError(f"cutoff source {src!r} needs a receiver position")
    elif src == "map":
        f_c, info = cutoff_from_map(
            lat_deg,
            lon_deg,
            year=year,
            date=date,
            mp_sigma_m=options.mp_sigma_m,
            margin_db=options.margin_db,
        )
        warnings += info.pop("warnings") + _carrier_warning(carriers_hz, "map")
        c = info["cell"]
        source = (
            f"map (cell {c['lat_deg'][0]:g}..{c['lat_deg'][1]:g} N, "
            f"{c['lon_deg'][0]:g}..{c['lon_deg'][1]:g} E; F10.7 {info['f107_sfu']:.0f} sfu, "
            f"{info['solar']}; nearest reference station {info.get('station', '?')})"
        )
        choice = CutoffChoice(f_c, source, info)
    else:
        f_c, info = cutoff_computed(
            lat_deg,
            lon_deg,
            year,
            date=date,
            mp_sigma_m=options.mp_sigma_m,
            margin_db=options.margin_db,
            carriers_hz=carriers_hz,
            system=system,
        )
        fa, fb = info["carriers_hz"]
        choice = CutoffChoice(
            f_c,
            f"computed (PyIRI, residual criterion, {year}, F10.7 {info['f107_sfu']:.0f} sfu, "
            f"{fa / 1e6:.2f}/{fb / 1e6:.2f} MHz, {info['constellation']})",
            info,
        )
    warnings += _band_warning(choice.f_c_hz, interval_s)
    return dataclasses.replace(choice, warnings=(*choice.warnings, *warnings))
