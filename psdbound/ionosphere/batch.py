"""Batch cutoff runs: days x satellites for a station, and the station map.

(docs/method/cutoff.rst, step 6-7.) Each station-day is one task
(:func:`~psdbound.ionosphere.tasks.station_day`) run by
:func:`psdbound.compute.run_tasks`: on a Dask ``distributed`` cluster, by
default a :class:`~dask.distributed.LocalCluster` of ``workers``
single-threaded processes, or any running scheduler given by its address
(its workers need psdbound installed); ``workers=0`` runs them in this
process without Dask (debugging, tiny runs). Whatever is opened is closed.

Results are cached on disk per task, in ``cache_dir`` (default
:func:`default_cache_dir`), keyed by a SHA-256 of every input that changes
the result (see :mod:`psdbound.ionosphere.tasks`). A second run with the
same inputs reads the cache and submits nothing. Files are written
atomically, so concurrent runs cannot leave a torn entry.

The per-station summary reports mean, min and max f_c over all series; the
recommended cutoff is the maximum (the thesis's choice: it removes the
fastest ionospheric dynamics met).
"""

from __future__ import annotations

import calendar
import datetime as _dt
import os
import re
import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from psdbound import compute
from psdbound.errors import InputError, NoDataError
from psdbound.ionosphere.constellation import nominal_constellation
from psdbound.ionosphere.iri import parse_date
from psdbound.ionosphere.results import CutoffMap, StationCutoffs
from psdbound.ionosphere.settings import CutoffSettings
from psdbound.ionosphere.stations import MAP_STATIONS, Station, validate_station
from psdbound.ionosphere.tasks import (
    SERIES_ARRAYS,
    day_cache,
    day_specs,
    orbit_identity,
    station_day,
)

__all__ = [
    "default_cache_dir",
    "map_cutoffs",
    "prepare_orbit",
    "run_groups",
    "select_days",
    "station_cutoffs",
]


def default_cache_dir() -> Path:
    """``$PSDBOUND_CACHE`` if set, else ``~/.cache/psdbound/cutoff``."""
    return compute.default_cache_dir("cutoff")


def _months(text: str) -> range | list[int]:
    """Return the months (1-12) of ``first-monday-of-MM[,MM...]``, all for the other names."""
    if not text.startswith("first-monday-of-"):
        return range(1, 13)
    try:
        months = [int(m) for m in text[len("first-monday-of-") :].split(",")]
    except ValueError:
        raise InputError(f"cannot read the month in {text!r}") from None
    for m in months:
        if not 1 <= m <= 12:
            raise InputError(f"month {m} in {text!r} is not 1-12")
    return months


def _first_mondays(year: int, text: str) -> list[_dt.date]:
    """Return the first Monday of each month the named selection ``text`` gives."""
    if not isinstance(year, int) or isinstance(year, bool):
        raise InputError(f"year {year!r} must be an integer")
    days = []
    for m in _months(text):
        first = _dt.date(year, m, 1) if 1 <= year <= 9999 else None
        if first is None:
            raise InputError(f"year {year} is not a calendar year")
        offset = (calendar.MONDAY - first.weekday()) % 7
        days.append(parse_date(first + _dt.timedelta(days=offset)))
    return days


def select_days(year: int, spec: str = "first-monday-each-month") -> list[_dt.date]:
    """Days of a run.

    Parameters
    ----------
    year : int
        Year of the named selections.
    spec : str, default "first-monday-each-month"
        ``"first-monday-each-month"``: the Monday of the first full
        (Monday-Sunday) week of each month, i.e. the first Monday (the
        thesis's choice); ``"first-monday-of-MM[,MM...]"`` for some months;
        ``"first-monday-quarterly"`` for March, June, September and December
        (equinoxes and solstices, the cutoff map's days); or a
        comma-separated list of ``YYYY-MM-DD`` dates (any year).

    Returns
    -------
    list of datetime.date

    Raises
    ------
    InputError
        For an unknown selection, an invalid date or one outside the
        supported range.
    """
    text = spec.strip()
    if text == "first-monday-quarterly":
        text = "first-monday-of-03,06,09,12"
    if text == "first-monday-each-month" or text.startswith("first-monday-of-"):
        return _first_mondays(year, text)
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not parts:
        raise InputError(
            f"unknown day selection {spec!r}: use first-monday-each-month or "
            "YYYY-MM-DD[,YYYY-MM-DD...]"
        )
    return [parse_date(p) for p in parts]


