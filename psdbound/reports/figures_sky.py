"""Report figure on the sky: the isolated multipath's RMS by azimuth and elevation.

Station operators find a reflector by where on the sky the multipath is
strong: a wall or a roof edge shows as a sector of high RMS at low
elevation, a ground reflection as a ring. The figure is drawn from the
``figures.sky`` cells of the result document
(:func:`psdbound.reports.figure_data.sky_cells`), so a report redrawn from
``result.json`` shows it too.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from psdbound.reports.figures_base import HALF_PAGE_H_IN, finish, new_figure
from psdbound.reports.layout import EDGE_IN, axis_room_in, renderer_of

__all__ = ["fig_sky"]


def _grid(d: dict[str, Any]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cell edges (azimuth in radians, zenith distance in degrees) and the RMS in mm."""
    az = np.radians(np.asarray(d["az_edges_deg"], dtype=float))
    zd = 90.0 - np.asarray(d["el_edges_deg"], dtype=float)
    rms = np.array([[np.nan if x is None else 1000.0 * x for x in row] for row in d["rms_m"]])
    return az, zd, rms


def fig_sky(r: dict[str, Any]) -> Figure | None:
    """Sky view: RMS of the isolated multipath per azimuth-elevation cell, mm.

    Polar axes with north up and azimuth clockwise; the radius is the zenith
    distance (90 deg minus elevation), so the horizon is the outer ring.
    Empty cells are left blank. The title gives the bound's sigma at zenith
    (``sqrt(sigma_GM^2 + sigma_WN^2)``) for comparison: the bound is
    elevation-mapped, the cells are not.
    """
    d = (r.get("figures") or {}).get("sky")
    if not d:
        return None
    az, zd, rms = _grid(d)
    fig = new_figure(HALF_PAGE_H_IN)
    ax = fig.add_axes((0.0, 0.0, 1.0, 1.0), projection="polar")  # placed by _place
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    mesh = ax.pcolormesh(az, zd, np.ma.masked_invalid(rms), cmap="viridis", shading="flat")
    ax.set_ylim(0.0, 90.0)
    ax.set_yticks([0.0, 30.0, 60.0, 80.0], ["90", "60", "30", "10"], fontsize=7)
    ax.set_rlabel_position(22.5)
    ax.tick_params(axis="x", labelsize=7)
    ax.grid(alpha=0.4)
    ax.set_xlabel("azimuth, clockwise from north [deg]", fontsize=8)
    ax.set_ylabel("elevation [deg]", fontsize=8)
    ax.yaxis.set_label_coords(-0.13, 0.5)  # left of the 270 deg label, not on it
    cb = fig.colorbar(mesh, cax=fig.add_axes((0.9, 0.1, 0.02, 0.8)))
    cb.set_label("isolated multipath RMS [mm]")
    b = r["bound"]
    sigma = 1000.0 * float(np.hypot(b["sigma_gm_m"], b["sigma_wn_m"]))
    ax.set_title(
        f"Screened multipath on the sky ({d['n_samples']} samples); bound sigma at "
        f"zenith {sigma:.2f} mm",
        fontsize=9,
    )
    _place(fig, ax, cb.ax)
    return finish(fig)


#: Room below the sky (azimuth labels and the axis label) and above it (north's label and
#: the title), in; the colour bar's width and its distance from the sky (the east label), in.
_BELOW_IN, _ABOVE_IN, _BAR_W_IN, _BAR_GAP_IN = 0.45, 0.47, 0.16, 0.75


def _place(fig: Figure, sky: Any, bar: Any) -> None:
    """Put the sky as large as the figure's height allows, its colour bar at the right edge.

    The colour bar's right margin holds its tick labels and label (measured);
    the bar is 0.8 of the sky's diameter tall, centred on it.
    """
    w, h = fig.get_size_inches()
    diameter = h - _BELOW_IN - _ABOVE_IN
    bar_x = w - EDGE_IN - axis_room_in(bar.yaxis, renderer_of(fig)) - _BAR_W_IN
    sky_x = bar_x - _BAR_GAP_IN - diameter
    sky.set_position((sky_x / w, _BELOW_IN / h, diameter / w, diameter / h))
    bar_y = _BELOW_IN + 0.1 * diameter
    bar.set_position((bar_x / w, bar_y / h, _BAR_W_IN / w, 0.8 * diameter / h))
