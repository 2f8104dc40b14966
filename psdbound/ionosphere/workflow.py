"""From options to output files: a whole cutoff run as one library call.

:func:`run_cutoff` is what ``psdbound cutoff`` does: check the position,
pick the days (:func:`~psdbound.ionosphere.batch.select_days`), build the
settings (:meth:`~psdbound.ionosphere.settings.CutoffSettings.from_mapping`),
load the orbit source (:func:`load_orbit`), run a station
(:func:`~psdbound.ionosphere.batch.station_cutoffs`), and write the outputs
(:func:`~psdbound.ionosphere.outputs.write_cutoff_outputs`).
:func:`run_world_map` is ``psdbound cutoff --map``: the world cutoff map
(:func:`~psdbound.ionosphere.worldmap.compute_world_map`), its files, and
optionally the package data file it replaces.
"""

from __future__ import annotations

import datetime as _dt
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from psdbound.common.notices import warn
from psdbound.errors import InputError
from psdbound.io.timescales import calendar_to_gps_s
from psdbound.ionosphere.almanac import read_yuma
from psdbound.ionosphere.batch import map_cutoffs, select_days, station_cutoffs
from psdbound.ionosphere.outputs import write_cutoff_outputs
from psdbound.ionosphere.results import CutoffMap, StationCutoffs
from psdbound.ionosphere.settings import CutoffSettings
from psdbound.ionosphere.stations import validate_station

__all__ = ["CutoffOutcome", "WorldMapOutcome", "load_orbit", "run_cutoff", "run_world_map"]


@dataclass
class CutoffOutcome:
    """What :func:`run_cutoff` computed and wrote.

    Attributes
    ----------
    result : StationCutoffs or CutoffMap
        The station or map run.
    days : list of datetime.date
        Days simulated.
    files : list of Path
        Output files written, in order.
    nearest : tuple of (dict, float) or None
        For a map run with a position: the nearest station's summary and its
        distance, degrees of arc.
    """

    result: StationCutoffs | CutoffMap
    days: list[_dt.date]
    files: list[Path] = field(default_factory=list)
    nearest: tuple[dict[str, Any], float] | None = None


def load_orbit(
    *,
    day: _dt.date,
    nav: str | os.PathLike[str] | None = None,
    sp3: str | os.PathLike[str] | None = None,
    almanac: str | os.PathLike[str] | None = None,
) -> Any:
    """Orbit source from a file, or None for the nominal constellation.

    Parameters
    ----------
    day : datetime.date
        First day of the run (resolves a YUMA almanac's week rollover).
    nav, sp3, almanac : str or path-like, optional
        RINEX navigation, SP3 or YUMA almanac file; at most one.

    Returns
    -------
    OrbitSource or None
        None when no file is given.

    Raises
    ------
    InputError
        For more than one file, or a file that cannot be read.
    """
    if sum(x is not None for x in (nav, sp3, almanac)) > 1:
        raise InputError("give at most one of a navigation, SP3 or almanac file")
    if nav or sp3:
        from psdbound.io import read_orbit

        return read_orbit(nav or sp3)
    if almanac:
        near = float(calendar_to_gps_s(day.year, day.month, day.day, 0, 0, 0))
        return read_yuma(almanac, near_gps_s=near)
    return None


def _system_satellites(
    orbit: Any, systems: str, path: str | os.PathLike[str] | None
) -> list[str] | None:
    """Return the orbit file's satellites of the requested systems (None: no file).

    Raises
    ------
    InputError
        The file holds none of them.
    """
    if orbit is None:
        return None
    held = sorted(orbit.satellites)
    sats = [s for s in held if s[0] in systems]
    if not sats:
        have = "".join(sorted({s[0] for s in held})) or "no satellite"
        raise InputError(
            f"the orbit file holds {have} only, not the systems asked for ({systems}); give "
            f"--systems {have[:1] or 'G'} or an orbit file with {systems}",
            path=path,
        )
    others = sorted({s[0] for s in held} - set(systems))
    if others:
        warn(
            f"the orbit file also holds {''.join(others)} satellites, not analysed (--systems "
            f"{systems})",
            path=path,
        )
    return sats


