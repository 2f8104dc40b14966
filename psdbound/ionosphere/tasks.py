"""The station-day task of batch cutoff runs, its cache key and its cache.

One **task** is one station-day (docs/method/cutoff.rst, step 6-7): the slant
delays of every satellite (one PyIRI grid per day), then one cutoff per
satellite series: by the time-domain residual criterion (all series of the
day at once, :func:`~psdbound.ionosphere.residual.residual_cutoffs`) or by
a periodogram criterion (one day replicated over 7 sidereal days,
:func:`~psdbound.ionosphere.cutoff.series_cutoff`).
:func:`station_day` runs it on a Dask worker from a plain dict
(:func:`day_specs`), and returns a dict: ``date``, ``rows`` (one per
analysed series), ``skipped`` and, when the delays are kept, ``t_gps_s``,
``sats`` and ``delay_m``.

Results are cached by :func:`day_cache` (a
:class:`~psdbound.compute.DiskCache`) under :func:`day_key`, a SHA-256 of
every input that changes the result: station, date, every
:class:`~psdbound.ionosphere.settings.CutoffSettings` field, the orbit
source (nominal constellation id, or the file's name and content hash), the
satellite subset, the psdbound version and :data:`CACHE_SCHEMA`.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from psdbound.compute import DiskCache, cache_key
from psdbound.errors import NoDataError
from psdbound.ionosphere.cutoff import one_day_series, series_cutoff
from psdbound.ionosphere.residual import ResidualCutoff, residual_cutoffs
from psdbound.ionosphere.settings import CutoffSettings
from psdbound.ionosphere.slant import simulate_slant_delay
from psdbound.ionosphere.stations import Station, validate_station
from psdbound.version import __version__, code_digest

__all__ = [
    "CACHE_SCHEMA",
    "SERIES_ARRAYS",
    "day_cache",
    "day_key",
    "day_specs",
    "orbit_identity",
    "residual_row",
    "station_day",
]

#: Version of the cache entry layout; bump when results change meaning or layout.
CACHE_SCHEMA = 4
#: Array fields of a task result that keeps the simulated delays.
SERIES_ARRAYS = ("delay_m", "t_gps_s")


def orbit_identity(orbit: Any) -> tuple[str, str]:
    """Identify an orbit source for cache keys and results.

    Parameters
    ----------
    orbit : OrbitSource
        Nominal constellation or almanac (with ``source_id``), or an object
        read from a file (with ``path``).

    Returns
    -------
    source : str
        Id of the source (a file's type, name and content hash).
    description : str
        Human-readable description.
    """
    sid = getattr(orbit, "source_id", None)
    if sid:
        return str(sid), str(getattr(orbit, "description", sid))
    path = getattr(orbit, "path", None)
    digest = "?"
    if path is not None and Path(path).is_file():
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    kind = type(orbit).__name__
    return f"{kind}:{Path(str(path)).name}:{digest}", f"{kind} from {path}"


def day_specs(
    station: Station,
    height_m: float,
    days: Sequence[_dt.date],
    orbit: Any,
    satellites: Sequence[str] | None,
    settings: CutoffSettings,
    keep_series: bool,
) -> list[dict[str, Any]]:
    """Build the task inputs of one station over its days.

    Parameters
    ----------
    station : Station
        Name and position.
    height_m : float
        Station height, m.
    days : sequence of datetime.date
        Days (UTC).
    orbit : OrbitSource
        Orbit source (sent to the workers).
    satellites : sequence of str or None
        Satellite subset.
    settings : CutoffSettings
        Run settings.
    keep_series : bool
        Return (and cache) the simulated delays.

    Returns
    -------
    list of dict
        One picklable spec per day, for :func:`station_day`.
    """
    source, _ = orbit_identity(orbit)
    lat, lon = validate_station(station.lat_deg, station.lon_deg)
    return [
        {
            "lat_deg": round(lat, 8),
            "lon_deg": round(lon, 8),
            "height_m": float(height_m),
            "date": d.isoformat(),
            "orbit_source": source,
            "satellites": None if satellites is None else sorted(satellites),
            "settings": settings.to_dict(),
            "orbit": orbit,
            "keep_series": keep_series,
        }
        for d in days
    ]


def day_key(spec: dict[str, Any]) -> str:
    """Return the cache key of a station-day spec (orbit object and ``keep_series`` excluded)."""
    payload = {k: v for k, v in spec.items() if k not in ("orbit", "keep_series")}
    payload["psdbound"] = __version__
    payload["code"] = code_digest()
    payload["schema"] = CACHE_SCHEMA
    return cache_key(payload)


def _wanted_arrays(spec: dict[str, Any]) -> tuple[str, ...]:
    return SERIES_ARRAYS if spec.get("keep_series") else ()


def day_cache(directory: str | Path) -> DiskCache:
    """Return the station-day cache in ``directory``.

    A spec that keeps the delays needs them in the entry (else it is a miss
    and is recomputed); one that does not loads only the JSON part.

    Parameters
    ----------
    directory : str or path-like
        Cache directory.

    Returns
    -------
    DiskCache
    """
    return DiskCache(directory, key=day_key, arrays=_wanted_arrays)


def residual_row(date: str, sat: str, r: ResidualCutoff) -> dict[str, Any]:
    """Return the result row of one series cut off by the residual criterion.

    Parameters
    ----------
    date, sat : str
        Day and satellite.
    r : ResidualCutoff
        Its cutoff.

    Returns
    -------
    dict
        ``date``, ``sat``, the scalar fields of :meth:`ResidualCutoff.to_dict`
        and the scanned curve (``curve_f_hz``, ``curve_rms_m`` as lists).
    """
    return {
        "date": date,
        "sat": sat,
        **r.to_dict(),
        "curve_f_hz": [float(v) for v in r.curve_f_hz],
        "curve_rms_m": [float(v) for v in r.curve_rms_m],
    }


def station_day(spec: dict[str, Any]) -> dict[str, Any]:
    """Simulate one station-day and compute every satellite's cutoff (runs on a worker).

    Parameters
    ----------
    spec : dict
        One of :func:`day_specs`.

    Returns
    -------
    dict
        ``date``, ``rows``, ``skipped`` and, with ``keep_series``, the
        delays ``t_gps_s``, ``sats``, ``delay_m`` (NaN below the mask).
    """
    s = CutoffSettings.from_mapping(spec["settings"])
    out: dict[str, Any] = {"date": spec["date"], "rows": [], "skipped": []}
    try:
        sd = simulate_slant_delay(
            spec["lat_deg"],
            spec["lon_deg"],
            spec["date"],
            orbit=spec["orbit"],
            height_m=spec["height_m"],
            satellites=spec["satellites"],
            **s.simulation_options(),
        )
    except NoDataError as exc:
        out["skipped"].append({"date": spec["date"], "sat": "*", "reason": exc.reason})
        return out
    kept = []
    for j, sat in enumerate(sd.sats):
        t, y = one_day_series(sd.t_gps_s, sd.delay_m[j], min_arc_s=s.min_arc_s)
        if t.size < s.min_samples:
            out["skipped"].append(
                {
                    "date": spec["date"],
                    "sat": sat,
                    "reason": f"{t.size} samples in arcs of at least {s.min_arc_s:g} s, "
                    f"fewer than {s.min_samples}",
                }
            )
            continue
        kept.append((sat, t, y))
    if s.criterion == "residual":
        found = residual_cutoffs([(t, y) for _, t, y in kept], **s.residual_options())
        out["rows"] = [
            residual_row(spec["date"], sat, r) for (sat, _, _), r in zip(kept, found, strict=True)
        ]
    else:
        for sat, t, y in kept:
            d = series_cutoff(t, y, **s.series_options()).to_dict()
            d.pop("settings")
            d.pop("criterion")
            out["rows"].append({"date": spec["date"], "sat": sat, **d})
    if spec.get("keep_series"):
        out.update(t_gps_s=sd.t_gps_s, sats=list(sd.sats), delay_m=sd.delay_m)
    return out
