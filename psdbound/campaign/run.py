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
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.campaign.heldout import held_out
from psdbound.campaign.tasks import pooled_days_bound, station_day_task
from psdbound.errors import InputError

__all__ = ["CampaignResult", "StationDay", "plan_campaign", "run_campaign"]

_GPS_EPOCH = _dt.datetime(1980, 1, 6)


@dataclass(frozen=True)
class StationDay:
    """The files of one station on one day (GPS calendar day of the first epoch)."""

    station: str
    day: str
    obs: tuple[str, ...]
    nav: str


def _day_of(t_gps_s: float) -> _dt.date:
    return (_GPS_EPOCH + _dt.timedelta(seconds=float(t_gps_s))).date()


def _name_day(name: str) -> tuple[int, str] | None:
    """Return (year, day of year) from a RINEX file name, or None."""
    m = re.search(r"_(\d{4})(\d{3})\d{4}_", name)
    if m:
        return int(m.group(1)), m.group(2)
    m = re.search(r"^\w{4}(\d{3})\w\.(\d{2})[a-z]", name, re.I)
    if m:
        yy = int(m.group(2))
        return (2000 + yy if yy < 80 else 1900 + yy), m.group(1)
    return None


def _nav_for(day: _dt.date, navs: Sequence[str]) -> str:
    """Return the navigation file of a day.

    A file whose name carries a date (RINEX 3 ``..._YYYYDDDHHMM_...``, RINEX 2
    ``ssssDDD0.YYn``) serves that day only; a file without one serves every
    day when it is the only undated file.
    """
    doy = f"{day.timetuple().tm_yday:03d}"
    dated = {n: _name_day(Path(n).name) for n in navs}
    hits = [n for n, d in dated.items() if d == (day.year, doy)]
    undated = [n for n, d in dated.items() if d is None]
    if len(hits) == 1:
        return hits[0]
    if not hits and len(undated) == 1:
        return undated[0]
    raise InputError(
        f"no single navigation file for {day.isoformat()} (day of year {doy}): "
        + (f"{len(hits)} match ({', '.join(Path(h).name for h in hits)})" if hits
           else f"none of {', '.join(Path(n).name for n in navs)} is named for that day")
        + "; give one navigation file per observation day (RINEX names hold the day of year)"
    )  # fmt: skip


def plan_campaign(obs: Sequence[str | os.PathLike[str]],
                  nav: Sequence[str | os.PathLike[str]]) -> list[StationDay]:  # fmt: skip
    """Group observation files by station and day and match each day's navigation file.

    Parameters
    ----------
    obs : sequence of path
        Observation files (any stations, days and order).
    nav : sequence of path
        Navigation (or SP3) files: one, or one per day (matched by the day
        of year in their names).

    Returns
    -------
    list of StationDay
        Sorted by station, then day.

    Raises
    ------
    InputError
        No file, a missing file, or a day without a navigation file.
    """
    from psdbound.io import read_obs
    from psdbound.io.merge import station_key

    if not obs:
        raise InputError("a campaign needs observation files")
    if not nav:
        raise InputError("a campaign needs navigation (or SP3) files: give --nav")
    navs = [os.fspath(n) for n in nav]
    for p in [*map(os.fspath, obs), *navs]:
        if not Path(p).is_file():
            raise InputError("file not found", path=p)
    groups: dict[tuple[str, str], list[str]] = {}
    for p in map(os.fspath, obs):
        o = read_obs(p, systems="G")
        if o.t_gps_s.size == 0:
            raise InputError("observation file holds no epoch", path=p)
        day = _day_of(o.t_gps_s[0])
        groups.setdefault((station_key(o), day.isoformat()), []).append(p)
    return [StationDay(st, d, tuple(files), _nav_for(_dt.date.fromisoformat(d), navs))
            for (st, d), files in sorted(groups.items())]  # fmt: skip


