"""Reports: figures, a self-contained HTML report and a PDF report from a result."""

from __future__ import annotations

from psdbound.reports.figures import FIGURES
from psdbound.reports.render import render_html, render_pdf, write_report_folder

__all__ = ["FIGURES", "render_html", "render_pdf", "write_report_folder"]
