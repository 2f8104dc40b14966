"""Output files of cutoff runs: CSV table, JSON document, HTML page and PNG figures.

For a station (:class:`~psdbound.ionosphere.results.StationCutoffs`), in
``out_dir``: ``cutoff_<name>.csv`` (one row per series),
``cutoff_<name>.json`` (summary, settings, orbit source, rows; schema
``psdbound/results/cutoff.schema.json``), ``cutoff_<name>.html`` (the
recommended cutoff, per-day and per-margin tables and the figures,
:func:`psdbound.reports.command_pages.write_cutoff_page`) and, with
figures, for the residual criterion ``cutoff_<name>_residual.png`` (every
series' residual against the cutoff), for a periodogram criterion
``cutoff_<name>_psd.png`` (the series with the largest f_c: PSD, envelope,
criterion) and ``cutoff_<name>_envelopes.png`` (every envelope).
For the 20-station map of one year
(:class:`~psdbound.ionosphere.results.CutoffMap`, library only):
``cutoff_map.csv``, ``cutoff_map.json`` and ``cutoff_map.png``. For the
world map document (:mod:`~psdbound.ionosphere.worldmap`,
:func:`write_world_map_outputs`): ``cutoff_map.json`` (the document, schema
``psdbound/results/cutoff_map.schema.json``), ``cutoff_map.csv`` (one row per
site and layer), ``cutoff_map.html`` and ``cutoff_map.png``. Every JSON file
goes through :func:`psdbound.results.write_json`; every file is written
atomically (:mod:`psdbound.common`).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np

from psdbound.common import atomic_write_text
from psdbound.ionosphere.cutoff import one_day_series, series_cutoff
from psdbound.ionosphere.figures import (
    plot_cutoff_map,
    plot_residual_curves,
    plot_series_psd,
    plot_station_envelopes,
    plot_world_map,
)
from psdbound.ionosphere.names import THESIS_CHICAGO_2020_HZ
from psdbound.ionosphere.results import CutoffMap, StationCutoffs
from psdbound.results import write_json

__all__ = [
    "file_tag",
    "write_cutoff_outputs",
    "write_map_outputs",
    "write_station_outputs",
    "world_map_csv",
    "write_world_map_outputs",
]


def file_tag(name: str) -> str:
    """Return a station name made safe for file names (other characters become ``_``)."""
    keep = "".join(c if c.isalnum() or c in "-_." else "_" for c in name)
    return keep or "station"


def write_station_outputs(
    result: StationCutoffs, out_dir: str | os.PathLike[str], *, figures: bool = True
) -> list[Path]:
    """Write a station's table, JSON document, HTML page and (optionally) figures.

    Parameters
    ----------
    result : StationCutoffs
        A station run with at least one series.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write the PNG figures (and show them on the page).

    Returns
    -------
    list of Path
        The files written, in order: CSV, JSON, the figures, HTML.
    """
    from psdbound.reports.command_pages import write_cutoff_page

    out = Path(out_dir)
    tag = file_tag(result.name)
    doc = result.to_dict()
    files = [
        atomic_write_text(out / f"cutoff_{tag}.csv", result.table_csv()),
        write_json(out / f"cutoff_{tag}.json", doc),
    ]
    drawn = _station_figures(result, out, tag) if figures else []
    files += [p for _, p in drawn]
    files.append(write_cutoff_page(out / f"cutoff_{tag}.html", doc, drawn))
    return files


def _station_figures(res: StationCutoffs, out: Path, tag: str) -> list[tuple[str, Path]]:
    """Draw a station's figures into ``out``; return (caption, file) of each."""
    rows = res.rows
    if res.settings.criterion == "residual":
        path = plot_residual_curves(
            [(r["curve_f_hz"], r["curve_rms_m"]) for r in rows],
            res.f_c_hz,
            res.settings.thresholds_m()[0],
            out / f"cutoff_{tag}_residual.png",
            reference_hz=THESIS_CHICAGO_2020_HZ["max"],
            title=f"{res.name}: residual ionosphere after the fit's high-pass, {len(rows)} "
            f"series on {len(res.days)} days",
        )
        caption = (
            "Residual ionosphere RMS (mm) the fit's high-pass leaves against its cutoff (Hz), "
            "every series, with the threshold and the mean and largest (recommended) cutoff."
        )
        return [(caption, path)]
    files = []
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
        path = plot_series_psd(
            r,
            out / f"cutoff_{tag}_psd.png",
            title=f"{res.name} {top['sat']} {top['date']}: LS PSD, envelope, f_c "
            "(largest f_c of the run)",
        )
        caption = (
            f"Lomb-Scargle PSD (m^2/Hz) of the series with the largest cutoff ({top['sat']} "
            f"{top['date']}), its envelope, the criterion's threshold and f_c."
        )
        files.append((caption, path))
    envs = res.envelopes
    f_lo = min(e.f_min_hz for e in envs) / 3.0
    f_hi = max(e.f_max_hz for e in envs)
    path = plot_station_envelopes(
        envs,
        res.f_c_hz,
        out / f"cutoff_{tag}_envelopes.png",
        f_range_hz=(f_lo, f_hi),
        reference_m2_hz=[r["reference_m2_hz"] for r in rows],
        title=f"{res.name}: envelopes of {len(envs)} series on {len(res.days)} days",
    )
    files.append(("PSD envelopes (m^2/Hz) of every series with the mean and largest f_c.", path))
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
        write_json(out / "cutoff_map.json", result.to_dict()),
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


