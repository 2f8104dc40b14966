"""Explicit layout of the report figures: margins measured from their own texts.

Matplotlib's constrained layout places the axes by laying out every axis's
ticks and labels to measure them, twice, before the figure is drawn and
lays them out again: about 0.4 s of the 1.4 s of CPU the nine figures of a
station day took. A report figure is simple (one grid of axes, a title per
axes, at most a figure legend or heading above it), so :func:`place_grid`
computes its margins from the texts alone: the tick labels as the axis's
own locator and formatter write them (no tick objects are made), the axis
labels and the titles (text extents, without hinting). On the ESBC day
and the demo the axes sit where constrained layout put them, within
0.04 in: the same pictures, drawn in 1.16 s of CPU instead of 1.42 s
(``tests/reports/test_layout.py`` checks that no text leaves the figure or
runs into a neighbour's).

Axes outside the grid (the sky figure's polar axes and colour bar, placed
by :func:`psdbound.reports.figures_sky.fig_sky` with :func:`axis_room_in`)
keep the positions they were given.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache

import matplotlib as mpl
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.backend_bases import RendererBase
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.font_manager import FontProperties
from matplotlib.textpath import text_to_path

__all__ = ["EDGE_IN", "GAP_IN", "axis_room_in", "place_grid", "renderer_of"]

#: Space between the outermost text and the figure's edge, in.
EDGE_IN = 0.03
#: Space between the texts of neighbouring axes, in.
GAP_IN = 0.06
_PT = 1.0 / 72.0


def renderer_of(fig: Figure) -> RendererBase:
    """Return the figure's Agg renderer (an Agg canvas is attached when it has none)."""
    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    return canvas.get_renderer()


def _labels(axis: Axis) -> list[tuple[float, str]]:
    """(value, text) of the labelled ticks in view, major then minor, as the axis writes them."""
    lo, hi = sorted(axis.get_view_interval())
    tol = 1e-10 * max(abs(lo), abs(hi), 1e-300)
    out = []
    for locs, fmt in (
        (axis.get_majorticklocs(), axis.get_major_formatter()),
        (axis.get_minorticklocs(), axis.get_minor_formatter()),
    ):
        texts = fmt.format_ticks(list(locs))
        out += [
            (float(v), s) for v, s in zip(locs, texts, strict=True) if lo - tol <= v <= hi + tol
        ]
    return [(v, s) for v, s in out if s]


@lru_cache(maxsize=4096)
def _text_size_in(text: str, size: float | str) -> tuple[float, float]:
    """(width, height) of one line of text at a font size as matplotlib boxes it, in.

    A line is at least as tall as ``"lp"`` (matplotlib's rule: lines of
    digits and of letters with descenders take the same height). Measured
    without hinting (resolution-independent), which differs from the drawn
    text by a fraction of a pixel.
    """
    font = FontProperties(size=size)
    w, h, _ = text_to_path.get_text_width_height_descent(text, font, ismath=False)
    _, h_lp, _ = text_to_path.get_text_width_height_descent("lp", font, ismath=False)
    return w * _PT, max(h, h_lp) * _PT


def axis_room_in(axis: Axis, renderer: RendererBase) -> float:
    """Depth of an axis's ticks, tick labels and label outside its axes, in.

    Across the axis: the tick length (when ticks are drawn), the tick pad and
    the widest tick label (a y axis) or the tallest (an x axis), then the
    label pad and the axis label.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        An x or y axis (of any side).
    renderer : RendererBase
        The figure's renderer (:func:`renderer_of`).

    Returns
    -------
    float
    """
    if not (axis.get_visible() and axis.axes.axison):
        return 0.0
    name = axis.axis_name
    params = axis.get_tick_params()
    sides = ("bottom", "top") if name == "x" else ("left", "right")
    ticks = any(params.get(s, s in ("bottom", "left")) for s in sides)
    shown = any(params.get(f"label{s}", s in ("bottom", "left")) for s in sides)
    dpi = axis.get_figure(root=True).dpi
    room = params.get("length", mpl.rcParams[f"{name}tick.major.size"]) * _PT if ticks else 0.0
    if shown:
        size = params.get("labelsize", mpl.rcParams[f"{name}tick.labelsize"])
        sizes = [_text_size_in(s, size) for _, s in _labels(axis)]
        depth = max((w if name == "y" else h for w, h in sizes), default=0.0)
        room += params.get("pad", mpl.rcParams[f"{name}tick.major.pad"]) * _PT + depth
    if axis.label.get_visible() and axis.label.get_text():
        box = axis.label.get_window_extent(renderer)
        room += axis.labelpad * _PT + (box.width if name == "y" else box.height) / dpi
    return room


def _title_room_in(ax: Axes, renderer: RendererBase) -> float:
    """How far an axes' (centre) title reaches above it, in (0 without one).

    The title stands on its baseline a pad above the axes: its descent lies in the pad.
    """
    if not (ax.title.get_visible() and ax.title.get_text()):
        return 0.0
    top = ax.title.get_window_extent(renderer).y1 - ax.get_window_extent(renderer).y1
    return max(0.0, top / ax.get_figure(root=True).dpi)


