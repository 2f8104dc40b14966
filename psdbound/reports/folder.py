"""The output folder of a run: the result file and its reports, written atomically.

Drawing is imported only when reports are written (matplotlib takes about
0.3 s to import): a run that writes ``result.json`` alone never loads it.
"""

from __future__ import annotations

import os
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from psdbound.common.outputs import output_folder
from psdbound.results import write_document

__all__ = ["write_report_folder"]


def write_report_folder(
    document: dict[str, Any],
    out_dir: str | os.PathLike[str],
    *,
    pdf: bool = True,
    report: bool = True,
    overwrite: bool = False,
    option: str = "output folder",
    extra: dict[str, bytes] | None = None,
    keep: Sequence[str] = (),
) -> dict[str, Path]:
    """Write ``result.json``, ``report.html`` and ``report.pdf`` safely and atomically.

    Everything is written into a temporary folder that is installed only
    when complete: a failed run leaves no half-written folder (and an
    existing folder untouched). An existing ``out_dir`` is replaced only when
    it is empty or a previous psdbound output; any other folder is refused
    unless ``overwrite`` (then psdbound's three files are written into it and
    nothing else is touched); an existing file is always refused (see
    :mod:`psdbound.common.outputs`).

    Parameters
    ----------
    document : dict
        The result document to write and render.
    out_dir : str or path-like
        Destination folder.
    pdf : bool, default True
        Also write the PDF report.
    report : bool, default True
        Write the reports at all: with ``False`` only ``result.json`` (and
        ``extra``) is written, and matplotlib is not imported; ``psdbound
        report`` renders them later from the result file alone.
    overwrite : bool, default False
        Allow writing into a folder that is not a psdbound output.
    extra : dict of str to bytes, optional
        Further files of the run (name -> content, e.g. ``series.csv.gz``),
        written into the same folder in the same atomic step.
    option : str, default "output folder"
        How to name the destination in messages (the CLI passes ``"--out"``).
    keep : sequence of str, optional
        Files of the existing ``out_dir`` to keep as they are (copied into the
        new folder before it is installed): ``psdbound report`` re-rendering
        a result in its own folder keeps the run's ``series.csv.gz``, and its
        ``report.pdf`` when no PDF is drawn. A name that is absent is skipped.

    Returns
    -------
    dict of str to Path
        ``{"result": ..., "html": ..., "pdf": ...}`` (the files written).

    Raises
    ------
    InputError
        The destination is refused (checked before anything is rendered).
    """
    out = Path(out_dir)
    with output_folder(out, overwrite=overwrite, option=option) as tmp:
        write_document(tmp / "result.json", document)
        if report:
            _write_reports(document, tmp, pdf=pdf)
        for name, data in (extra or {}).items():
            (tmp / name).write_bytes(data)
        for name in keep:
            if (out / name).is_file() and not (tmp / name).exists():
                shutil.copy2(out / name, tmp / name)
    paths = {"result": out / "result.json"}
    if report:
        paths["html"] = out / "report.html"
    if report and pdf:
        paths["pdf"] = out / "report.pdf"
    return paths | {Path(name).name.split(".")[0]: out / name for name in extra or {}}


def _write_reports(document: dict[str, Any], folder: Path, *, pdf: bool) -> None:
    """Draw the figures once and write ``report.html`` (and ``report.pdf``) into ``folder``."""
    from psdbound.reports.render import render_html, render_pdf, rendered_figures

    figures = rendered_figures(document)  # drawn once: the same pixels in both reports
    (folder / "report.html").write_text(render_html(document, rendered=figures))
    if pdf:
        render_pdf(document, folder / "report.pdf", rendered=figures)
