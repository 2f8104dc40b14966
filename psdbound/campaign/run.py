"""A campaign: many observation files, days and stations in one run on Dask.

:func:`plan_campaign` groups observation files by station and day and matches
navigation files to the days; :func:`run_campaign` runs every station-day as
a Dask task (:func:`psdbound.compute.run_tasks`, a local cluster by default
or any scheduler), cached by the hash of its inputs so that a re-run only
computes what changed, then pools each station's days and tests every day
against the bound of the station's other days (:func:`~psdbound.campaign.heldout.held_out`).
"""

from __future__ import annotations

import datetime as _dt
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.campaign.heldout import held_out
from psdbound.campaign.sidereal import repeat_warnings, sidereal_repeats
from psdbound.campaign.tasks import station_day_task
from psdbound.errors import InputError

__all__ = ["SCHEMA", "CampaignResult", "StationDay", "plan_campaign", "run_campaign"]

_GPS_EPOCH = _dt.datetime(1980, 1, 6)


@dataclass(frozen=True)
class StationDay:
    """The files of one station on one day (GPS calendar day of the first epoch)."""

    station: str
    day: str
    obs: tuple[str, ...]
    nav: str
    #: When several navigation files cover the day: which was used and why (else "").
    nav_note: str = ""


def _day_of(t_gps_s: float) -> _dt.date:
    return (_GPS_EPOCH + _dt.timedelta(seconds=float(t_gps_s))).date()


_Files = dict[tuple[str, str], list[tuple[str, float, float]]]


def _read_days(obs: Sequence[str], system: str) -> _Files:
    """Group observation files by (station, GPS day of the first epoch): (path, first, last)."""
    from psdbound.io import read_obs
    from psdbound.io.merge import station_key

    groups: _Files = {}
    for p in obs:
        o = read_obs(p, systems=system)
        if o.t_gps_s.size == 0:
            raise InputError("observation file holds no epoch", path=p)
        t0, t1 = float(o.t_gps_s[0]), float(o.t_gps_s[-1])
        groups.setdefault((station_key(o), _day_of(t0).isoformat()), []).append((p, t0, t1))
    return groups


def plan_campaign(
    obs: Sequence[str | os.PathLike[str]],
    nav: Sequence[str | os.PathLike[str]],
    *,
    system: str = "G",
) -> list[StationDay]:
    """Group observation files by station and day and match each day's navigation file.

    Parameters
    ----------
    obs : sequence of path
        Observation files (any stations, days and order).
    nav : sequence of path
        Navigation (or SP3) files, any names: each is read and matched to
        the observation day whose span it covers for ``system``
        (:func:`~psdbound.campaign.navmatch.match_nav`).
    system : str, default "G"
        Satellite system letter fitted (the observation files must hold it,
        the navigation file must cover it).

    Returns
    -------
    list of StationDay
        Sorted by station, then day.

    Raises
    ------
    InputError
        No file, a missing file, or a day that no navigation file covers
        (a day that several cover uses one, with a warning: see
        :func:`~psdbound.campaign.navmatch.match_nav`).
    """
    from psdbound.campaign.navmatch import nav_choice, orbit_span
    from psdbound.common.notices import warn

    if not obs:
        raise InputError("a campaign needs observation files")
    if not nav:
        raise InputError("a campaign needs navigation (or SP3) files: give --nav")
    navs = list(dict.fromkeys(os.fspath(n) for n in nav))
    obs_paths = [os.fspath(p) for p in obs]
    for p in [*obs_paths, *navs]:
        if not Path(p).is_file():
            raise InputError("file not found", path=p)
    spans = [orbit_span(n) for n in navs]
    plan = []
    for (st, d), files in sorted(_read_days(obs_paths, system).items()):
        paths = tuple(f[0] for f in files)
        span = (min(f[1] for f in files), max(f[2] for f in files))
        nav_path, note = nav_choice(paths, span, system, spans, station=st)
        if note:
            warn(note, path=" + ".join(paths))
        plan.append(StationDay(st, d, paths, nav_path, note))
    return plan


