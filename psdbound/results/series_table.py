"""The isolated multipath as data: one row per satellite and epoch, with what became of it.

Users of GNSS quality tools analyse the multipath series themselves (their
own statistics, maps, comparisons between days). This table holds every
isolated sample, not only the ones the bound was fitted to, and says for each
what the pipeline did with it:

``t_gps_s``, ``sat``, ``azimuth_deg``, ``elevation_deg``, ``value_m``
    GPS time, satellite (or pair for double differences), direction (NaN
    azimuth without an orbit or for dual-antenna pairs) and the isolated
    multipath, metres (before the elevation mapping);
``screened``
    why the sample was screened out (``ionosphere``, ``implausible``,
    ``short remainder``), empty when it was kept;
``window``
    index of the first stationary window holding it (``windows.per_window``
    of result.json), -1 when none: such a kept sample lies outside the bound.

:func:`write_series_csv` writes it as CSV (gzip-compressed when the name
ends in ``.gz``), atomically.
"""

from __future__ import annotations

import gzip
import io
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.common.atomic import atomic_write_bytes

__all__ = ["COLUMNS", "series_csv", "series_table", "write_series_csv"]

#: The table's columns, in order.
COLUMNS = ("t_gps_s", "sat", "azimuth_deg", "elevation_deg", "value_m", "screened", "window")


def _mark_spans(
    sat: NDArray,
    t: NDArray,
    spans: Sequence[tuple[str, float, float]],
    out: NDArray,
    values: Sequence[Any],
) -> None:
    """Set ``out`` to ``values[k]`` on the samples of span ``k`` (first span wins)."""
    free = np.ones(t.size, dtype=bool)
    for (s, t0, t1), val in zip(spans, values, strict=True):
        sel = free & (sat == s) & (t >= t0) & (t <= t1)
        out[sel] = val
        free &= ~sel


def series_table(
    series: Any, arcs: Any, excluded: Sequence[dict[str, Any]], per_window: Sequence[dict[str, Any]]
) -> dict[str, NDArray]:
    """Return every isolated sample with its direction, screening and window.

    Parameters
    ----------
    series : MultipathSeries
        The isolated series before screening.
    arcs : ArcSet or None
        The tracking arcs (azimuths; None: NaN azimuths).
    excluded : sequence of dict
        ``screening.excluded`` of the result (``sat``, ``start_gps_s``,
        ``stop_gps_s``, ``kind``).
    per_window : sequence of dict
        ``windows.per_window`` of the result (``sats``, ``t_start_gps_s``,
        ``t_stop_gps_s``).

    Returns
    -------
    dict of str to ndarray
        One array per column of :data:`COLUMNS`, all of one length.
    """
    n = series.t_gps_s.size
    sat = np.empty(n, dtype=object)
    az = np.full(n, np.nan)
    for k, (lo, hi) in enumerate(series.arc_bounds()):
        sat[lo:hi] = series.arc_sats[k]
        if arcs is not None:
            az[lo:hi] = arcs.azimuth_at(series.arc_sats[k], series.t_gps_s[lo:hi])
    t = np.asarray(series.t_gps_s, dtype=float)
    screened = np.full(n, "", dtype=object)
    _mark_spans(
        sat,
        t,
        [(e["sat"], e["start_gps_s"], e["stop_gps_s"]) for e in excluded],
        screened,
        [e["kind"] for e in excluded],
    )
    window = np.full(n, -1, dtype=np.int64)
    _mark_spans(
        sat,
        t,
        [(w["sats"], w["t_start_gps_s"], w["t_stop_gps_s"]) for w in per_window],
        window,
        range(len(per_window)),
    )
    window[screened != ""] = -1
    return {
        "t_gps_s": t,
        "sat": sat,
        "azimuth_deg": az,
        "elevation_deg": np.asarray(series.elevation_deg, dtype=float),
        "value_m": np.asarray(series.value_m, dtype=float),
        "screened": screened,
        "window": window,
    }


def series_csv(table: dict[str, NDArray], *, gz: bool = False) -> bytes:
    """Return a series table as CSV bytes (gzip-compressed when ``gz``).

    Parameters
    ----------
    table : dict of str to ndarray
        :func:`series_table`.
    gz : bool, default False
        Compress with gzip (reproducibly: no time stamp).

    Returns
    -------
    bytes
    """
    buf = io.StringIO()
    buf.write(",".join(COLUMNS) + "\n")
    for t, sat, az, el, v, scr, win in zip(*(table[c] for c in COLUMNS), strict=True):
        buf.write(
            f"{t:.1f},{sat},{'' if np.isnan(az) else f'{az:.2f}'},{el:.2f},{v:.6f},{scr},{win}\n"
        )
    data = buf.getvalue().encode()
    return gzip.compress(data, mtime=0) if gz else data


def write_series_csv(table: dict[str, NDArray], path: str | os.PathLike[str]) -> Path:
    """Write a series table as CSV (gzip when ``path`` ends in ``.gz``), atomically.

    Parameters
    ----------
    table : dict of str to ndarray
        :func:`series_table`.
    path : str or path-like
        Destination file.

    Returns
    -------
    Path
    """
    p = Path(path)
    return atomic_write_bytes(p, series_csv(table, gz=p.name.endswith(".gz")))
