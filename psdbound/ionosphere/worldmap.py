"""The worldwide cutoff map: compute it on Dask, ship it, interpolate it.

The thesis (section 5.2, appendix C) proposes a map of cutoffs over 20
reference stations, a receiver taking its nearest station's value. This
map adds a regular latitude-longitude grid and solar activity:

* **sites**: the 20 stations of table C.1 and a grid (:func:`grid_sites`,
  default every 20 deg of latitude from -80 to 80 and every 90 deg of
  longitude, 36 nodes: the ionosphere's climatology follows (magnetic)
  latitude, and a whole day at a fixed place sees every local time);
* **layers**: one per solar activity level, :data:`DEFAULT_LAYERS`: 2020
  (solar minimum, the thesis's year) and 2024 (solar maximum of cycle 25),
  each simulated with its year's mean monthly F10.7
  (:func:`~psdbound.ionosphere.solar.annual_f107`, 73.8 and 185.4 sfu);
* **days**: the first Monday of March, June, September and December of the
  layer's year (equinoxes and solstices; on Chicago 2020 the maximum over
  these four days equals the maximum over the thesis's twelve, the June
  value);
* **criterion**: the default :class:`~psdbound.ionosphere.CutoffSettings`
  (the residual criterion, docs/method/cutoff.rst); each site-layer records the
  recommended (maximum), mean and minimum cutoff, and the recommended
  cutoff at the margins of :data:`~psdbound.ionosphere.settings.LEVELS_DB`.

:func:`compute_world_map` runs every station-day of every site and layer
as one batch on the compute layer (a local Dask cluster or ``scheduler``)
and returns the map document (JSON-ready, with its provenance: PyIRI and
psdbound versions, settings, days, F10.7 per layer, creation date, run
time). :func:`map_validation` compares, at the 20 stations, the value
interpolated from the grid with the station's own. ``psdbound cutoff
--map`` regenerates ``psdbound/ionosphere/data/cutoff_map.json``.

:func:`interpolate_map` gives the cutoff at a position and F10.7: bilinear
in latitude and longitude on the grid (longitude periodic, latitude clamped
to the outer rows), then linear in F10.7 between the layers (clamped below
the lowest; extrapolated linearly above the highest, which raises the
cutoff, the conservative direction).
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import functools
import json
import os
import platform
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from importlib import resources
from typing import Any

import numpy as np

from psdbound.errors import InputError
from psdbound.ionosphere.batch import prepare_orbit, run_groups, select_days
from psdbound.ionosphere.results import StationCutoffs
from psdbound.ionosphere.settings import CutoffSettings
from psdbound.ionosphere.solar import annual_f107, f107_table
from psdbound.ionosphere.stations import MAP_STATIONS, Station, nearest_station
from psdbound.ionosphere.tasks import day_specs, orbit_identity
from psdbound.version import __version__

__all__ = [
    "DEFAULT_GRID_STEP_DEG",
    "DEFAULT_LAYERS",
    "F107_TOLERANCE_SFU",
    "MAP_DAYS",
    "MAP_FILE",
    "MAP_FORMAT",
    "MapLayer",
    "compute_world_map",
    "grid_sites",
    "interpolate_map",
    "load_map",
    "map_validation",
    "nearest_map_station",
]

#: Package data file of the shipped map.
MAP_FILE = "data/cutoff_map.json"
#: Format tag of the map document.
MAP_FORMAT = "psdbound-cutoff-map/2"
#: Default grid steps (latitude, longitude), degrees.
DEFAULT_GRID_STEP_DEG = (20.0, 90.0)
#: Days of each layer's year (see :func:`~psdbound.ionosphere.batch.select_days`).
MAP_DAYS = "first-monday-quarterly"
#: A flux this close to a layer's counts as the layer's (the document rounds to 0.01 sfu).
F107_TOLERANCE_SFU = 0.5


@dataclass(frozen=True)
class MapLayer:
    """One solar-activity layer of the map.

    Attributes
    ----------
    name : str
        E.g. ``"solar-min"``.
    year : int
        Year of the days simulated.
    f107_sfu : float or None
        F10.7 of the simulation, sfu; None takes the year's mean monthly
        value from the shipped table.
    """

    name: str
    year: int
    f107_sfu: float | None = None

    def flux(self) -> float:
        """Return the layer's F10.7, sfu."""
        if self.f107_sfu is not None:
            return float(self.f107_sfu)
        f = annual_f107(self.year)
        if f is None:
            raise InputError(f"no F10.7 for {self.year} in the shipped table: give f107_sfu")
        return float(f)


