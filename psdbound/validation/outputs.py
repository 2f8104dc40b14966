"""Output files of a cutoff validation: CSV table, JSON document and PNG figures.

:func:`write_validation_outputs` writes, into a folder, ``validation.csv``
(:func:`validation_csv` of the report's rows), ``validation.json`` (the
report's dict) and, with figures, ``validation_expansion.png`` and (when a
direct simulation ran) ``validation_direct.png``, each atomically
(:mod:`psdbound.common`).
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

#: Table and document written by :func:`write_validation_outputs`.
OUTPUT_FILES = ("validation.csv", "validation.json")


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
    """Write a report's table, JSON document and (optionally) figures.

    Parameters
    ----------
    report : ValidationReport
        From :func:`~psdbound.validation.validate_cutoff`.
    out_dir : str or path-like
        Output folder (created if missing).
    figures : bool, default True
        Also write the PNG figures (matplotlib).

    Returns
    -------
    list of Path
        The files written, in order.
    """
    out = Path(out_dir)
    written = [
        atomic_write_text(out / OUTPUT_FILES[0], validation_csv(report.rows())),
        write_json(out / OUTPUT_FILES[1], report.to_dict()),
    ]
    if figures:
        from psdbound.validation.figures import plot_direct, plot_expansion, save_figure

        written.append(
            save_figure(plot_expansion(report.expansion), out / "validation_expansion.png")
        )
        if report.direct:
            fig = plot_direct(report.direct, report.expansion)
            written.append(save_figure(fig, out / "validation_direct.png"))
    return written