@dataclass
class CampaignResult:
    """Per-day results and verdicts, pooled bounds and verdicts per station, held-out tests.

    Attributes
    ----------
    days : list of dict
        One per station-day, without the PSD arrays: ``verdict`` and
        ``verdict_reasons`` (those of ``psdbound fit`` for the day),
        ``in_pool``, the files (``obs``, ``nav``), the bound or ``error``.
    stations : list of dict
        Per station: the pooled bound of its bounded days and its verdict
        (:func:`~psdbound.campaign.pool.pool_station`).
    held_out : list of dict
        Per pooled station-day: the bound of the station's other pooled days tested on it.
    n_computed, n_cached : int
        Station-days computed by this run and read from the cache.
    documents : list of dict or None
        Per day (in the order of ``days``), the result document of its fit
        (None when the day failed); not part of ``campaign.json``, the
        station-day reports are drawn from it.
    """

    days: list[dict[str, Any]]
    stations: list[dict[str, Any]]
    held_out: list[dict[str, Any]]
    n_computed: int = 0
    n_cached: int = 0
    meta: dict[str, Any] = field(default_factory=dict)
    documents: list[dict[str, Any] | None] = field(default_factory=list)

    @property
    def verdict(self) -> str:
        """``"bounded"`` when every station's pooled bound is bounded, else ``"not-bounded"``."""
        ok = self.stations and all(s["verdict"] == "bounded" for s in self.stations)
        return "bounded" if ok else "not-bounded"

    def to_dict(self) -> dict[str, Any]:
        """Return the ``campaign.json`` content (schema ``psdbound-campaign/2``)."""
        return {
            "schema": SCHEMA,
            "verdict": self.verdict,
            "stations": self.stations,
            "days": self.days,
            "held_out": self.held_out,
            "n_computed": self.n_computed,
            "n_cached": self.n_cached,
            **self.meta,
        }

    def summary(self) -> str:
        """Return a text summary: verdicts of the stations and days, and the held-out tests."""
        lines = [
            f"campaign verdict: {self.verdict.upper()}",
            f"{len(self.days)} station-days ({self.n_computed} computed, {self.n_cached} "
            f"from the cache); {len(self.stations)} station(s)",
        ]
        lines += [line for s in self.stations for line in _station_lines(s)]
        for d in self.days:
            lines.append(
                f"  {d['station']} {d['day']}: {d['verdict']}"
                + ("" if d["in_pool"] else " (not pooled)")
            )
            lines += [f"    reason: {x}" for x in d["verdict_reasons"]]
        lines += [f"  warning: {w}" for w in repeat_warnings(self.meta.get("sidereal_repeat", []))]
        lines += [
            f"  {k['station']} {k['day']}: fitted again keeping {k['n_spans']} span(s) "
            f"({k['kept_s'] / 60:.0f} min) that repeat with the sidereal day as multipath"
            for k in self.meta.get("sidereal_kept", [])
        ]
        for h in self.held_out:
            lines.append(
                f"  held out {h['station']} {h['day']}: windows covered "
                f"{100 * h['windows_covered_fraction']:.0f} %, worst excess "
                f"{h['worst_excess_db']:.1f} dB, KF max generalised eigenvalue "
                f"{h['kf_max_generalized_eigenvalue']:.2f} (windows bounded "
                f"{100 * h.get('kf_windows_bounded_fraction', float('nan')):.0f} %)"
            )
        return "\n".join(lines)


#: Schema name of ``campaign.json``.
SCHEMA = "psdbound-campaign/2"