#: Solar minimum (2020, the thesis's year) and solar maximum (2024, cycle 25).
DEFAULT_LAYERS = (MapLayer("solar-min", 2020), MapLayer("solar-max", 2024))


def grid_sites(lat_step_deg: float, lon_step_deg: float) -> list[Station]:
    """Nodes of the map grid, named like ``G+40-060``.

    Latitudes ``-90 + step/2, ..., 90 - step/2``; longitudes
    ``-180, -180 + step, ...`` (below 180).

    Parameters
    ----------
    lat_step_deg, lon_step_deg : float
        Grid steps, degrees (180 and 360 must be multiples of them).

    Returns
    -------
    list of Station
        Row-major (latitude outer, longitude inner).
    """
    lat, lon = _axes(lat_step_deg, lon_step_deg)
    return [Station(f"G{a:+03.0f}{o:+04.0f}", float(a), float(o)) for a in lat for o in lon]


def _axes(lat_step: float, lon_step: float) -> tuple[np.ndarray, np.ndarray]:
    n_lat, n_lon = 180.0 / lat_step, 360.0 / lon_step
    if not (lat_step > 0 and lon_step > 0 and n_lat.is_integer() and n_lon.is_integer()):
        raise InputError(
            f"grid steps {lat_step} x {lon_step} deg must divide 180 and 360 deg exactly"
        )
    lat = -90.0 + lat_step / 2 + lat_step * np.arange(int(n_lat))
    lon = -180.0 + lon_step * np.arange(int(n_lon))
    return lat, lon


def _sig(v: float, digits: int = 4) -> float | None:
    return None if not np.isfinite(v) else float(f"{v:.{digits}g}")


def _site_entry(sc: StationCutoffs) -> dict[str, Any]:
    s = sc.summary()
    return {
        "recommended_f_c_hz": _sig(s["recommended_f_c_hz"]),
        "mean_f_c_hz": _sig(s["mean_f_c_hz"]),
        "min_f_c_hz": _sig(s["min_f_c_hz"]),
        "n_series": s["n_series"],
        "by_margin_hz": {f"{m['margin_db']:g}": _sig(m["max_f_c_hz"]) for m in sc.by_margin()},
    }


def _map_groups(
    layers: Sequence[MapLayer],
    sites: list[Station],
    days: str,
    settings: CutoffSettings,
    orbit: Any,
) -> tuple[list[tuple[Any, ...]], list[tuple[MapLayer, CutoffSettings, list[_dt.date]]]]:
    """Return the batch's groups (site, height, day specs, settings) and each layer's days."""
    groups = []
    layer_info = []
    for layer in layers:
        s_l = dataclasses.replace(settings, f107_sfu=layer.flux())
        day_list = select_days(layer.year, days)
        layer_info.append((layer, s_l, day_list))
        for site in sites:
            specs = day_specs(site, 0.0, day_list, orbit, None, s_l, False)
            groups.append((site, 0.0, specs, s_l))
    return groups, layer_info


