"""Batch cutoff runs: days x satellites for a station, and the station map (Dask, cached).

(method.md section 2, steps 6-7.) One **task** is one station-day: the slant
delays of every satellite (one PyIRI grid per day), then one cutoff per
satellite series (one day, replicated over 7 sidereal days). Tasks run on a
Dask ``distributed`` cluster: by default a :class:`~dask.distributed.LocalCluster`
of ``workers`` single-threaded processes, or any running scheduler given by
its address (its workers need psdbound installed); ``workers=0`` runs them
in this process without Dask (debugging, tiny runs). Whatever is opened is
closed.

Results are cached on disk per task, in ``cache_dir`` (default
``$PSDBOUND_CACHE`` or ``~/.cache/psdbound/cutoff``), keyed by a SHA-256 of
every input that changes the result: station, date, every
:class:`CutoffSettings` field, the orbit source (nominal constellation id,
or the file's name and content hash), the satellite subset, the psdbound
version and the cache schema. A second run with the same inputs reads the
cache and submits nothing. Files are written atomically (temporary name,
then rename), so concurrent runs cannot leave a torn entry.

The per-station summary reports mean, min and max f_c over all series; the
recommended cutoff is the maximum (the thesis's choice: it removes the
fastest ionospheric dynamics met).
"""

from __future__ import annotations

import calendar
import csv
import dataclasses
import datetime as _dt
import hashlib
import io
import json
import logging
import os
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.errors import InputError, NoDataError
from psdbound.ionosphere.constellation import nominal_constellation
from psdbound.ionosphere.cutoff import (
    CRITERIA,
    DEFAULT_DROP_DB,
    DEFAULT_VARIANCE_M2,
    MIN_ARC_S,
    MIN_SERIES_SAMPLES,
    REFERENCES,
    one_day_series,
    series_cutoff,
)
from psdbound.ionosphere.envelope import Envelope
from psdbound.ionosphere.iri import (
    DEFAULT_F107_SFU,
    DEFAULT_SHELL_HEIGHT_KM,
    FREQUENCIES_HZ,
    IRI_MODELS,
    METHODS,
    parse_date,
    simulate_slant_delay,
    validate_station,
)
from psdbound.ionosphere.stations import MAP_STATIONS, Station, nearest_station

__all__ = [
    "CACHE_SCHEMA",
    "CutoffMap",
    "CutoffSettings",
    "StationCutoffs",
    "default_cache_dir",
    "map_cutoffs",
    "select_days",
    "station_cutoffs",
]

#: Version of the cache entry layout; bump when results change meaning.
CACHE_SCHEMA = 2
_log = logging.getLogger(__name__)


