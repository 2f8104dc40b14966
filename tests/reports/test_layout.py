"""The explicit layout of the report figures (psdbound.reports.layout): nothing clipped or crowded.

Every report figure is placed by margins measured from its own texts (no
layout engine). Drawn, every axes' texts (tick labels, axis labels, title,
legend) must lie inside the figure, and the texts of two axes, or of an
axes and a figure legend, must not run into each other: on the demo's
figures, on wide lane labels (dual-antenna pairs), on the code-multipath
Q-Q figure (two columns and a heading) and on the VPL figure (two rows).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg

import psdbound
from psdbound.reports.figures import FIGURES, fig_windows
from psdbound.reports.figures_aviation import fig_overbound_qq, fig_vpl
from psdbound.reports.figures_base import new_figure
from psdbound.reports.layout import EDGE_IN, place_grid


@pytest.fixture(scope="module")
def demo_doc():
    return psdbound.fit().document


def _drawn_tick_labels(axis):
    """The tick labels an axis drew (ticks in view, labels shown and not empty)."""
    lo, hi = sorted(axis.get_view_interval())
    span = hi - lo
    out = []
    for tick in axis.get_major_ticks() + axis.get_minor_ticks():
        if lo - 1e-9 * span <= tick.get_loc() <= hi + 1e-9 * span:
            out += [t for t in (tick.label1, tick.label2) if t.get_visible() and t.get_text()]
    return out


def _texts(ax, renderer):
    """Window extents of every text an axes drew: tick labels, axis labels, title, legend."""
    texts = [ax.title, ax.xaxis.label, ax.yaxis.label]
    texts += [ax.xaxis.get_offset_text(), ax.yaxis.get_offset_text()]
    texts += _drawn_tick_labels(ax.xaxis) + _drawn_tick_labels(ax.yaxis)
    boxes = [t.get_window_extent(renderer) for t in texts if t.get_visible() and t.get_text()]
    legend = ax.get_legend()
    return boxes + ([legend.get_window_extent(renderer)] if legend else [])


def _assert_laid_out(fig, name):
    """Draw ``fig``: every text inside it; no text on another axes' frame or texts."""
    assert fig.get_layout_engine() is None, name
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    page = fig.bbox
    parts = [(f"axes {k}", ax.bbox, _texts(ax, renderer)) for k, ax in enumerate(fig.axes)]
    for k, leg in enumerate(fig.legends):
        box = leg.get_window_extent(renderer)
        parts.append((f"figure legend {k}", box, [box]))
    for what, _, boxes in parts:
        for b in boxes:
            inside = b.x0 >= page.x0 - 1 and b.x1 <= page.x1 + 1
            assert inside and b.y0 >= page.y0 - 1 and b.y1 <= page.y1 + 1, (
                f"{name}: a text of {what} leaves the figure: {b} (figure {page})"
            )
    for (wa, frame_a, texts_a), (wb, frame_b, texts_b) in combinations(parts, 2):
        for a, b in (
            [(t, frame_b) for t in texts_a]
            + [(frame_a, t) for t in texts_b]
            + [(t, u) for t in texts_a for u in texts_b]
        ):
            assert not a.overlaps(b), f"{name}: {wa} and {wb} run into each other: {a} / {b}"


def test_demo_figures_are_laid_out(demo_doc):
    drawn = 0
    for key, _, func in FIGURES:
        fig = func(demo_doc)
        if fig is not None:
            _assert_laid_out(fig, key)
            drawn += 1
    assert drawn >= 8


def test_wide_lane_labels_move_the_axes_right():
    """Pair lanes ('G01-G05') take a wider margin than single satellites, and fit in it."""
    t0 = 1.3e9

    def doc(names):
        arcs = [{"sat": s, "t0": t0, "t1": t0 + 7200.0} for s in names]
        wins = [{"sats": s, "t_start_gps_s": t0, "t_stop_gps_s": t0 + 3600.0} for s in names]
        return {
            "method": "DA" if "-" in names[0] else "DF",
            "data_span": {"start_gps_s": t0, "stop_gps_s": t0 + 7200.0, "n_arcs": len(names)},
            "windows": {"count": len(wins), "per_window": wins, "never_stationary_s": 0.0},
            "screening": {"excluded": [], "excluded_s": 0.0},
            "figures": {"t_ref_gps_s": t0, "arcs": arcs, "mapped": []},
        }

    single = fig_windows(doc([f"G{k:02d}" for k in range(1, 9)]))
    pairs = fig_windows(doc([f"G{k:02d}-G{k + 10:02d}" for k in range(1, 9)]))
    _assert_laid_out(single, "single lanes")
    _assert_laid_out(pairs, "pair lanes")
    assert pairs.axes[0].get_position().x0 > single.axes[0].get_position().x0


def test_qq_and_vpl_figures_are_laid_out():
    rng = np.random.default_rng(3)
    bins = [
        {
            "elevation_deg": [lo, lo + 30.0],
            "bias": 0.0,
            "sigma": 0.3 / (1 + k),
            "std": 0.25 / (1 + k),
            "inflation": 1.2,
            "n": 500,
            "n_eff": 120.0,
        }
        for k, lo in enumerate((0.0, 30.0, 60.0))
    ]
    z = np.sort(rng.standard_normal(200))
    qq = {"[{:g}, {:g}) deg".format(*b["elevation_deg"]): {"z": z, "x": z} for b in bins}
    fig = fig_overbound_qq({"method": "paired", "bins": bins}, qq, title="Q-Q " * 12, unit="m")
    _assert_laid_out(fig, "code Q-Q")
    t = 1.3e9 + 30.0 * np.arange(200)
    vpl = {
        "t_gps_s": t.tolist(),
        "time_gps": ["2021-03-01T00:00:00"],
        "vpl_m": (10 + rng.random(200)).tolist(),
        "vpl_h0_m": (9 + rng.random(200)).tolist(),
        "vpl_eph_m": (8 + rng.random(200)).tolist(),
        "val_m": 35.0,
        "n_sats": rng.integers(5, 12, 200).tolist(),
        "elevation_mask_deg": 5.0,
        "options": {
            "process": "GM",
            "base_frequency": "L1",
            "tau_gnd_s": 100.0,
            "tau_air_s": 100.0,
            "x_air_m": 5000.0,
        },
    }
    _assert_laid_out(fig_vpl(vpl), "VPL")


def test_margins_follow_the_tick_labels():
    """Longer y tick labels give a wider left margin; a bare grid keeps only the edge."""
    narrow, wide = new_figure(3.0), new_figure(3.0)
    narrow.add_subplot().plot([0, 1], [0, 1])
    wide.add_subplot().plot([0, 1], [0, 123456.0])
    for fig in (narrow, wide):
        place_grid(fig)
    assert wide.axes[0].get_position().x0 > narrow.axes[0].get_position().x0
    bare = new_figure(3.0)
    ax = bare.add_subplot()
    ax.set_axis_off()
    place_grid(bare)
    assert ax.get_position().x0 * bare.get_figwidth() == pytest.approx(EDGE_IN)