def _layer_doc(
    layer: MapLayer,
    s_l: CutoffSettings,
    day_list: list[_dt.date],
    res: list[StationCutoffs],
    stations: Sequence[Station],
    shape: tuple[int, int],
) -> dict[str, Any]:
    """Return one layer of the map document: its grid fields and named stations."""
    entries = [_site_entry(sc) for sc in res]
    st_entries = [
        {"name": st.name, "lat_deg": st.lat_deg, "lon_deg": st.lon_deg, **e}
        for st, e in zip(stations, entries[: len(stations)], strict=True)
    ]
    g = entries[len(stations) :]

    def field(key: str, g: list[dict[str, Any]] = g, shape: tuple[int, int] = shape) -> list:
        return np.array([e[key] for e in g], dtype=object).reshape(shape).tolist()

    margins = list(g[0]["by_margin_hz"]) if g else []
    return {
        "name": layer.name,
        "year": layer.year,
        "f107_sfu": round(s_l.f107_sfu, 2),
        "f107_source": "given"
        if layer.f107_sfu is not None
        else f"mean monthly F10.7 of {layer.year} ({f107_table()['source']})",
        "days": [d.isoformat() for d in day_list],
        "grid": {
            "recommended_f_c_hz": field("recommended_f_c_hz"),
            "mean_f_c_hz": field("mean_f_c_hz"),
            "min_f_c_hz": field("min_f_c_hz"),
            "n_series": field("n_series"),
            "by_margin_hz": {
                m: np.array([e["by_margin_hz"][m] for e in g], dtype=object).reshape(shape).tolist()
                for m in margins
            },
        },
        "stations": st_entries,
    }


def _criterion_doc(settings: CutoffSettings) -> dict[str, Any]:
    """Return the map document's description of the criterion and the fit's filter."""
    return {
        "name": settings.criterion,
        "mp_sigma_m": settings.mp_sigma_m,
        "margin_db": settings.margin_db,
        "threshold_m": settings.thresholds_m()[0],
        "scale": settings.residual_scale,
        "filter": {
            "kind": settings.filter_kind,
            "order": settings.filter_order,
            "edge": settings.filter_edge,
        },
    }


