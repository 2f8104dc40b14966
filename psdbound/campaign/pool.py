"""A station's pooled bound over its bounded days, and the pooled bound's own verdict.

Every station-day carries the verdict ``psdbound fit`` gives it
(:func:`~psdbound.campaign.tasks.station_day_task`). Only the **bounded**
days of a station enter its pool (of one sampling interval: the most common
one among them); the others are listed with their reasons. The pooled bound
(:func:`~psdbound.campaign.tasks.pooled_days_bound`, with the days' bound
options) is judged by :func:`psdbound.pipeline.verdict.judge_pooled`: no
bounded day left, degenerate bound, too little stationary data for tau over
the pooled windows, and the low-frequency rule.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from typing import Any

import numpy as np

from psdbound.campaign.tasks import pooled_days_bound

__all__ = ["pool_station", "pool_stations"]


def _pool_interval(bounded: Sequence[dict[str, Any]]) -> float | None:
    """Return the pool's sampling interval, s: the most common one, the shortest on a tie."""
    if not bounded:
        return None
    counts = Counter(round(float(d["dt_s"]), 6) for d in bounded)
    return min(counts, key=lambda dt: (-counts[dt], dt))


def _excluded(day: dict[str, Any], dt_s: float | None) -> dict[str, Any]:
    """Return the entry of a day left out of the pool: its verdict and why."""
    if day["verdict"] == "bounded":  # bounded, but sampled at another interval
        why = [f"sampling interval {day['dt_s']:g} s differs from the pool's {dt_s:g} s"]
    else:
        why = list(day["verdict_reasons"])
    return {"day": day["day"], "verdict": day["verdict"], "reasons": why}


def _bound_row(days: list[dict[str, Any]], options: Any) -> dict[str, Any]:
    """Return the pooled bound of days of one station and one interval (plain numbers)."""
    sb = pooled_days_bound(days, f_min_hz=max(float(r["f_min_hz"]) for r in days), options=options)
    b = sb.fit
    return {
        "sigma_gm_m": b.sigma_gm_m,
        "tau_s": b.tau_s,
        "sigma_wn_m": b.sigma_wn_m,
        "dt_s": float(days[0]["dt_s"]),
        "band_hz": [b.f_min_hz, b.f_max_hz],
        "confidence_level": b.level,
        "n_groups": sb.limits.n_groups,
        "tau_grid_s": list(b.tau_grid_s),
        "low_frequency": sb.low_frequency.to_dict(),
    }


def _comparison_note(n_pooled: int) -> str | None:
    """Say what the held-out test cannot do for a station (None when it can)."""
    if n_pooled == 0:
        return "no bounded day: no pooled bound and no day-to-day comparison"
    if n_pooled == 1:
        return (
            "one day: no day-to-day comparison (the held-out test needs two bounded days "
            "at one sampling interval)"
        )
    return None


_Rows = list[dict[str, Any]]


def pool_station(
    days: Sequence[dict[str, Any]], *, bound_options: Any = None, verdict_options: Any = None
) -> tuple[dict[str, Any], _Rows]:
    """Pool one station's bounded days and judge the pooled bound.

    Parameters
    ----------
    days : sequence of dict
        Every station-day result of one station (any verdict).
    bound_options : BoundOptions, optional
        The pooled rule's options (those of the days' fits).
    verdict_options : VerdictOptions, optional
        The verdict thresholds and low-frequency policy of the days' fits.

    Returns
    -------
    row : dict
        ``station``, ``verdict``, ``verdict_reasons``, ``verdict_checks``
        (each rule applied, with its numbers), ``n_days``, ``n_pooled``,
        ``pooled_days``,
        ``excluded_days`` (day, verdict, reasons), ``covered_s`` (s, the
        pooled windows' time), ``comparison_note`` and the bound
        (``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``, ``dt_s``, ``band_hz``,
        ``confidence_level``, ``n_groups``, ``low_frequency``; None values
        when nothing was pooled).
    pooled : list of dict
        The day results in the pool.
    """
    from psdbound.pipeline.verdict import pooled_checks, verdict_of

    days = sorted(days, key=lambda d: d["day"])
    dt = _pool_interval([d for d in days if d["verdict"] == "bounded"])
    pooled = [d for d in days if d["verdict"] == "bounded" and np.isclose(d["dt_s"], dt)]
    bound = _bound_row(pooled, bound_options) if pooled else None
    covered = float(sum(d.get("covered_s", 0.0) for d in pooled))
    checks = pooled_checks(bound, covered_s=covered, n_days=len(pooled), options=verdict_options)
    verdict, reasons = verdict_of(checks)
    empty = dict.fromkeys(
        (
            "sigma_gm_m",
            "tau_s",
            "sigma_wn_m",
            "dt_s",
            "band_hz",
            "confidence_level",
            "n_groups",
            "low_frequency",
        )
    )
    row = {
        "station": days[0]["station"],
        "verdict": verdict,
        "verdict_reasons": reasons,
        "verdict_checks": [c.to_dict() for c in checks],
        "n_days": len(days),
        "n_pooled": len(pooled),
        "pooled_days": [d["day"] for d in pooled],
        "excluded_days": [_excluded(d, dt) for d in days if all(d is not p for p in pooled)],
        "covered_s": covered,
        "comparison_note": _comparison_note(len(pooled)),
        **(bound or empty),
    }
    row.pop("tau_grid_s", None)
    return row, pooled


def pool_stations(
    results: Sequence[dict[str, Any]], *, bound_options: Any = None, verdict_options: Any = None
) -> tuple[_Rows, _Rows]:
    """Pool every station (see :func:`pool_station`).

    Parameters
    ----------
    results : sequence of dict
        Station-day results of any stations.
    bound_options, verdict_options : optional
        As :func:`pool_station`.

    Returns
    -------
    stations : list of dict
        One row per station, sorted by name.
    pooled : list of dict
        Every day result that entered its station's pool.
    """
    rows, pooled = [], []
    for st in sorted({r["station"] for r in results}):
        row, used = pool_station(
            [r for r in results if r["station"] == st],
            bound_options=bound_options,
            verdict_options=verdict_options,
        )
        rows.append(row)
        pooled += used
    return rows, pooled