def prepare_orbit(orbit: Any, settings: CutoffSettings) -> Any:
    """Return ``orbit``, or the nominal constellation of ``settings.systems`` when None."""
    return nominal_constellation(settings.systems) if orbit is None else orbit


def run_groups(
    groups: list[tuple[Station, float, list[dict[str, Any]], CutoffSettings]],
    *,
    orbit: Any,
    workers: int,
    scheduler: str | None,
    cache_dir: str | os.PathLike[str] | None,
    use_cache: bool,
    progress: Callable[[int, int], None] | None,
) -> list[StationCutoffs]:
    """Run every station-day of every group on one cluster; assemble one result per group.

    Parameters
    ----------
    groups : list of (Station, float, list of dict, CutoffSettings)
        Per group: station, height (m), its station-day specs
        (:func:`~psdbound.ionosphere.tasks.day_specs`) and their settings.
    orbit : OrbitSource
        The orbit source of the specs.
    workers, scheduler, cache_dir, use_cache, progress
        As for :func:`station_cutoffs`.

    Returns
    -------
    list of StationCutoffs
        One per group, in order.
    """
    source, description = orbit_identity(orbit)
    flat = [(g, spec) for g, (_, _, specs, _) in enumerate(groups) for spec in specs]
    cache = None
    if use_cache:
        cache = day_cache(Path(cache_dir) if cache_dir is not None else default_cache_dir())
    run = compute.run_tasks(
        station_day,
        [spec for _, spec in flat],
        workers=workers,
        scheduler=scheduler,
        cache=cache,
        progress=progress,
    )
    results = run.results
    out = []
    for g, (station, height_m, specs, settings) in enumerate(groups):
        idx = [i for i, (gg, _) in enumerate(flat) if gg == g]
        rows, skipped = [], []
        for i in idx:
            rows += results[i]["rows"]
            skipped += results[i]["skipped"]
        sc = StationCutoffs(
            name=station.name,
            lat_deg=station.lat_deg,
            lon_deg=station.lon_deg,
            height_m=height_m,
            rows=rows,
            skipped=skipped,
            settings=settings,
            orbit_source=source,
            orbit_description=description,
            days=[s["date"] for s in specs],
            from_cache=[run.from_cache[i] for i in idx],
            elapsed_s=run.elapsed_s,
            series_by_date={results[i]["date"]: _series(results[i]) for i in idx},
        )
        out.append(sc)
    return out


def _series(result: dict[str, Any]) -> dict[str, Any] | None:
    """Return the delays a task result kept (``t_gps_s``, ``sats``, ``delay_m``), or None."""
    if not all(name in result for name in SERIES_ARRAYS):
        return None
    return {"t_gps_s": result["t_gps_s"], "sats": result["sats"], "delay_m": result["delay_m"]}


