"""Reports: figure data from the stage results, figures, HTML and PDF reports.

The drawing is imported on first use (:mod:`psdbound.common.lazy`): writing a
result folder without reports does not load matplotlib. The figure data
(numpy only) are imported here: their function shares its submodule's name,
and a lazy export would be shadowed by the submodule once it is imported.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports
from psdbound.reports.figure_data import figure_data, psd_outline

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.reports.figures import FIGURES
    from psdbound.reports.folder import write_report_folder
    from psdbound.reports.render import render_html, render_pdf

__all__ = [
    "FIGURES",
    "figure_data",
    "psd_outline",
    "render_html",
    "render_pdf",
    "write_report_folder",
]

_EXPORTS = {
    "FIGURES": ("psdbound.reports.figures", "FIGURES"),
    "render_html": ("psdbound.reports.render", "render_html"),
    "render_pdf": ("psdbound.reports.render", "render_pdf"),
    "write_report_folder": ("psdbound.reports.folder", "write_report_folder"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