def _station_lines(s: dict[str, Any]) -> list[str]:
    """Summary lines of one station: pooled bound, verdict and reasons, what is missing."""
    head = f"  {s['station']}: {s['verdict']}"
    if s["n_pooled"]:
        head += (
            f"; pooled over {s['n_pooled']} of {s['n_days']} day(s): sigma_GM "
            f"{1e3 * s['sigma_gm_m']:.2f} mm, tau {s['tau_s']:.1f} s, sigma_WN "
            f"{1e3 * s['sigma_wn_m']:.2f} mm"
        )
    lines = [head] + [f"    reason: {x}" for x in s["verdict_reasons"]]
    if s["comparison_note"]:
        lines.append(f"    {s['comparison_note']}")
    return lines


def _public(result: dict[str, Any], item: dict[str, Any], in_pool: bool) -> dict[str, Any]:
    """Return a day's entry in ``campaign.json``: no PSD arrays; its files; whether pooled."""
    out = {
        k: (v.tolist() if isinstance(v, np.ndarray) else v)
        for k, v in result.items()
        if not k.startswith("psd_") and k != "document"
    }
    out.update(obs=[Path(p).name for p in item["obs"]], nav=Path(item["nav"]).name, in_pool=in_pool)
    if item.get("nav_note"):
        out["nav_note"] = item["nav_note"]
    return out


def _day_options(options: dict[str, dict[str, Any]] | None) -> Any:
    """Return the FitConfig of the day options; refuse what a campaign cannot use."""
    from psdbound.pipeline.config import FitConfig

    options = options or {}
    if options.get("code_multipath", {}).get("codes"):
        raise InputError(
            "[code_multipath] is a fit option: a campaign pools the carrier-phase "
            "bounds only; run `psdbound fit --code-multipath` per day, or remove it"
        )
    cfg = FitConfig.from_dict(options, source="campaign options")
    if cfg.bound.rule != "pooled":
        raise InputError(
            f"bound rule {cfg.bound.rule!r}: a campaign pools the days' window "
            "spectra with the pooled rule; remove the envelope rule "
            "(--rule pooled, the default)"
        )
    return cfg


def run_campaign(
    obs: Sequence[str | os.PathLike[str]],
    nav: Sequence[str | os.PathLike[str]],
    *,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    options: dict[str, dict[str, Any]] | None = None,
    progress: Callable[[int, int], None] | None = None,
    sidereal_keep: bool = True,
) -> CampaignResult:
    """Fit every station-day on Dask, judge it, pool each station's bounded days, test held out.

    Parameters
    ----------
    obs, nav : sequence of path
        Observation and navigation files (see :func:`plan_campaign`).
    workers : int, default 2
        Local Dask workers (0: in this process). Ignored with ``scheduler``.
    scheduler : str, optional
        Address of a running Dask scheduler.
    cache_dir : path, optional
        Task cache (default :func:`psdbound.compute.default_cache_dir`
        ``("campaign")``); a station-day is recomputed only when its files
        (SHA-256) or options change.
    options : dict, optional
        :class:`~psdbound.pipeline.FitConfig` sections for every station-day
        (``inputs`` may set ``system`` and ``signals``; the files are the
        campaign's). The pooled bounds use the same ``bound`` options and the
        verdicts the same ``verdict`` options.
    progress : callable, optional
        ``progress(done, total)`` after each computed station-day.
    sidereal_keep : bool, default True
        Fit again, keeping them as multipath, the days whose spans screened
        as ionosphere repeat one sidereal day later on a neighbouring day
        (:mod:`psdbound.campaign.sidereal`; ``campaign.json``
        ``sidereal_kept``).

    Returns
    -------
    CampaignResult

    Raises
    ------
    InputError
        Bad files or options, a day without its navigation file (before
        anything is computed).
    """
    from psdbound.campaign.pool import pool_stations
    from psdbound.compute import lazy_client, run_tasks
    from psdbound.version import __version__

    cfg = _day_options(options)
    plan = plan_campaign(obs, nav, system=cfg.inputs.system)
    items = [_item(sd, options or {}) for sd in plan]
    # one client for both passes (a second local cluster, forked after the first, can hang)
    with lazy_client(workers=workers, scheduler=scheduler) as client:

        def fit_days(todo: list[dict[str, Any]]) -> Any:
            return run_tasks(
                station_day_task,
                todo,
                workers=workers,
                scheduler=scheduler,
                cache=_cache(cache_dir),
                progress=progress,
                client=client,
            )

        run = fit_days(items)
        results = list(run.results)
        first = [r.get("document") for r in results]
        repeats = sidereal_repeats(items, first)
        kept, n_again = (
            _keep_repeating_spans(items, results, fit_days) if sidereal_keep else ([], 0)
        )
    stations, pooled = pool_stations(results, bound_options=cfg.bound, verdict_options=cfg.verdict)
    days = [
        _public(r, it, any(r is p for p in pooled)) for r, it in zip(results, items, strict=True)
    ]
    return CampaignResult(
        days=days,
        stations=stations,
        held_out=held_out(pooled, options=cfg.bound),
        n_computed=run.n_computed + n_again,
        n_cached=run.n_cached,
        meta={
            "files": [
                {"station": it["station"], "day": it["day"], "sha256": it["sha256"]} for it in items
            ],
            "options": options or {},
            "psdbound": __version__,
            "sidereal_repeat": repeats,
            "sidereal_kept": kept,
        },
        documents=[r.get("document") for r in results],
    )