@dataclass
class CampaignResult:
    """Per-day results, pooled bounds per station and held-out tests.

    Attributes
    ----------
    days : list of dict
        One per station-day (bound or ``error``), without the PSD arrays.
    stations : list of dict
        Per station: the pooled bound of all its good days.
    held_out : list of dict
        Per station-day: the bound of the station's other days tested on it.
    n_computed, n_cached : int
        Station-days computed by this run and read from the cache.
    """

    days: list[dict[str, Any]]
    stations: list[dict[str, Any]]
    held_out: list[dict[str, Any]]
    n_computed: int = 0
    n_cached: int = 0
    meta: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """Return the ``campaign.json`` content."""
        return {"schema": "psdbound-campaign/1", "days": self.days, "stations": self.stations,
                "held_out": self.held_out, "n_computed": self.n_computed,
                "n_cached": self.n_cached, **self.meta}  # fmt: skip

    def summary(self) -> str:
        """Return a text table of the held-out tests."""
        lines = [f"{len(self.days)} station-days ({self.n_computed} computed, {self.n_cached} "
                 f"from the cache); {len(self.stations)} station(s)"]  # fmt: skip
        for s in self.stations:
            lines.append(f"  {s['station']}: pooled over {s['n_days']} day(s): sigma_GM "
                         f"{1e3 * s['sigma_gm_m']:.2f} mm, tau {s['tau_s']:.1f} s, sigma_WN "
                         f"{1e3 * s['sigma_wn_m']:.2f} mm")  # fmt: skip
        for d in self.days:
            if not d["ok"]:
                lines.append(f"  {d['station']} {d['day']}: no bound: {d['error']}")
        for h in self.held_out:
            lines.append(
                f"  held out {h['station']} {h['day']}: windows covered "
                f"{100 * h['windows_covered_fraction']:.0f} %, worst excess "
                f"{h['worst_excess_db']:.1f} dB, KF max generalised eigenvalue "
                f"{h['kf_max_generalized_eigenvalue']:.2f} (windows bounded "
                f"{100 * h.get('kf_windows_bounded_fraction', float('nan')):.0f} %)"
            )
        return "\n".join(lines)


def _public(result: dict[str, Any]) -> dict[str, Any]:
    return {k: (v.tolist() if isinstance(v, np.ndarray) else v)
            for k, v in result.items() if not k.startswith("psd_")}  # fmt: skip


def _station_bounds(results: list[dict[str, Any]]) -> list[dict[str, Any]]:
    out = []
    good = [r for r in results if r.get("ok")]
    for st in sorted({r["station"] for r in good}):
        days = [r for r in good if r["station"] == st]
        dt = float(days[0]["dt_s"])
        days = [r for r in days if np.isclose(r["dt_s"], dt)]
        sb = pooled_days_bound(days, f_min_hz=max(float(r["f_min_hz"]) for r in days))
        b = sb.fit
        out.append({"station": st, "n_days": len(days), "sigma_gm_m": b.sigma_gm_m,
                    "tau_s": b.tau_s, "sigma_wn_m": b.sigma_wn_m, "dt_s": dt,
                    "band_hz": [b.f_min_hz, b.f_max_hz], "confidence_level": b.level,
                    "n_groups": sb.limits.n_groups,
                    "low_frequency": sb.low_frequency.as_dict()})  # fmt: skip
    return out


def run_campaign(
    obs: Sequence[str | os.PathLike[str]],
    nav: Sequence[str | os.PathLike[str]],
    *,
    workers: int = 2,
    scheduler: str | None = None,
    cache_dir: str | os.PathLike[str] | None = None,
    options: dict[str, dict[str, Any]] | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> CampaignResult:
    """Fit every station-day on Dask, pool each station, test every day held out.

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
        :class:`~psdbound.pipeline.FitConfig` sections for every station-day.
    progress : callable, optional
        ``progress(done, total)`` after each computed station-day.

    Returns
    -------
    CampaignResult
    """
    from psdbound.common import file_sha256
    from psdbound.compute import DiskCache, cache_key, default_cache_dir, run_tasks
    from psdbound.version import __version__, code_digest

    if (options or {}).get("code_multipath", {}).get("codes"):
        raise InputError("[code_multipath] is a fit option: a campaign pools the carrier-phase "
                         "bounds only; run `psdbound fit --code-multipath` per day, or remove it")
    plan = plan_campaign(obs, nav)
    items = []
    for sd in plan:
        digests = {Path(p).name: file_sha256(p) for p in (*sd.obs, sd.nav)}
        items.append({"station": sd.station, "day": sd.day, "obs": list(sd.obs), "nav": sd.nav,
                      "sha256": digests, "options": options or {}})  # fmt: skip
    cache = DiskCache(
        cache_dir or default_cache_dir("campaign"),
        key=lambda it: cache_key({"task": "station-day", "version": __version__,
                                  "code": code_digest(), "sha256": it["sha256"],
                                  "options": it["options"]}),
    )  # fmt: skip
    run = run_tasks(station_day_task, items, workers=workers, scheduler=scheduler, cache=cache,
                    progress=progress)  # fmt: skip
    results = list(run.results)
    return CampaignResult(
        days=[_public(r) for r in results],
        stations=_station_bounds(results),
        held_out=held_out(results),
        n_computed=run.n_computed,
        n_cached=run.n_cached,
        meta={"files": [{"station": it["station"], "day": it["day"], "sha256": it["sha256"]}
                        for it in items], "psdbound": __version__},  # fmt: skip
    )