@dataclass(frozen=True)
class _Room:
    """Depth of an axes' texts on each side, in."""

    left: float
    bottom: float
    top: float


def _rooms(grid: Sequence[Axes], renderer: RendererBase) -> dict[Axes, _Room]:
    return {
        ax: _Room(
            axis_room_in(ax.yaxis, renderer),
            axis_room_in(ax.xaxis, renderer),
            _title_room_in(ax, renderer),
        )
        for ax in grid
    }


def _above_in(fig: Figure, above: Sequence[Artist], renderer: RendererBase) -> float:
    """Depth below the figure's top edge of artists placed above the grid, in."""
    h_px = fig.get_figheight() * fig.dpi
    lows = [a.get_window_extent(renderer).y0 for a in above if a.get_visible()]
    return (h_px - min(lows)) / fig.dpi if lows else 0.0


def place_grid(fig: Figure, *, above: Sequence[Artist] = ()) -> None:
    """Place a figure's grid of axes with margins measured from its texts.

    The left margin holds the widest y-axis texts of the first column, the
    bottom one the x-axis texts of the last row, the top one the titles of
    the first row below the ``above`` artists; gaps between rows and
    columns hold the titles and axis texts between them. The right margin
    holds the x tick labels that reach past the last column. Nothing
    happens to a figure without a grid of axes.

    Parameters
    ----------
    fig : Figure
        The figure, with all its texts.
    above : sequence of Artist, optional
        Figure-level artists above the grid (a figure legend, a heading).
    """
    first = next((ax for ax in fig.axes if ax.get_subplotspec() is not None), None)
    if first is None:
        return
    gs = first.get_subplotspec().get_gridspec()
    grid = [
        ax for ax in fig.axes if ax.get_subplotspec() and ax.get_subplotspec().get_gridspec() is gs
    ]
    renderer = renderer_of(fig)
    above_in = _above_in(fig, above, renderer)
    # twice, as constrained layout does: an axis's ticks (and so the width of its labels)
    # depend on its length, which the first placement changes
    for _ in range(2):
        _place_once(fig, grid, gs.get_geometry(), above_in, renderer)


def _place_once(
    fig: Figure,
    grid: Sequence[Axes],
    shape: tuple[int, int],
    above_in: float,
    renderer: RendererBase,
) -> None:
    """Measure the texts of the grid's axes as they are placed now, and place them again."""
    nrows, ncols = shape
    room = _rooms(grid, renderer)
    spans = {ax: (ax.get_subplotspec().rowspan, ax.get_subplotspec().colspan) for ax in grid}

    def most(values: list[float]) -> float:
        return max(values, default=0.0)

    margins = {
        "left": most([room[a].left for a in grid if spans[a][1].start == 0]) + EDGE_IN,
        "bottom": most([room[a].bottom for a in grid if spans[a][0].stop == nrows]) + EDGE_IN,
        "top": most([room[a].top for a in grid if spans[a][0].start == 0]) + above_in + EDGE_IN,
        "right": EDGE_IN,
    }
    hspace = most([room[a].top for a in grid if spans[a][0].start > 0]) + most(
        [room[a].bottom for a in grid if spans[a][0].stop < nrows]
    )
    wspace = most([room[a].left for a in grid if spans[a][1].start > 0])
    gaps = (hspace + GAP_IN if nrows > 1 else 0.0, wspace + GAP_IN if ncols > 1 else 0.0)
    _adjust(fig, margins, gaps, (nrows, ncols))
    margins["right"] += most([_overhang_in(a, renderer) for a in grid if spans[a][1].stop == ncols])
    if margins["right"] > EDGE_IN:
        _adjust(fig, margins, gaps, (nrows, ncols))


def _adjust(
    fig: Figure, m: dict[str, float], gaps: tuple[float, float], shape: tuple[int, int]
) -> None:
    """Apply margins and gaps given in inches."""
    w, h = fig.get_size_inches()
    rows, cols = shape
    cell_h = max((h - m["top"] - m["bottom"] - (rows - 1) * gaps[0]) / rows, 1e-3)
    cell_w = max((w - m["left"] - m["right"] - (cols - 1) * gaps[1]) / cols, 1e-3)
    fig.subplots_adjust(
        left=m["left"] / w,
        right=1.0 - m["right"] / w,
        bottom=m["bottom"] / h,
        top=1.0 - m["top"] / h,
        hspace=gaps[0] / cell_h,
        wspace=gaps[1] / cell_w,
    )


def _overhang_in(ax: Axes, renderer: RendererBase) -> float:
    """How far the x tick labels reach past the axes' right edge, in (0 when they do not)."""
    params = ax.xaxis.get_tick_params()
    if not (params.get("labelbottom", True) or params.get("labeltop", False)):
        return 0.0
    dpi = ax.get_figure(root=True).dpi
    size = params.get("labelsize", mpl.rcParams["xtick.labelsize"])
    right = ax.get_window_extent(renderer).x1
    to_px = ax.get_xaxis_transform()
    reach = [
        to_px.transform((v, 0.0))[0] + 0.5 * _text_size_in(s, size)[0] * dpi
        for v, s in _labels(ax.xaxis)
    ]
    return max(0.0, (max(reach, default=right) - right) / dpi)
