"""Reports: figure data from the stage results, figures, HTML and PDF reports."""

from __future__ import annotations

from psdbound.reports.figure_data import figure_data, psd_outline
from psdbound.reports.figures import FIGURES
from psdbound.reports.render import render_html, render_pdf, write_report_folder

__all__ = [
    "FIGURES",
    "figure_data",
    "psd_outline",
    "render_html",
    "render_pdf",
    "write_report_folder",
]
