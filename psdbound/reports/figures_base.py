"""Shared pieces of the report figures: sizes, a bare figure, the finish, time origin.

Every figure is :data:`FIG_W_IN` wide, the text width of an A4 page, so the
PDF places it at its own size (no rescaling, text at the size it was drawn);
figures up to :data:`HALF_PAGE_H_IN` tall go two to a page.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Any

import matplotlib

matplotlib.use("Agg")
from matplotlib.artist import Artist  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.ticker import LogFormatterSciNotation, LogLocator  # noqa: E402

from psdbound.reports.layout import place_grid  # noqa: E402

__all__ = [
    "FIG_W_IN",
    "HALF_PAGE_H_IN",
    "FULL_PAGE_H_IN",
    "PlainLogFormatter",
    "finish",
    "new_figure",
    "t0_gps_s",
]

#: Width of every figure: A4 (8.27 in) less two 0.45 in margins, in.
FIG_W_IN = 7.35
#: Tallest figure that still goes two to an A4 page (with captions), in.
HALF_PAGE_H_IN = 4.9
#: Tallest figure a page holds (with its caption), in.
FULL_PAGE_H_IN = 10.3


def new_figure(height_in: float, *, width_in: float = FIG_W_IN) -> Figure:
    """Return a figure (no layout engine, no pyplot state) of the report's width.

    Its grid of axes is placed by :func:`finish` (explicit layout,
    :func:`psdbound.reports.layout.place_grid`).

    Parameters
    ----------
    height_in : float
        Height, in (clipped to one A4 page).
    width_in : float, default :data:`FIG_W_IN`
        Width, in.

    Returns
    -------
    matplotlib.figure.Figure
        Not registered with pyplot: nothing to close, garbage-collected.
    """
    return Figure(figsize=(width_in, min(float(height_in), FULL_PAGE_H_IN)))


def t0_gps_s(r: dict[str, Any]) -> float:
    """Time origin of the figures: the first epoch of the observations, GPS s."""
    return float(r["figures"].get("t_ref_gps_s", r["data_span"]["start_gps_s"]))


_SUPERSCRIPT = str.maketrans(
    "0123456789-", "\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079\u207b"
)


class PlainLogFormatter(LogFormatterSciNotation):
    """Log-axis tick labels as plain text with Unicode exponents (10⁻³, 2×10⁻³).

    The same labels as matplotlib's default, without mathtext: parsing a
    mathtext label costs about 20 ms, and a report has dozens of them.
    """

    def __call__(self, x: float, pos: int | None = None) -> str:
        """Return the label of the tick at ``x``."""
        s = super().__call__(x, pos)
        if not s.startswith("$"):
            return s
        s = s.strip("$").replace("\\mathdefault{", "", 1)[:-1].replace("\\times", "\u00d7")
        s = re.sub(r"\^\{?(-?\d+)\}?", lambda m: m.group(1).translate(_SUPERSCRIPT), s)
        return s.replace("-", "\u2212")


def finish(fig: Figure, *, above: Sequence[Artist] = ()) -> Figure:
    """Give every log axis plain-text tick labels and minor ticks at 2 and 5, place the axes.

    Minor ticks at 2 and 5 (not 2..9) keep a readable grid and make a third
    fewer tick objects, which dominate the drawing time of a small figure.
    The grid of axes is then placed with margins measured from the figure's
    texts (:func:`psdbound.reports.layout.place_grid`).

    Parameters
    ----------
    fig : Figure
        The figure, complete.
    above : sequence of Artist, optional
        Figure-level artists above the axes (a figure legend, a heading).

    Returns
    -------
    Figure
        ``fig``.
    """
    for ax in fig.axes:
        for axis, scale in ((ax.xaxis, ax.get_xscale()), (ax.yaxis, ax.get_yscale())):
            if scale == "log":
                axis.set_minor_locator(LogLocator(subs=(2.0, 5.0)))
                axis.set_major_formatter(PlainLogFormatter())
                axis.set_minor_formatter(PlainLogFormatter(labelOnlyBase=False))
    place_grid(fig, above=above)
    return fig