def world_map_csv(doc: dict[str, Any]) -> str:
    """Return one CSV row per site (reference stations, then grid nodes) and layer."""
    lines = ["layer,f107_sfu,site,lat_deg,lon_deg,recommended_f_c_hz,mean_f_c_hz,min_f_c_hz"]
    lat, lon = doc["grid"]["lat_deg"], doc["grid"]["lon_deg"]
    for layer in doc["layers"]:
        head = f"{layer['name']},{layer['f107_sfu']:g}"
        for st in layer["stations"]:
            lines.append(
                f"{head},{st['name']},{st['lat_deg']:g},{st['lon_deg']:g},"
                f"{st['recommended_f_c_hz']},{st['mean_f_c_hz']},{st['min_f_c_hz']}"
            )
        g = layer["grid"]
        for i, a in enumerate(lat):
            for j, o in enumerate(lon):
                lines.append(
                    f"{head},grid,{a:g},{o:g},{g['recommended_f_c_hz'][i][j]},"
                    f"{g['mean_f_c_hz'][i][j]},{g['min_f_c_hz'][i][j]}"
                )
    return "\n".join(lines) + "\n"


def write_world_map_outputs(
    doc: dict[str, Any],
    out_dir: str | os.PathLike[str],
    *,
    figures: bool = True,
    install_path: str | os.PathLike[str] | None = None,
) -> list[Path]:
    """Write the world map document, its table, its HTML page and (optionally) its figure.

    Parameters
    ----------
    doc : dict
        The map document (:func:`psdbound.ionosphere.worldmap.compute_world_map`).
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write ``cutoff_map.png`` (and show it on the page).
    install_path : str or path-like, optional
        Also write the document there (e.g. the package data file).

    Returns
    -------
    list of Path
        The files written, in order: JSON, CSV, the figure, HTML, the installed copy.
    """
    from psdbound.reports.command_pages import write_cutoff_map_page

    out = Path(out_dir)
    sections = frozenset(doc)  # one line per top-level section
    files = [
        write_json(out / "cutoff_map.json", doc, compact=sections),
        atomic_write_text(out / "cutoff_map.csv", world_map_csv(doc)),
    ]
    drawn = []
    if figures:
        caption = (
            "Recommended cutoff (Hz) of every grid node (shaded) and reference station "
            "(marked), one panel per solar-activity layer."
        )
        drawn.append((caption, plot_world_map(doc, out / "cutoff_map.png")))
    files += [p for _, p in drawn]
    files.append(write_cutoff_map_page(out / "cutoff_map.html", doc, drawn))
    if install_path is not None:
        files.append(write_json(Path(install_path), doc, compact=sections))
    return files
