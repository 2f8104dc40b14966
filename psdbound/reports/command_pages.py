"""The HTML pages of ``cutoff`` and ``validate``, drawn from their JSON documents.

Each page (:func:`psdbound.reports.page.write_page`) is built from the
document its command writes beside it, so the page shows exactly what the
JSON holds: :func:`write_cutoff_page` from ``cutoff_<name>.json`` (a
station), :func:`write_cutoff_map_page` from ``cutoff_map.json`` (the world
map) and :func:`write_validation_page` from ``validation.json``. Each opens
with a headline (the recommended cutoff, the map's range, the verdict),
then the settings in sentences, the tables and the command's figures,
inlined and linked to their PNG files.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from psdbound.reports.page import Table, write_page

__all__ = ["write_cutoff_map_page", "write_cutoff_page", "write_validation_page"]

#: A figure written beside the page: its caption and its PNG file.
FigureFile = tuple[str, Path]


def _num(value: float | None, fmt: str = ".3e") -> str:
    """Return ``value`` formatted, or ``n/a`` for a missing (null) number."""
    return "n/a" if value is None else format(value, fmt)


def _figures(figures: Sequence[FigureFile]) -> list[tuple[str, bytes, str]]:
    """Read each PNG file; link it by its name (the page is written beside it)."""
    return [(caption, Path(p).read_bytes(), Path(p).name) for caption, p in figures]


def _carrier(settings: dict[str, Any]) -> str:
    """Return the simulated carrier (or carrier pair) of cutoff settings, in MHz."""
    f1 = settings["frequency_hz"] / 1e6
    f2 = settings.get("second_frequency_hz")
    if f2 is None:
        return f"{f1:.2f} MHz"
    return f"the {f1:.2f} - {f2 / 1e6:.2f} MHz difference"


def _criterion_line(summary: dict[str, Any], settings: dict[str, Any]) -> str:
    """Return the criterion of a station run, with its parameters and units, in one sentence."""
    crit = settings["criterion"]
    thr_m = summary.get("threshold_m")
    if crit == "residual":
        how = (
            f"Residual criterion: the ionosphere the fit's high-pass ({settings['filter_kind']}, "
            f"order {settings['filter_order']}) leaves stays {settings['margin_db']:g} dB below "
            f"the {1e3 * settings['mp_sigma_m']:g} mm reference multipath (residual RMS "
            f"{_num(None if thr_m is None else 1e3 * thr_m, '.3g')} mm)"
        )
    elif crit == "relative":
        how = (
            f"Relative Lomb-Scargle criterion: the PSD envelope {settings['drop_db']:g} dB below "
            f"its reference ({settings['reference']})"
        )
    else:
        how = (
            "Absolute Lomb-Scargle criterion: residual variance above f_c at most "
            f"{settings['variance_m2']:g} m^2"
        )
    return (
        f"{how}; slant delays simulated with PyIRI ({settings['iri_model']}, "
        f"{settings['method']}) at F10.7 {settings['f107_sfu']:g} sfu on {_carrier(settings)}, "
        f"every {settings['sampling_s']:g} s above {settings['elevation_mask_deg']:g} deg."
    )


def _day_rows(doc: dict[str, Any]) -> list[list[str]]:
    """Return per day: series, skipped, mean and largest cutoff (Hz), the largest's tau_c (min)."""
    out = []
    for day in doc["days"]:
        fc = [r["f_c_hz"] for r in doc["rows"] if r["date"] == day]
        skipped = sum(1 for s in doc["skipped"] if s["date"] == day)
        mean = sum(fc) / len(fc) if fc else None
        top = max(fc) if fc else None
        tau = None if top is None else 1.0 / top / 60.0
        out.append([day, str(len(fc)), str(skipped), _num(mean), _num(top), _num(tau, ".2f")])
    return out


def _margin_table(summary: dict[str, Any]) -> list[Table]:
    """Return the residual criterion's cutoffs at every recorded margin (none otherwise)."""
    rows = [
        [
            f"{m['margin_db']:g}",
            _num(m["threshold_m"], ".3g"),
            _num(m["mean_f_c_hz"]),
            _num(m["max_f_c_hz"]),
        ]
        for m in summary.get("by_margin") or []
    ]
    if not rows:
        return []
    head = ["margin [dB]", "residual RMS [m]", "mean f_c [Hz]", "recommended f_c [Hz]"]
    return [("Cutoff at each margin below the reference multipath", head, rows)]