def _keep_repeating_spans(
    items: list[dict[str, Any]], results: list[dict[str, Any]], fit_days: Callable[..., Any]
) -> tuple[list[dict[str, Any]], int]:
    """Fit again the days whose ionosphere spans repeat with the sidereal day, keeping them.

    The spans that repeat on a neighbouring day one sidereal day later
    (:func:`~psdbound.campaign.sidereal.repeating_spans`) are passed as the
    screening's ``keep_spans``; ``items`` and ``results`` are updated in
    place. Returns one entry per day fitted again (station, day, spans kept
    and their time, s) and the number of days computed (not from the cache).
    """
    from psdbound.campaign.sidereal import repeating_spans

    keep = repeating_spans(items, [r.get("document") for r in results])
    if not keep:
        return [], 0
    again = {i: _with_keep_spans(items[i], spans) for i, spans in keep.items()}
    run = fit_days(list(again.values()))
    out = []
    for (i, item), result in zip(again.items(), run.results, strict=True):
        items[i], results[i] = item, result
        spans = keep[i]
        out.append(
            {
                "station": item["station"],
                "day": item["day"],
                "n_spans": len(spans),
                "kept_s": float(sum(b - a for _, a, b in spans)),
            }
        )
    return out, run.n_computed


def _with_keep_spans(item: dict[str, Any], spans: list[tuple[str, float, float]]) -> dict:
    """Return a station-day item whose screening keeps ``spans`` as multipath."""
    options = {k: dict(v) for k, v in item["options"].items()}
    options.setdefault("screening", {})["keep_spans"] = [list(s) for s in spans]
    return {**item, "options": options}


def _item(sd: StationDay, options: dict[str, dict[str, Any]]) -> dict[str, Any]:
    """Return the Dask task item of one station-day (files, their SHA-256, the options)."""
    from psdbound.common import file_sha256

    digests = {Path(p).name: file_sha256(p) for p in (*sd.obs, sd.nav)}
    return {
        "station": sd.station,
        "day": sd.day,
        "obs": list(sd.obs),
        "nav": sd.nav,
        "nav_note": sd.nav_note,
        "sha256": digests,
        "options": options,
    }


def _cache(cache_dir: str | os.PathLike[str] | None) -> Any:
    """Return the station-day task cache (key: the files' hashes, the options, the code)."""
    from psdbound.compute import DiskCache, cache_key, default_cache_dir
    from psdbound.version import __version__, code_digest

    return DiskCache(
        cache_dir or default_cache_dir("campaign"),
        key=lambda it: cache_key(
            {
                "task": "station-day",
                "version": __version__,
                "code": code_digest(),
                "sha256": it["sha256"],
                "options": it["options"],
            }
        ),
    )