def compute_world_map(
    *,
    layers: Sequence[MapLayer] = DEFAULT_LAYERS,
    grid_step_deg: tuple[float, float] = DEFAULT_GRID_STEP_DEG,
    stations: Sequence[Station] = MAP_STATIONS,
    days: str = MAP_DAYS,
    settings: CutoffSettings | None = None,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    use_cache: bool = True,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, Any]:
    """Compute the cutoff map (every site, layer and day as one Dask batch).

    Parameters
    ----------
    layers : sequence of MapLayer, default :data:`DEFAULT_LAYERS`
        Solar-activity layers.
    grid_step_deg : (float, float), default (20, 90)
        Grid steps in latitude and longitude, degrees.
    stations : sequence of Station, default the 20 reference stations
        Named stations computed besides the grid.
    days : str, default "first-monday-quarterly"
        Day selection within each layer's year.
    settings : CutoffSettings, optional
        Criterion and simulation settings (default values); each layer
        replaces ``f107_sfu`` by its own.
    workers, scheduler, cache_dir, use_cache, progress
        Execution, as for :func:`~psdbound.ionosphere.station_cutoffs`.

    Returns
    -------
    dict
        The map document (see :func:`load_map`).
    """
    t0 = time.perf_counter()
    settings = settings or CutoffSettings()
    settings.validate()
    if not layers:
        raise InputError("the map needs at least one layer")
    orbit = prepare_orbit(None, settings)
    grid = grid_sites(*grid_step_deg)
    sites = [*stations, *grid]
    groups, layer_info = _map_groups(layers, sites, days, settings, orbit)
    results = run_groups(
        groups,
        orbit=orbit,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    lat_axis, lon_axis = _axes(*grid_step_deg)
    n_sites = len(sites)
    shape = (lat_axis.size, lon_axis.size)
    out_layers = []
    for k, (layer, s_l, day_list) in enumerate(layer_info):
        res = results[k * n_sites : (k + 1) * n_sites]
        out_layers.append(_layer_doc(layer, s_l, day_list, res, stations, shape))
    import PyIRI

    source, description = orbit_identity(orbit)
    s_doc = settings.to_dict()
    s_doc.pop("f107_sfu")
    doc = {
        "format": MAP_FORMAT,
        "created_utc": _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "psdbound_version": __version__,
        "pyiri_version": getattr(PyIRI, "__version__", "?"),
        "python": platform.python_version(),
        "criterion": _criterion_doc(settings),
        "settings": s_doc,
        "days": days,
        "orbit_source": source,
        "orbit_description": description,
        "grid": {
            "lat_step_deg": grid_step_deg[0],
            "lon_step_deg": grid_step_deg[1],
            "lat_deg": lat_axis.tolist(),
            "lon_deg": lon_axis.tolist(),
        },
        "layers": out_layers,
        "compute": {
            "elapsed_s": round(time.perf_counter() - t0, 1),
            "workers": workers if scheduler is None else None,
            "scheduler": scheduler,
            "n_station_days": sum(len(g[2]) for g in groups),
            "n_from_cache": int(sum(sum(r.from_cache) for r in results)),
        },
    }
    doc["validation"] = map_validation(doc)
    return doc


@functools.lru_cache(maxsize=4)
def _read_map(path: str | None) -> str:
    if path is None:
        return resources.files("psdbound.ionosphere").joinpath(MAP_FILE).read_text()
    with open(path) as f:
        return f.read()


def load_map(path: str | os.PathLike[str] | None = None) -> dict[str, Any]:
    """Read a map document (default the shipped one).

    Parameters
    ----------
    path : str or path-like, optional
        A map written by ``psdbound cutoff --map``.

    Returns
    -------
    dict
        ``format``, provenance (``created_utc``, ``psdbound_version``,
        ``pyiri_version``, ``settings``, ``criterion``, ``days``), ``grid``
        (``lat_deg``, ``lon_deg``) and ``layers`` (``name``, ``year``,
        ``f107_sfu``, ``days``, ``grid`` fields, ``stations``).

    Raises
    ------
    InputError
        For a file that is not a map of this format.
    """
    doc = json.loads(_read_map(None if path is None else os.fspath(path)))
    if doc.get("format") != MAP_FORMAT:
        raise InputError(f"{path or MAP_FILE} is not a {MAP_FORMAT} cutoff map")
    return doc


def _bilinear(doc: dict[str, Any], values: list, lat: float, lon: float) -> tuple[float, dict]:
    lat_ax = np.asarray(doc["grid"]["lat_deg"])
    lon_ax = np.asarray(doc["grid"]["lon_deg"])
    v = np.array(values, dtype=float)
    la = float(np.clip(lat, lat_ax[0], lat_ax[-1]))
    i = int(np.clip(np.searchsorted(lat_ax, la) - 1, 0, lat_ax.size - 2))
    wy = (la - lat_ax[i]) / (lat_ax[i + 1] - lat_ax[i])
    step = lon_ax[1] - lon_ax[0]
    x = ((lon - lon_ax[0]) % 360.0) / step
    j = int(np.floor(x)) % lon_ax.size
    j1 = (j + 1) % lon_ax.size
    wx = x - np.floor(x)
    corners = [v[i, j], v[i, j1], v[i + 1, j], v[i + 1, j1]]
    value = (1 - wy) * ((1 - wx) * corners[0] + wx * corners[1]) + wy * (
        (1 - wx) * corners[2] + wx * corners[3]
    )
    cell = {
        "lat_deg": [float(lat_ax[i]), float(lat_ax[i + 1])],
        "lon_deg": [float(lon_ax[j]), float(lon_ax[j] + step)],
        "corner_f_c_hz": [float(c) for c in corners],
    }
    return float(value), cell


def _field(layer: dict[str, Any], margin_db: float | None) -> list:
    if margin_db is None:
        return layer["grid"]["recommended_f_c_hz"]
    key = f"{margin_db:g}"
    if key not in layer["grid"]["by_margin_hz"]:
        raise InputError(
            f"the map holds margins {', '.join(layer['grid']['by_margin_hz'])} dB, not {key}"
        )
    return layer["grid"]["by_margin_hz"][key]


def interpolate_map(
    doc: dict[str, Any],
    lat_deg: float,
    lon_deg: float,
    f107_sfu: float,
    *,
    margin_db: float | None = None,
) -> tuple[float, dict[str, Any]]:
    """Cutoff at a position and solar flux, from a map document.

    Parameters
    ----------
    doc : dict
        A map (:func:`load_map`).
    lat_deg, lon_deg : float
        Position, degrees.
    f107_sfu : float
        Solar flux of the data's date, sfu.
    margin_db : float, optional
        One of the map's recorded margins (default: its main criterion).

    Returns
    -------
    f_c_hz : float
        Interpolated cutoff, Hz.
    info : dict
        ``cell`` (grid cell bounds and the corner values of the first
        layer), ``layers`` (per layer: name, F10.7, interpolated value),
        ``f107_sfu``, ``solar`` (``"interpolated"``, ``"clamped"`` or
        ``"extrapolated"``).
    """
    layers = sorted(doc["layers"], key=lambda layer: layer["f107_sfu"])
    vals, cells = [], []
    for layer in layers:
        v, cell = _bilinear(doc, _field(layer, margin_db), lat_deg, lon_deg)
        vals.append(v)
        cells.append(cell)
    fx = np.array([layer["f107_sfu"] for layer in layers], dtype=float)
    if len(layers) == 1 or f107_sfu <= fx[0]:
        value = vals[0]
        solar = "clamped" if f107_sfu < fx[0] - F107_TOLERANCE_SFU else "interpolated"
    else:
        k = int(np.clip(np.searchsorted(fx, f107_sfu) - 1, 0, fx.size - 2))
        w = (f107_sfu - fx[k]) / (fx[k + 1] - fx[k])
        value = (1 - w) * vals[k] + w * vals[k + 1]
        solar = "extrapolated" if f107_sfu > fx[-1] + F107_TOLERANCE_SFU else "interpolated"
    info = {
        "cell": cells[0],
        "layers": [
            {
                "name": layer["name"],
                "year": layer["year"],
                "f107_sfu": layer["f107_sfu"],
                "f_c_hz": v,
            }
            for layer, v in zip(layers, vals, strict=True)
        ],
        "f107_sfu": float(f107_sfu),
        "solar": solar,
    }
    return float(value), info


def map_validation(doc: dict[str, Any]) -> list[dict[str, Any]]:
    """Grid interpolation against the stations' own cutoffs, per layer.

    Parameters
    ----------
    doc : dict
        A map document with stations.

    Returns
    -------
    list of dict
        Per layer: ``name``, ``median_rel_error``, ``max_rel_error`` (of
        the interpolated recommended cutoff against the station's), and
        the station with the largest error.
    """
    out = []
    for layer in doc["layers"]:
        errs = []
        for st in layer["stations"]:
            if st["recommended_f_c_hz"] is None:
                continue
            v, _ = _bilinear(doc, layer["grid"]["recommended_f_c_hz"], st["lat_deg"], st["lon_deg"])
            errs.append((v / st["recommended_f_c_hz"] - 1.0, st["name"]))
        if not errs:
            continue
        e = np.array([x for x, _ in errs])
        worst = max(errs, key=lambda x: abs(x[0]))
        out.append(
            {
                "name": layer["name"],
                "median_abs_rel_error": round(float(np.median(np.abs(e))), 4),
                "max_abs_rel_error": round(float(np.max(np.abs(e))), 4),
                "worst_station": worst[1],
                "worst_rel_error": round(float(worst[0]), 4),
            }
        )
    return out


def nearest_map_station(doc: dict[str, Any], lat_deg: float, lon_deg: float) -> dict[str, Any]:
    """Nearest reference station of the map and its distance (first layer's entry).

    Parameters
    ----------
    doc : dict
        A map document.
    lat_deg, lon_deg : float
        Position, degrees.

    Returns
    -------
    dict
        ``station``, ``station_distance_deg`` and, per layer, the station's
        recommended cutoff (``station_f_c_hz``).
    """
    cands = [Station(s["name"], s["lat_deg"], s["lon_deg"]) for s in doc["layers"][0]["stations"]]
    if not cands:
        return {}
    st, dist = nearest_station(lat_deg, lon_deg, cands)
    return {
        "station": st.name,
        "station_distance_deg": float(dist),
        "station_f_c_hz": {
            layer["name"]: next(
                s["recommended_f_c_hz"] for s in layer["stations"] if s["name"] == st.name
            )
            for layer in doc["layers"]
        },
    }