def write_cutoff_page(
    path: str | os.PathLike[str], doc: dict[str, Any], figures: Sequence[FigureFile] = ()
) -> Path:
    """Write the page of a station's cutoff run (``cutoff_<name>.html``), atomically.

    Parameters
    ----------
    path : str or path-like
        The HTML file (beside the JSON document and the figures).
    doc : dict
        The station document (``cutoff_<name>.json``,
        :meth:`psdbound.ionosphere.StationCutoffs.to_dict`).
    figures : sequence of (caption, PNG path), optional
        The run's figures, written beside the page.

    Returns
    -------
    Path
    """
    s, st = doc["summary"], doc["station"]
    name = st["name"] or "station"
    headline = (
        f"Recommended cutoff f_c = {_num(s['recommended_f_c_hz'])} Hz (tau_c = "
        f"{_num(s['recommended_tau_c_min'], '.2f')} min): the largest of {s['n_series']} "
        f"satellite series on {s['n_days']} day(s)."
    )
    lines = [
        f"{name} at {st['lat_deg']:.4f} deg N, {st['lon_deg']:.4f} deg E, {st['height_m']:g} m; "
        f"satellites: {doc['orbit_description']}.",
        _criterion_line(s, doc["settings"]),
        f"Cutoff of the series: mean {_num(s['mean_f_c_hz'])} Hz, smallest "
        f"{_num(s['min_f_c_hz'])} Hz, largest {_num(s['max_f_c_hz'])} Hz; "
        f"{s['n_not_reached']} series miss the criterion even at the top of the search, "
        f"{s['n_floor']} meet it down to its bottom; "
        f"{s['n_skipped']} series skipped (listed with the reason in the JSON).",
    ]
    head = ["day", "series", "skipped", "mean f_c [Hz]", "largest f_c [Hz]", "its tau_c [min]"]
    tables = [("Per day", head, _day_rows(doc)), *_margin_table(s)]
    return write_page(
        path,
        command="cutoff",
        title=f"ionosphere high-pass cutoff at {name}",
        json_name=Path(path).with_suffix(".json").name,
        schema_name="cutoff.schema.json",
        headline=headline,
        lines=lines,
        tables=tables,
        figures=_figures(figures),
    )


def _map_lines(doc: dict[str, Any]) -> list[str]:
    """Return the world map's criterion, layers, compute and interpolation check, in sentences."""
    c, comp = doc["criterion"], doc["compute"]
    lines = [
        f"{c['name']} criterion: the residual ionosphere after the fit's high-pass "
        f"{c['margin_db']:g} dB below {1e3 * c['mp_sigma_m']:g} mm; orbits: "
        f"{doc['orbit_description']}; days {doc['days']}.",
    ]
    lines += [
        f"Layer {la['name']}: {la['year']}, F10.7 {la['f107_sfu']:g} sfu ({la['f107_source']}), "
        f"days {', '.join(la['days'])}."
        for la in doc["layers"]
    ]
    lines.append(
        f"{comp['n_station_days']} station-days ({comp['n_from_cache']} from the cache) in "
        f"{comp['elapsed_s']:g} s."
    )
    lines += [
        f"Grid interpolation at the stations ({v['name']}): median error "
        f"{100 * v['median_abs_rel_error']:.1f} %, worst {100 * v['worst_rel_error']:+.1f} % "
        f"({v['worst_station']})."
        for v in doc["validation"]
    ]
    return lines


def write_cutoff_map_page(
    path: str | os.PathLike[str], doc: dict[str, Any], figures: Sequence[FigureFile] = ()
) -> Path:
    """Write the page of the world cutoff map (``cutoff_map.html``), atomically.

    Parameters
    ----------
    path : str or path-like
        The HTML file (beside ``cutoff_map.json``).
    doc : dict
        The map document (:func:`psdbound.ionosphere.worldmap.compute_world_map`).
    figures : sequence of (caption, PNG path), optional
        The map figure, written beside the page.

    Returns
    -------
    Path
    """
    layers = doc["layers"]
    stations = layers[0]["stations"] if layers else []
    values = [s["recommended_f_c_hz"] for la in layers for s in la["stations"]]
    values = [v for v in values if v is not None]
    g = doc["grid"]
    headline = (
        f"World cutoff map: {len(stations)} reference stations and a {len(g['lat_deg'])} x "
        f"{len(g['lon_deg'])} grid in {len(layers)} solar-activity layer(s); recommended "
        f"cutoff at the stations {_num(min(values, default=None))} to "
        f"{_num(max(values, default=None))} Hz."
    )
    by_name = [{s["name"]: s for s in la["stations"]} for la in layers]
    rows = [
        [s["name"], f"{s['lat_deg']:.2f}", f"{s['lon_deg']:.2f}"]
        + [_num(m[s["name"]]["recommended_f_c_hz"]) for m in by_name]
        for s in stations
    ]
    head = ["station", "latitude [deg]", "longitude [deg]"]
    head += [f"{la['name']} f_c [Hz]" for la in layers]
    return write_page(
        path,
        command="cutoff",
        title="world ionosphere cutoff map",
        json_name=Path(path).with_suffix(".json").name,
        headline=headline,
        lines=_map_lines(doc),
        tables=[("Recommended cutoff at the reference stations", head, rows)],
        figures=_figures(figures),
    )