def station_cutoffs(
    lat_deg: float,
    lon_deg: float,
    days: Iterable[str | _dt.date],
    *,
    name: str = "",
    height_m: float = 0.0,
    orbit: Any = None,
    satellites: Sequence[str] | None = None,
    settings: CutoffSettings | None = None,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    keep_series: bool | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> StationCutoffs:
    """Cutoff of every satellite series on every day at one station.

    Parameters
    ----------
    lat_deg, lon_deg : float
        Station geodetic position, degrees.
    days : iterable of str or datetime.date
        Days (UTC), e.g. from :func:`select_days`.
    name : str, optional
        Station name for tables and figures.
    height_m : float, default 0
        Station height, m.
    orbit : OrbitSource, optional
        Navigation, SP3, almanac or constellation object; default the
        nominal constellation of ``settings.systems``.
    satellites : sequence of str, optional
        Restrict to these satellites.
    settings : CutoffSettings, optional
        Simulation, spectrum and criterion settings (default values).
    workers : int, default 2
        Worker processes of the local Dask cluster (0: in-process, no Dask).
    scheduler : str, optional
        Address of a running Dask scheduler to use instead.
    cache_dir : str or path-like, optional
        Cache directory (default :func:`default_cache_dir`).
    use_cache : bool, default True
        Read and write the cache.
    keep_series : bool, optional
        Keep (and cache) the simulated delays, for figures; default only for
        the periodogram criteria, whose figures redraw a series' PSD (the
        residual criterion's figure uses the rows' curves; moving and
        compressing 0.8 MB of delays per day costs about 10 % of a
        station-year).
    progress : callable, optional
        ``progress(done, total)`` after each computed task.

    Returns
    -------
    StationCutoffs

    Raises
    ------
    InputError
        For a bad position, date or setting.
    NoDataError
        If no satellite rises above the mask on any day.
    """
    settings = settings or CutoffSettings()
    settings.validate()
    lat, lon = validate_station(lat_deg, lon_deg)
    day_list = [parse_date(d) for d in days]
    if not day_list:
        raise InputError("no day selected")
    orbit = prepare_orbit(orbit, settings)
    station = Station(name or f"{lat:.2f},{lon:.2f}", lat, lon)
    if keep_series is None:
        keep_series = settings.criterion != "residual"
    specs = day_specs(station, height_m, day_list, orbit, satellites, settings, keep_series)
    (res,) = run_groups(
        [(station, height_m, specs, settings)],
        orbit=orbit,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    if not res.rows:
        reasons = _grouped_by_day([s["reason"] for s in res.skipped]) or ["no series"]
        raise NoDataError(f"no satellite series to analyse at {station.name}: {'; '.join(reasons)}")
    return res


#: A calendar day in a message (``2024-07-27``).
_DAY = re.compile(r"\d{4}-\d{2}-\d{2}")


def _grouped_by_day(reasons: Sequence[str]) -> list[str]:
    """Say each reason once, with the days it holds for (the same sentence per day, once)."""
    days: dict[str, list[str]] = {}
    for text in dict.fromkeys(reasons):
        found = _DAY.findall(text)
        key = _DAY.sub("{day}", text) if len(found) == 1 else text
        days.setdefault(key, []).extend(found[:1] if len(found) == 1 else [])
    out = []
    for key, when in days.items():
        if not when:
            out.append(key)
            continue
        shown = ", ".join(when[:3]) + (f" and {len(when) - 3} more days" if len(when) > 3 else "")
        out.append(key.replace("{day}", shown))
    return out


def map_cutoffs(
    days: Iterable[str | _dt.date],
    *,
    stations: Sequence[Station] = MAP_STATIONS,
    orbit: Any = None,
    satellites: Sequence[str] | None = None,
    settings: CutoffSettings | None = None,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    progress: Callable[[int, int], None] | None = None,
) -> CutoffMap:
    """Recommended cutoffs over a set of stations (all station-days on one Dask cluster).

    Parameters
    ----------
    days : iterable of str or datetime.date
        Days (UTC) simulated at every station.
    stations : sequence of Station, default the 20 map stations
        Stations of the map.
    orbit, satellites, settings, workers, scheduler, cache_dir, use_cache, progress
        As for :func:`station_cutoffs` (the delays are not kept).

    Returns
    -------
    CutoffMap
        With :meth:`CutoffMap.nearest` for a user position.
    """
    settings = settings or CutoffSettings()
    settings.validate()
    day_list = [parse_date(d) for d in days]
    if not day_list:
        raise InputError("no day selected")
    if not stations:
        raise InputError("no station in the map")
    orbit = prepare_orbit(orbit, settings)
    t0 = time.perf_counter()
    groups = [
        (st, 0.0, day_specs(st, 0.0, day_list, orbit, satellites, settings, False), settings)
        for st in stations
    ]
    res = run_groups(
        groups,
        orbit=orbit,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    return CutoffMap(stations=res, elapsed_s=time.perf_counter() - t0)
