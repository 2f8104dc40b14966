"""Report figures, drawn from a result document alone (``result.json``).

Every function takes the result ``dict`` and returns a matplotlib
:class:`~matplotlib.figure.Figure` (Agg, explicit layout by
:mod:`psdbound.reports.layout`, not registered with pyplot), or None when
the result holds no data for that figure. Every figure is one A4 text
width wide (:data:`~psdbound.reports.figures_base.FIG_W_IN`)
so that the PDF places it unscaled, two to a page where they fit; every axis
label carries its unit in brackets.

The functions live in :mod:`psdbound.reports.figures_time` (against time),
:mod:`psdbound.reports.figures_spectra` (against frequency),
:mod:`psdbound.reports.figures_sky` (on the sky) and
:mod:`psdbound.reports.figures_aviation` (the optional code multipath);
:data:`FIGURES` lists them in report order.
"""

from __future__ import annotations

from psdbound.reports.figures_aviation import fig_code_qq
from psdbound.reports.figures_base import t0_gps_s
from psdbound.reports.figures_sky import fig_sky
from psdbound.reports.figures_spectra import (
    cutoff_curves,
    fig_cutoff_envelope,
    fig_jacobi_anger,
    fig_psds_bound,
    fig_tau_search,
)
from psdbound.reports.figures_time import fig_df_filter, fig_mapped, fig_screening, fig_windows

__all__ = [
    "FIGURES",
    "cutoff_curves",
    "fig_code_qq",
    "fig_cutoff_envelope",
    "fig_df_filter",
    "fig_jacobi_anger",
    "fig_mapped",
    "fig_psds_bound",
    "fig_screening",
    "fig_sky",
    "fig_tau_search",
    "fig_windows",
    "t0_gps_s",
]

#: (key, caption, function) of every report figure, in report order.
FIGURES = (
    (
        "windows",
        "Arcs, spans screened out (by reason) and stationary windows per satellite",
        fig_windows,
    ),
    ("df_filter", "Dual-frequency difference before and after filtering", fig_df_filter),
    ("screening", "Screening per satellite: ROTI vs threshold, cuts by test", fig_screening),
    ("sky", "Sky view: multipath RMS by azimuth and elevation", fig_sky),
    ("mapped", "Elevation-mapped residuals", fig_mapped),
    (
        "psds",
        "Window PSD estimates, their pooled upper limits and the bound (estimates "
        "scatter above their true PSD; the bound covers the true PSDs at the stated confidence)",
        fig_psds_bound,
    ),
    ("tau", "Tightness search over tau", fig_tau_search),
    ("cutoff", "Cutoff criterion and f_c", fig_cutoff_envelope),
    ("jacobi_anger", "Jacobi-Anger cutoff check", fig_jacobi_anger),
    (
        "code_qq",
        "Code multipath (carrier levelled): Q-Q per elevation bin and Gaussian overbounds",
        fig_code_qq,
    ),
)