def _pct(value: float | None) -> str:
    return "n/a" if value is None else f"{100 * value:.2f}"


def _expansion_rows(doc: dict[str, Any]) -> list[list[str]]:
    """Return one row per Jacobi-Anger check: model, geometry, convention, z, rate, fractions."""
    out = []
    for r in doc["expansion"]:
        rng = r["fraction_range"]
        out.append(
            [
                r["model"],
                r["geometry"],
                r["convention"],
                _num(r["z_rad"], ".4g"),
                _num(r["rate_hz"], ".4g"),
                _pct(r["fraction_below_cutoff_first_order"]),
                _pct(r["fraction_below_cutoff_second_order"]),
                "-" if rng is None else f"{_pct(rng[0])} - {_pct(rng[1])}",
                r["verdict"],
            ]
        )
    return out


def _direct_rows(doc: dict[str, Any]) -> list[list[str]]:
    """Return one row per direct simulation: what, geometry, convention, length, fractions."""
    return [
        [
            r["label"],
            r["geometry"],
            r["convention"],
            f"{r['duration_s'] / 3600.0:.2f}",
            _pct(r["fraction_below_cutoff"]),
            _pct(r["expansion_fraction"]),
            r["verdict"],
        ]
        for r in doc["direct"]
    ]


def _validation_tables(doc: dict[str, Any]) -> list[Table]:
    head = ["model", "geometry", "convention", "z [rad]", "rate [Hz]", "1st order [%]"]
    head += ["2nd order [%]", "over +- tolerance [%]", "verdict"]
    out = [("Jacobi-Anger expansion: power below f_c", head, _expansion_rows(doc))]
    if doc["direct"]:
        head = ["simulated", "geometry", "convention", "length [h]", "below f_c [%]"]
        head += ["expansion [%]", "verdict"]
        out.append(("Direct simulation: power below f_c", head, _direct_rows(doc)))
    return out


def write_validation_page(
    path: str | os.PathLike[str], doc: dict[str, Any], figures: Sequence[FigureFile] = ()
) -> Path:
    """Write the page of a cutoff validation (``validation.html``), atomically.

    Parameters
    ----------
    path : str or path-like
        The HTML file (beside ``validation.json``).
    doc : dict
        The document (:meth:`psdbound.validation.ValidationReport.to_dict`).
    figures : sequence of (caption, PNG path), optional
        The expansion and direct-simulation figures, written beside the page.

    Returns
    -------
    Path
    """
    physical = [r for r in (*doc["expansion"], *doc["direct"]) if r["convention"] == "physical"]
    fractions = [r["fraction_below_cutoff"] for r in physical]
    worst = max((f for f in fractions if f is not None), default=None)
    verdict = "pass" if doc["passed"] else "FAIL"
    headline = (
        f"Verdict (physical convention): {verdict} - at most {_pct(worst)} % of the multipath "
        f"power lies below f_c = {doc['cutoff_hz']:.4g} Hz (threshold "
        f"{100 * doc['threshold']:g} %)"
        + ("." if doc["passed"] else "; the cutoff removes too much multipath.")
    )
    lines = [
        f"Reflected/direct amplitude ratio alpha = {doc['alpha']:g}, carrier wavelength "
        f"{doc['wavelength_m']:.6f} m; verdict from the {doc['verdict_basis']}.",
        *(f"{name} convention: {text}" for name, text in doc["conventions"].items()),
        *(f"Note: {n}" for n in doc["notes"]),
    ]
    return write_page(
        path,
        command="validate",
        title=f"does the cutoff f_c = {doc['cutoff_hz']:.4g} Hz remove too much multipath?",
        json_name=Path(path).with_suffix(".json").name,
        headline=headline,
        lines=lines,
        tables=_validation_tables(doc),
        figures=_figures(figures),
    )