@dataclass(frozen=True)
class CutoffSettings:
    """Every setting of a cutoff run besides station, dates and orbit source.

    Simulation: ``f107_sfu``, ``elevation_mask_deg``, ``method``,
    ``iri_model``, ``frequency_hz``, ``second_frequency_hz``, ``sampling_s``,
    ``alt_range_km``, ``shell_height_km``, ``grid_size``, ``ut_step_h``,
    ``ray_stride`` (see :func:`~psdbound.ionosphere.iri.simulate_slant_delay`).
    Spectrum and criterion: ``copies``, ``oversample``, ``nyquist_fraction``,
    ``criterion``, ``drop_db``, ``reference``, ``variance_m2``, ``degree``,
    ``quantile``, ``envelope_method``, ``bins_per_decade``
    (see :func:`~psdbound.ionosphere.cutoff.series_cutoff`). ``systems``
    picks the nominal constellation when no orbit file is given;
    ``min_arc_s`` drops shorter arcs from each one-day series and
    ``min_samples`` is the shortest one-day series analysed (shorter ones are
    listed as skipped); see :func:`~psdbound.ionosphere.cutoff.one_day_series`.
    """

    f107_sfu: float = DEFAULT_F107_SFU
    elevation_mask_deg: float = 10.0
    method: str = "line-of-sight"
    iri_model: str = "ursi"
    frequency_hz: float = FREQUENCIES_HZ["L1"]
    second_frequency_hz: float | None = None
    sampling_s: float = 12.0
    alt_range_km: tuple[float, float] = (60.0, 2000.0)
    shell_height_km: float = DEFAULT_SHELL_HEIGHT_KM
    grid_size: int = 21
    ut_step_h: float = 0.5
    ray_stride: int = 5
    systems: str = "G"
    copies: int = 7
    oversample: float = 1.0
    nyquist_fraction: float = 0.99
    criterion: str = "relative"
    drop_db: float = DEFAULT_DROP_DB
    reference: str = "psd"
    variance_m2: float = DEFAULT_VARIANCE_M2
    degree: int = 3
    quantile: float = 0.99
    envelope_method: str = "quantreg"
    bins_per_decade: float = 20.0
    min_samples: int = MIN_SERIES_SAMPLES
    min_arc_s: float = MIN_ARC_S

    def validate(self) -> None:
        """Raise :class:`InputError` for an unknown choice or an out-of-range number."""
        checks = [
            (self.method in METHODS, f"method {self.method!r} not in {METHODS}"),
            (self.iri_model in IRI_MODELS, f"iri_model {self.iri_model!r} not in {IRI_MODELS}"),
            (self.criterion in CRITERIA, f"criterion {self.criterion!r} not in {CRITERIA}"),
            (self.reference in REFERENCES, f"reference {self.reference!r} not in {REFERENCES}"),
            (
                50.0 <= self.f107_sfu <= 400.0,
                f"F10.7 = {self.f107_sfu} sfu is outside the plausible range 50-400 sfu",
            ),
            (
                0.0 <= self.elevation_mask_deg < 90.0,
                f"elevation mask {self.elevation_mask_deg} deg is out of range: expected "
                "0 <= mask < 90",
            ),
            (self.copies >= 1, f"copies = {self.copies} must be at least 1"),
            (self.drop_db > 0, f"drop_db = {self.drop_db} must be positive"),
            (self.variance_m2 > 0, f"variance_m2 = {self.variance_m2} must be positive"),
            (set(self.systems) <= {"G", "E"} and self.systems, "systems must be G, E or GE"),
            (self.degree >= 0, f"envelope degree {self.degree} must be non-negative"),
            (0.5 <= self.quantile <= 1.0, f"quantile {self.quantile} must be in [0.5, 1]"),
            (self.min_arc_s >= 0, f"min_arc_s = {self.min_arc_s} must be non-negative"),
        ]
        for ok, message in checks:
            if not ok:
                raise InputError(message)

    def series_options(self) -> dict[str, Any]:
        """Return the keyword options of :func:`series_cutoff` for these settings."""
        return {
            "dt_s": self.sampling_s,
            "copies": self.copies,
            "oversample": self.oversample,
            "nyquist_fraction": self.nyquist_fraction,
            "criterion": self.criterion,
            "drop_db": self.drop_db,
            "reference": self.reference,
            "variance_m2": self.variance_m2,
            "degree": self.degree,
            "quantile": self.quantile,
            "envelope_method": self.envelope_method,
            "bins_per_decade": self.bins_per_decade,
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the settings."""
        d = dataclasses.asdict(self)
        d["alt_range_km"] = list(self.alt_range_km)
        return d


def default_cache_dir() -> Path:
    """``$PSDBOUND_CACHE`` if set, else ``~/.cache/psdbound/cutoff``."""
    env = os.environ.get("PSDBOUND_CACHE")
    return Path(env) if env else Path.home() / ".cache" / "psdbound" / "cutoff"


def select_days(year: int, spec: str = "first-monday-each-month") -> list[_dt.date]:
    """Days of a run.

    Parameters
    ----------
    year : int
        Year of the named selections.
    spec : str, default "first-monday-each-month"
        ``"first-monday-each-month"``: the Monday of the first full
        (Monday-Sunday) week of each month, i.e. the first Monday (the
        thesis's choice); ``"first-monday-of-MM"`` for one month; or a
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
    if text == "first-monday-each-month" or text.startswith("first-monday-of-"):
        if not isinstance(year, int) or isinstance(year, bool):
            raise InputError(f"year {year!r} must be an integer")
        months = range(1, 13)
        if text.startswith("first-monday-of-"):
            try:
                months = [int(text.rsplit("-", 1)[1])]
            except ValueError:
                raise InputError(f"cannot read the month in {text!r}") from None
            if not 1 <= months[0] <= 12:
                raise InputError(f"month {months[0]} in {text!r} is not 1-12")
        days = []
        for m in months:
            first = _dt.date(year, m, 1) if 1 <= year <= 9999 else None
            if first is None:
                raise InputError(f"year {year} is not a calendar year")
            offset = (calendar.MONDAY - first.weekday()) % 7
            days.append(parse_date(first + _dt.timedelta(days=offset)))
        return days
    parts = [p.strip() for p in text.split(",") if p.strip()]
    if not parts:
        raise InputError(
            f"unknown day selection {spec!r}: use first-monday-each-month or "
            "YYYY-MM-DD[,YYYY-MM-DD...]"
        )
    return [parse_date(p) for p in parts]


@dataclass
class StationCutoffs:
    """Per-series cutoffs of one station over its days, and their summary.

    Attributes
    ----------
    name : str
        Station name.
    lat_deg, lon_deg, height_m : float
        Station position.
    rows : list of dict
        One per analysed series: ``date``, ``sat``, ``f_c_hz``,
        ``tau_c_min``, ``reached``, ``n_samples``, ``peak_hz``,
        ``peak_psd_m2_hz``, ``threshold_m2_hz``, ``residual_m2``,
        ``variance_m2`` and the ``envelope`` (dict).
    skipped : list of dict
        Series not analysed (``date``, ``sat``, ``reason``), and days
        without any satellite above the mask.
    settings : CutoffSettings
        The run's settings.
    orbit_source, orbit_description : str
        What gave the satellite positions (recorded with the results).
    days : list of str
        Days requested (``YYYY-MM-DD``).
    from_cache : list of bool
        Per day, whether the result came from the cache.
    elapsed_s : float
        Wall time of the run, s.
    series_by_date : dict
        Per day, the simulated delays (``t_gps_s``, ``sats``, ``delay_m``
        with NaN below the mask) when kept, else None.
    """

    name: str
    lat_deg: float
    lon_deg: float
    height_m: float
    rows: list[dict]
    skipped: list[dict]
    settings: CutoffSettings
    orbit_source: str
    orbit_description: str
    days: list[str]
    from_cache: list[bool] = field(default_factory=list)
    elapsed_s: float = 0.0
    series_by_date: dict[str, dict | None] = field(default_factory=dict, repr=False)

    @property
    def f_c_hz(self) -> np.ndarray:
        """Cutoffs of all series, Hz."""
        return np.array([r["f_c_hz"] for r in self.rows], dtype=float)

    @property
    def envelopes(self) -> list[Envelope]:
        """Envelopes of all series."""
        return [Envelope.from_dict(r["envelope"]) for r in self.rows]

    def summary(self) -> dict[str, Any]:
        """Mean, min, max and recommended (= max) f_c, with counts and provenance."""
        fc = self.f_c_hz
        out: dict[str, Any] = {
            "name": self.name,
            "lat_deg": self.lat_deg,
            "lon_deg": self.lon_deg,
            "n_days": len(self.days),
            "n_series": int(fc.size),
            "n_skipped": len(self.skipped),
            "criterion": self.settings.criterion,
            "orbit_source": self.orbit_source,
        }
        if fc.size:
            out.update(
                mean_f_c_hz=float(fc.mean()),
                min_f_c_hz=float(fc.min()),
                max_f_c_hz=float(fc.max()),
                recommended_f_c_hz=float(fc.max()),
                recommended_tau_c_min=float(1.0 / fc.max() / 60.0),
                n_not_reached=int(sum(not r["reached"] for r in self.rows)),
            )
        else:
            out.update(
                mean_f_c_hz=float("nan"),
                min_f_c_hz=float("nan"),
                max_f_c_hz=float("nan"),
                recommended_f_c_hz=float("nan"),
                recommended_tau_c_min=float("nan"),
                n_not_reached=0,
            )
        return out

    def table_csv(self) -> str:
        """Per-series table as CSV text."""
        cols = [
            "date", "sat", "f_c_hz", "tau_c_min", "reached", "n_samples", "peak_hz",
            "peak_psd_m2_hz", "threshold_m2_hz", "residual_m2", "variance_m2",
        ]  # fmt: skip
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(cols)
        for r in self.rows:
            w.writerow([_fmt(r[c]) for c in cols])
        return buf.getvalue()

    def to_json_dict(self) -> dict[str, Any]:
        """Everything as a JSON-ready dict (summary, settings, provenance, rows)."""
        return {
            "summary": self.summary(),
            "station": {
                "name": self.name,
                "lat_deg": self.lat_deg,
                "lon_deg": self.lon_deg,
                "height_m": self.height_m,
            },
            "days": self.days,
            "orbit_source": self.orbit_source,
            "orbit_description": self.orbit_description,
            "settings": self.settings.to_dict(),
            "from_cache": self.from_cache,
            "elapsed_s": self.elapsed_s,
            "rows": self.rows,
            "skipped": self.skipped,
        }


@dataclass
class CutoffMap:
    """Recommended cutoffs over a set of stations, with nearest-station lookup.

    Attributes
    ----------
    stations : list of StationCutoffs
        One per station, in input order.
    elapsed_s : float
        Wall time of the run, s.
    """

    stations: list[StationCutoffs]
    elapsed_s: float = 0.0

    def rows(self) -> list[dict[str, Any]]:
        """One summary dict per station."""
        return [s.summary() for s in self.stations]

    def nearest(self, lat_deg: float, lon_deg: float) -> tuple[dict[str, Any], float]:
        """Summary of the station nearest a position, and its distance (deg).

        Parameters
        ----------
        lat_deg, lon_deg : float
            Position, degrees.

        Returns
        -------
        summary : dict
            The nearest station's summary (``recommended_f_c_hz`` ...).
        distance_deg : float
            Great-circle distance, degrees.
        """
        cands = [Station(s.name, s.lat_deg, s.lon_deg) for s in self.stations]
        st, d = nearest_station(lat_deg, lon_deg, cands)
        return self.stations[cands.index(st)].summary(), d

    def table_csv(self) -> str:
        """Station table as CSV text."""
        cols = [
            "name", "lat_deg", "lon_deg", "n_series", "mean_f_c_hz", "min_f_c_hz",
            "max_f_c_hz", "recommended_f_c_hz", "recommended_tau_c_min", "n_skipped",
        ]  # fmt: skip
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(cols)
        for r in self.rows():
            w.writerow([_fmt(r[c]) for c in cols])
        return buf.getvalue()

    def to_json_dict(self) -> dict[str, Any]:
        """JSON-ready dict: station summaries, settings and provenance."""
        first = self.stations[0] if self.stations else None
        return {
            "stations": self.rows(),
            "days": first.days if first else [],
            "settings": first.settings.to_dict() if first else {},
            "orbit_source": first.orbit_source if first else "",
            "orbit_description": first.orbit_description if first else "",
            "elapsed_s": self.elapsed_s,
        }


def _fmt(v: Any) -> Any:
    if isinstance(v, float):
        return f"{v:.6g}"
    return v


def _orbit_identity(orbit: Any) -> tuple[str, str]:
    """(source id for cache keys and results, human description)."""
    sid = getattr(orbit, "source_id", None)
    if sid:
        return str(sid), str(getattr(orbit, "description", sid))
    path = getattr(orbit, "path", None)
    digest = "?"
    if path is not None and Path(path).is_file():
        digest = hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    kind = type(orbit).__name__
    return f"{kind}:{Path(str(path)).name}:{digest}", f"{kind} from {path}"


def _task_key(spec: dict[str, Any]) -> str:
    from psdbound import __version__

    payload = {k: v for k, v in spec.items() if k not in ("orbit", "keep_series")}
    payload["psdbound"] = __version__
    payload["schema"] = CACHE_SCHEMA
    text = json.dumps(payload, sort_keys=True, default=str)
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def _day_task(spec: dict[str, Any]) -> dict[str, Any]:
    """Simulate one station-day and compute every satellite's cutoff (runs on a worker)."""
    s = CutoffSettings(
        **{**spec["settings"], "alt_range_km": tuple(spec["settings"]["alt_range_km"])}
    )
    out: dict[str, Any] = {"date": spec["date"], "rows": [], "skipped": []}
    try:
        sd = simulate_slant_delay(
            spec["lat_deg"],
            spec["lon_deg"],
            spec["date"],
            orbit=spec["orbit"],
            height_m=spec["height_m"],
            satellites=spec["satellites"],
            f107_sfu=s.f107_sfu,
            elevation_mask_deg=s.elevation_mask_deg,
            method=s.method,
            frequency_hz=s.frequency_hz,
            second_frequency_hz=s.second_frequency_hz,
            sampling_s=s.sampling_s,
            iri_model=s.iri_model,
            alt_range_km=s.alt_range_km,
            shell_height_km=s.shell_height_km,
            grid_size=s.grid_size,
            ut_step_h=s.ut_step_h,
            ray_stride=s.ray_stride,
        )
    except NoDataError as exc:
        out["skipped"].append({"date": spec["date"], "sat": "*", "reason": exc.reason})
        return out
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
        r = series_cutoff(t, y, **s.series_options())
        row = {"date": spec["date"], "sat": sat}
        d = r.to_dict()
        d.pop("settings")
        d.pop("criterion")
        row.update(d)
        out["rows"].append(row)
    if spec.get("keep_series"):
        out["series"] = {
            "t_gps_s": sd.t_gps_s,
            "sats": list(sd.sats),
            "delay_m": sd.delay_m,
        }
    return out


def _cache_paths(cache_dir: Path, key: str) -> tuple[Path, Path]:
    return cache_dir / f"{key}.json", cache_dir / f"{key}.npz"


def _cache_read(cache_dir: Path, key: str, need_series: bool) -> dict[str, Any] | None:
    pj, pn = _cache_paths(cache_dir, key)
    if not pj.is_file() or (need_series and not pn.is_file()):
        return None
    try:
        out = json.loads(pj.read_text())
        if need_series:
            with np.load(pn) as z:
                out["series"] = {
                    "t_gps_s": z["t_gps_s"],
                    "sats": [str(s) for s in z["sats"]],
                    "delay_m": z["delay_m"],
                }
    except (OSError, ValueError, KeyError) as exc:  # torn or foreign file: recompute
        _log.warning("ignoring unreadable cache entry %s: %s", pj, exc)
        return None
    return out


def _cache_write(cache_dir: Path, key: str, result: dict[str, Any]) -> None:
    cache_dir.mkdir(parents=True, exist_ok=True)
    pj, pn = _cache_paths(cache_dir, key)
    series = result.get("series")
    if series is not None:
        tmp = pn.with_name(pn.stem + f".{os.getpid()}.tmp.npz")
        np.savez_compressed(
            tmp,
            t_gps_s=series["t_gps_s"],
            sats=np.array(series["sats"]),
            delay_m=series["delay_m"],
        )
        os.replace(tmp, pn)
    body = {k: v for k, v in result.items() if k != "series"}
    tmp = pj.with_name(pj.name + f".{os.getpid()}.tmp")
    tmp.write_text(json.dumps(body, default=_json_default))
    os.replace(tmp, pj)


def _json_default(o: Any) -> Any:
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _run_tasks(
    specs: list[dict[str, Any]],
    *,
    workers: int,
    scheduler: str | None,
    progress: Callable[[int, int], None] | None,
) -> list[dict[str, Any]]:
    """Run day tasks on Dask (or in-process for workers=0 without a scheduler)."""
    if not specs:
        return []
    if scheduler is None and workers == 0:
        out = []
        for i, spec in enumerate(specs):
            out.append(_day_task(spec))
            if progress:
                progress(i + 1, len(specs))
        return out
    from dask.distributed import Client, LocalCluster, as_completed

    cluster = None
    if scheduler is None:
        if workers < 0:
            raise InputError(f"workers = {workers} must be >= 0")
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            silence_logs=logging.ERROR,
        )
        client = Client(cluster)
    else:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError) as exc:
            raise InputError(f"cannot reach the Dask scheduler at {scheduler!r}: {exc}") from None
    try:
        futures = client.map(_day_task, specs, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results: list[dict[str, Any] | None] = [None] * len(specs)
        done = 0
        for fut in as_completed(futures):
            results[index[fut.key]] = fut.result()
            done += 1
            if progress:
                progress(done, len(specs))
        return [r for r in results if r is not None]
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def _prepare_orbit(orbit: Any, settings: CutoffSettings) -> Any:
    return nominal_constellation(settings.systems) if orbit is None else orbit


def _specs_for(
    station: Station,
    height_m: float,
    days: Sequence[_dt.date],
    orbit: Any,
    satellites: Sequence[str] | None,
    settings: CutoffSettings,
    keep_series: bool,
) -> list[dict[str, Any]]:
    source, _ = _orbit_identity(orbit)
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


def _execute(
    groups: list[tuple[Station, float, list[dict[str, Any]]]],
    *,
    orbit: Any,
    settings: CutoffSettings,
    workers: int,
    scheduler: str | None,
    cache_dir: str | os.PathLike[str] | None,
    use_cache: bool,
    progress: Callable[[int, int], None] | None,
) -> list[StationCutoffs]:
    t_start = time.perf_counter()
    cdir = Path(cache_dir) if cache_dir is not None else default_cache_dir()
    source, description = _orbit_identity(orbit)
    flat = [(g, spec) for g, (_, _, specs) in enumerate(groups) for spec in specs]
    keys = [_task_key(spec) for _, spec in flat]
    results: list[dict[str, Any] | None] = [None] * len(flat)
    cached = [False] * len(flat)
    if use_cache:
        for i, ((_, spec), key) in enumerate(zip(flat, keys, strict=True)):
            hit = _cache_read(cdir, key, bool(spec["keep_series"]))
            if hit is not None:
                results[i], cached[i] = hit, True
    todo = [i for i, r in enumerate(results) if r is None]
    computed = _run_tasks(
        [flat[i][1] for i in todo], workers=workers, scheduler=scheduler, progress=progress
    )
    for i, res in zip(todo, computed, strict=True):
        results[i] = res
        if use_cache:
            _cache_write(cdir, keys[i], res)
    elapsed = time.perf_counter() - t_start
    out = []
    for g, (station, height_m, specs) in enumerate(groups):
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
            from_cache=[cached[i] for i in idx],
            elapsed_s=elapsed,
            series_by_date={results[i]["date"]: results[i].get("series") for i in idx},
        )
        out.append(sc)
    return out


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
    keep_series: bool = True,
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
    keep_series : bool, default True
        Keep (and cache) the simulated delays, for figures.
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
    orbit = _prepare_orbit(orbit, settings)
    station = Station(name or f"{lat:.2f},{lon:.2f}", lat, lon)
    specs = _specs_for(station, height_m, day_list, orbit, satellites, settings, keep_series)
    (res,) = _execute(
        [(station, height_m, specs)],
        orbit=orbit,
        settings=settings,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    if not res.rows:
        reasons = sorted({s["reason"] for s in res.skipped}) or ["no series"]
        raise NoDataError(f"no satellite series to analyse at {station.name}: {'; '.join(reasons)}")
    return res


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
    orbit = _prepare_orbit(orbit, settings)
    t0 = time.perf_counter()
    groups = [
        (st, 0.0, _specs_for(st, 0.0, day_list, orbit, satellites, settings, False))
        for st in stations
    ]
    res = _execute(
        groups,
        orbit=orbit,
        settings=settings,
        workers=workers,
        scheduler=scheduler,
        cache_dir=cache_dir,
        use_cache=use_cache,
        progress=progress,
    )
    return CutoffMap(stations=res, elapsed_s=time.perf_counter() - t0)
