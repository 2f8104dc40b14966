"""Output files of a cutoff validation: CSV table, JSON document, HTML page and PNG figures.

:func:`write_validation_outputs` writes, into a folder, ``validation.csv``
(:func:`validation_csv` of the report's rows), ``validation.json`` (the
report's dict, through :func:`psdbound.results.write_json`; schema
``psdbound/results/validation.schema.json``), with figures
``validation_expansion.png`` and (when a direct simulation ran)
``validation_direct.png``, and ``validation.html`` (the verdict, the tables
and the figures, :func:`psdbound.reports.command_pages.write_validation_page`),
each atomically (:mod:`psdbound.common`).
"""

from __future__ import annotations

import csv
import io
import json
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from psdbound.common import atomic_write_text
from psdbound.results import write_json
from psdbound.validation.results import ValidationReport

__all__ = ["OUTPUT_FILES", "validation_csv", "write_validation_outputs"]

#: Table, document and page written by :func:`write_validation_outputs`.
OUTPUT_FILES = ("validation.csv", "validation.json", "validation.html")


def validation_csv(rows: Sequence[dict[str, Any]]) -> str:
    """CSV text of report rows.

    Columns are the union of the rows' keys in first-seen order; lists and
    dicts are written as JSON, None as an empty cell.

    Parameters
    ----------
    rows : sequence of dict
        E.g. :meth:`ValidationReport.rows`.

    Returns
    -------
    str
        CSV text with a header line, one line per row.
    """
    fields: list[str] = []
    for r in rows:
        fields += [k for k in r if k not in fields]
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=fields, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow(
            {
                k: json.dumps(v) if isinstance(v, list | dict) else ("" if v is None else v)
                for k, v in r.items()
            }
        )
    return buf.getvalue()


def write_validation_outputs(
    report: ValidationReport, out_dir: str | os.PathLike[str], *, figures: bool = True
) -> list[Path]:
    """Write a report's table, JSON document, HTML page and (optionally) figures.

    Parameters
    ----------
    report : ValidationReport
        From :func:`~psdbound.validation.validate_cutoff`.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write the PNG figures (matplotlib) and show them on the page.

    Returns
    -------
    list of Path
        The files written, in order: CSV, JSON, the figures, HTML.
    """
    from psdbound.reports.command_pages import write_validation_page

    out = Path(out_dir)
    doc = report.to_dict()
    written = [
        atomic_write_text(out / OUTPUT_FILES[0], validation_csv(report.rows())),
        write_json(out / OUTPUT_FILES[1], doc),
    ]
    drawn = _figures(report, out) if figures else []
    written += [p for _, p in drawn]
    written.append(write_validation_page(out / OUTPUT_FILES[2], doc, drawn))
    return written


def _figures(report: ValidationReport, out: Path) -> list[tuple[str, Path]]:
    """Draw the expansion and (when one ran) the direct-simulation figure; (caption, file)."""
    from psdbound.validation.figures import plot_direct, plot_expansion, save_figure

    fig = plot_expansion(report.expansion)
    drawn = [
        (
            "Harmonic power of the Jacobi-Anger expansion against frequency (Hz), per geometry "
            "and convention, with the cutoff f_c.",
            save_figure(fig, out / "validation_expansion.png"),
        )
    ]
    if report.direct:
        fig = plot_direct(report.direct, report.expansion)
        drawn.append(
            (
                "Cumulative fraction of the simulated multipath power against frequency (Hz), "
                "per geometry and convention, with the cutoff f_c.",
                save_figure(fig, out / "validation_direct.png"),
            )
        )
    return drawn