def run_cutoff(
    *,
    lat_deg: float | None = None,
    lon_deg: float | None = None,
    station_map: bool = False,
    year: int = 2020,
    days: str = "first-monday-each-month",
    name: str = "",
    height_m: float = 0.0,
    settings: CutoffSettings | Mapping[str, Any] | None = None,
    nav: str | os.PathLike[str] | None = None,
    sp3: str | os.PathLike[str] | None = None,
    almanac: str | os.PathLike[str] | None = None,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    out_dir: str | os.PathLike[str] = ".",
    figures: bool = True,
    progress: Callable[[int, int], None] | None = None,
) -> CutoffOutcome:
    """Run a station (or the station map) and write its outputs.

    Parameters
    ----------
    lat_deg, lon_deg : float, optional
        Station position, degrees; with ``station_map``, the position whose
        nearest map station is looked up.
    station_map : bool, default False
        Run the 20 map stations instead of one station.
    year : int, default 2020
        Year of a named day selection.
    days : str, default "first-monday-each-month"
        Day selection (see :func:`~psdbound.ionosphere.batch.select_days`).
    name : str, optional
        Station name for outputs.
    height_m : float, default 0
        Station height, m.
    settings : CutoffSettings or mapping, optional
        Settings, or a mapping of setting names for
        :meth:`CutoffSettings.from_mapping`; default values otherwise.
    nav, sp3, almanac : str or path-like, optional
        Orbit file (see :func:`load_orbit`); default the nominal constellation.
    workers, scheduler, cache_dir, use_cache, progress
        Execution (see :func:`~psdbound.ionosphere.batch.station_cutoffs`).
    out_dir : str or path-like, default "."
        Output folder.
    figures : bool, default True
        Also write the PNG figures.

    Returns
    -------
    CutoffOutcome

    Raises
    ------
    InputError
        For a bad position, day selection, setting or file.
    NoDataError
        If a station has no satellite series to analyse.
    """
    if (lat_deg is None) != (lon_deg is None):
        raise InputError("latitude and longitude go together")
    if not station_map and lat_deg is None:
        raise InputError("give a station position, or run the station map")
    if lat_deg is not None:
        validate_station(lat_deg, lon_deg)
    day_list = select_days(year, days)
    if not isinstance(settings, CutoffSettings):
        settings = CutoffSettings.from_mapping(settings or {})
    settings.validate()
    common = {
        "orbit": load_orbit(day=day_list[0], nav=nav, sp3=sp3, almanac=almanac),
        "settings": settings,
        "workers": workers,
        "scheduler": scheduler,
        "cache_dir": cache_dir,
        "use_cache": use_cache,
        "progress": progress,
    }
    sats = _system_satellites(common["orbit"], settings.systems, nav or sp3 or almanac)
    if sats is not None:
        common["satellites"] = sats
    if station_map:
        result: StationCutoffs | CutoffMap = map_cutoffs(day_list, **common)
    else:
        result = station_cutoffs(lat_deg, lon_deg, day_list, name=name, height_m=height_m, **common)
    files = write_cutoff_outputs(result, out_dir, figures=figures)
    nearest = None
    if station_map and lat_deg is not None:
        nearest = result.nearest(lat_deg, lon_deg)
    return CutoffOutcome(result=result, days=day_list, files=files, nearest=nearest)


@dataclass
class WorldMapOutcome:
    """What :func:`run_world_map` computed and wrote.

    Attributes
    ----------
    doc : dict
        The map document.
    files : list of Path
        Files written.
    at_position : tuple of (float, dict) or None
        The cutoff interpolated at the requested position and its details.
    """

    doc: dict[str, Any]
    files: list[Path] = field(default_factory=list)
    at_position: tuple[float, dict[str, Any]] | None = None


def run_world_map(
    *,
    settings: CutoffSettings | Mapping[str, Any] | None = None,
    grid_step_deg: tuple[float, float] | None = None,
    days: str | None = None,
    lat_deg: float | None = None,
    lon_deg: float | None = None,
    year: int = 2020,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    out_dir: str | os.PathLike[str] = ".",
    figures: bool = True,
    install: bool = False,
    progress: Callable[[int, int], None] | None = None,
) -> WorldMapOutcome:
    """Compute the world cutoff map, write it, and optionally install it as package data.

    Parameters
    ----------
    settings : CutoffSettings or mapping, optional
        Criterion and simulation settings (``f107_sfu`` is each layer's).
    grid_step_deg : (float, float), optional
        Grid steps, default :data:`~psdbound.ionosphere.worldmap.DEFAULT_GRID_STEP_DEG`.
    days : str, optional
        Day selection within each layer's year (default quarterly).
    lat_deg, lon_deg : float, optional
        A position to interpolate the new map at (with the F10.7 of ``year``).
    year : int, default 2020
        Year of that position's data.
    workers, scheduler, cache_dir, use_cache, progress
        Execution (see :func:`~psdbound.ionosphere.batch.station_cutoffs`).
    out_dir : str or path-like, default "."
        Output folder.
    figures : bool, default True
        Also write ``cutoff_map.png``.
    install : bool, default False
        Also replace the shipped map (``psdbound/ionosphere/data/cutoff_map.json``).

    Returns
    -------
    WorldMapOutcome
    """
    from importlib import resources

    from psdbound.ionosphere.outputs import write_world_map_outputs
    from psdbound.ionosphere.solar import annual_f107
    from psdbound.ionosphere.worldmap import (
        DEFAULT_GRID_STEP_DEG,
        MAP_DAYS,
        MAP_FILE,
        compute_world_map,
        interpolate_map,
    )

    if not isinstance(settings, CutoffSettings):
        settings = CutoffSettings.from_mapping(settings or {})
    doc = compute_world_map(
        grid_step_deg=grid_step_deg or DEFAULT_GRID_STEP_DEG,
        days=days or MAP_DAYS,
        settings=settings,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    target = None
    if install:
        target = Path(str(resources.files("psdbound.ionosphere").joinpath(MAP_FILE)))
    files = write_world_map_outputs(doc, out_dir, figures=figures, install_path=target)
    at = None
    if lat_deg is not None and lon_deg is not None:
        lat, lon = validate_station(lat_deg, lon_deg)
        f107 = annual_f107(year) or max(la["f107_sfu"] for la in doc["layers"])
        at = interpolate_map(doc, lat, lon, f107)
    return WorldMapOutcome(doc=doc, files=files, at_position=at)
