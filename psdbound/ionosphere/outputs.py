"""Output files of cutoff runs: CSV table, JSON document and PNG figures.

For a station (:class:`~psdbound.ionosphere.results.StationCutoffs`), in
``out_dir``: ``cutoff_<name>.csv`` (one row per series),
``cutoff_<name>.json`` (summary, settings, orbit source, rows) and, with
figures, ``cutoff_<name>_psd.png`` (the series with the largest f_c: PSD,
envelope, criterion) and ``cutoff_<name>_envelopes.png`` (every envelope).
For the station map (:class:`~psdbound.ionosphere.results.CutoffMap`):
``cutoff_map.csv``, ``cutoff_map.json`` and ``cutoff_map.png``. Every file
is written atomically (:mod:`psdbound.common`).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.common import atomic_write_text
from psdbound.ionosphere.cutoff import one_day_series, series_cutoff
from psdbound.ionosphere.figures import plot_cutoff_map, plot_series_psd, plot_station_envelopes
from psdbound.ionosphere.results import CutoffMap, StationCutoffs

__all__ = [
    "file_tag",
    "json_text",
    "write_cutoff_outputs",
    "write_map_outputs",
    "write_station_outputs",
]


def file_tag(name: str) -> str:
    """Return a station name made safe for file names (other characters become ``_``)."""
    keep = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
    return keep or "station"


def json_text(obj: Any) -> str:
    """Return the JSON text of a result dict (NumPy values converted, NaN allowed)."""

    def default(o: Any) -> Any:
        if isinstance(o, np.generic):
            return o.item()
        if isinstance(o, np.ndarray):
            return o.tolist()
        raise TypeError(type(o).__name__)

    return json.dumps(obj, indent=1, default=default, allow_nan=True) + "\n"


def write_station_outputs(
    result: StationCutoffs, out_dir: str | os.PathLike[str], *, figures: bool = True
) -> list[Path]:
    """Write a station's table, JSON document and (optionally) figures.

    Parameters
    ----------
    result : StationCutoffs
        A station run with at least one series.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write the PNG figures.

    Returns
    -------
    list of Path
        The files written, in order.
    """
    out = Path(out_dir)
    tag = file_tag(result.name)
    files = [
        atomic_write_text(out / f"cutoff_{tag}.csv", result.table_csv()),
        atomic_write_text(out / f"cutoff_{tag}.json", json_text(result.to_json_dict())),
    ]
    if figures:
        files += _station_figures(result, out, tag)
    return files


def _station_figures(res: StationCutoffs, out: Path, tag: str) -> list[Path]:
    files = []
    rows = res.rows
    top = max(rows, key=lambda r: r["f_c_hz"])
    series = res.series_by_date.get(top["date"])
    if series is not None:
        j = list(series["sats"]).index(top["sat"])
        s = res.settings
        t, y = one_day_series(
            np.asarray(series["t_gps_s"]),
            np.asarray(series["delay_m"][j], dtype=np.float64),
            min_arc_s=s.min_arc_s,
        )
        r = series_cutoff(t, y, **s.series_options(), keep_spectrum=True)
        files.append(
            plot_series_psd(
                r,
                out / f"cutoff_{tag}_psd.png",
                title=f"{res.name} {top['sat']} {top['date']}: LS PSD, envelope, f_c "
                "(largest f_c of the run)",
            )
        )
    envs = res.envelopes
    f_lo = min(e.f_min_hz for e in envs) / 3.0
    f_hi = max(e.f_max_hz for e in envs)
    files.append(
        plot_station_envelopes(
            envs,
            res.f_c_hz,
            out / f"cutoff_{tag}_envelopes.png",
            f_range_hz=(f_lo, f_hi),
            reference_m2_hz=[r["reference_m2_hz"] for r in rows],
            title=f"{res.name}: envelopes of {len(envs)} series on {len(res.days)} days",
        )
    )
    return files


def write_map_outputs(
    result: CutoffMap, out_dir: str | os.PathLike[str], *, figures: bool = True
) -> list[Path]:
    """Write the station map's table, JSON document and (optionally) map figure.

    Parameters
    ----------
    result : CutoffMap
        A map run.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write ``cutoff_map.png``.

    Returns
    -------
    list of Path
        The files written, in order.
    """
    out = Path(out_dir)
    files = [
        atomic_write_text(out / "cutoff_map.csv", result.table_csv()),
        atomic_write_text(out / "cutoff_map.json", json_text(result.to_json_dict())),
    ]
    if figures:
        rows = result.rows()
        n_days = len(result.stations[0].days)
        files.append(
            plot_cutoff_map(
                [r["name"] for r in rows],
                [r["lat_deg"] for r in rows],
                [r["lon_deg"] for r in rows],
                [r["recommended_f_c_hz"] for r in rows],
                out / "cutoff_map.png",
                title=f"Recommended ionosphere cutoff ({n_days} days, "
                f"{result.stations[0].settings.criterion} criterion)",
            )
        )
    return files


def write_cutoff_outputs(
    result: StationCutoffs | CutoffMap, out_dir: str | os.PathLike[str], *, figures: bool = True
) -> list[Path]:
    """Write the outputs of a station or map run (see the module notes).

    Parameters
    ----------
    result : StationCutoffs or CutoffMap
        The run.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write the PNG figures.

    Returns
    -------
    list of Path
        The files written, in order.
    """
    if isinstance(result, CutoffMap):
        return write_map_outputs(result, out_dir, figures=figures)
    return write_station_outputs(result, out_dir, figures=figures)
