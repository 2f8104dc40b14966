"""Report figures against time: windows per satellite, filter, screening, mapped series.

Each function takes the result document and returns a
:class:`~matplotlib.figure.Figure` or None when the document holds no data
for it. Counts in titles are read from the same fields as the report's
tables (``data_span.n_arcs``, ``windows.count``, ``windows.never_stationary_s``,
``screening.excluded_s``), never recounted from the figure data.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from psdbound.reports.figures_base import finish, new_figure, t0_gps_s
from psdbound.reports.layout import renderer_of
from psdbound.screening.rot import ROTI_BLOCK_S

__all__ = ["fig_df_filter", "fig_mapped", "fig_screening", "fig_windows"]

#: Height of one satellite lane of the window figure, in (32 lanes fit half a page).
LANE_IN = 0.112

_GREENS = ("#2ca02c", "#145a14")
#: Colour of the screened-out spans by why they were excluded (``screening.excluded[].kind``).
_SCREENED = {"ionosphere": "#ff7f0e", "implausible": "#9467bd", "short remainder": "0.45"}


def _spans(
    items: list[tuple[str, float, float]], lane: dict[str, int], t0: float, half: float
) -> tuple[np.ndarray, np.ndarray]:
    """Rectangles (as polygon vertices) of time spans in their lanes, and the lane order."""
    if not items:
        return np.zeros((0, 4, 2)), np.zeros(0, dtype=int)
    y = np.array([lane[s] for s, _, _ in items], dtype=float)
    a = (np.array([x[1] for x in items], dtype=float) - t0) / 3600.0
    b = (np.array([x[2] for x in items], dtype=float) - t0) / 3600.0
    verts = np.stack(
        [
            np.column_stack([a, y - half]),
            np.column_stack([a, y + half]),
            np.column_stack([b, y + half]),
            np.column_stack([b, y - half]),
        ],
        axis=1,
    )
    return verts, y.astype(int)


def _lane_key(s: str) -> tuple[int, int, str]:
    """Order lanes by system (GPS first) and number: G2 before G10 before R01."""
    digits = "".join(c for c in s[1:3] if c.isdigit())
    system = "GRECJIS".find(s[:1])
    return (system if system >= 0 else 99, int(digits) if digits else 0, s)


def fig_windows(r: dict[str, Any]) -> Figure | None:
    """Stationary windows in satellite lanes (pairs for dual-antenna), time in hours.

    Per lane: the tracked arcs (light grey: what is left of them is data the
    isolation dropped, e.g. the filter's edges), the spans screening removed,
    coloured by why (ionosphere orange, beyond the carrier-multipath limit
    purple, remainders too short for a window dark grey; the legend counts
    the spans and gives the screen's false-alarm probability), the stationary
    windows (green, alternating shades so that neighbours stay apart) and the
    stretches never found stationary (red), each only in its own lane.
    Collections, not one artist per window: a day with 1,000 windows in 40
    lanes draws as fast and stays readable.
    """
    figs = r["figures"]
    w = r["windows"]
    wins = w.get("per_window") or []
    arcs = figs.get("arcs") or []
    mapped = figs.get("mapped") or []
    if not wins and not arcs and not mapped:
        return None
    t0 = t0_gps_s(r)
    tracked = [(a["sat"], a["t0"], a["t1"]) for a in arcs]
    used = [(m["sats"], m["t_gps_s"][0], m["t_gps_s"][-1]) for m in mapped if len(m["t_gps_s"])]
    excl = [e for e in r.get("screening", {}).get("excluded", []) if "sat" in e]
    screened = [(e["sat"], e["start_gps_s"], e["stop_gps_s"]) for e in excl]
    windows = [(x["sats"], x["t_start_gps_s"], x["t_stop_gps_s"]) for x in wins]
    never = [(str(u[1]), u[2], u[3]) for u in w.get("never_stationary", [])]
    names = {s for group in (tracked, used, screened, windows, never) for s, _, _ in group}
    lanes = sorted(names, key=_lane_key)
    lane = {s: k for k, s in enumerate(lanes)}
    pair = r.get("method") == "DA"
    fig = new_figure(1.25 + LANE_IN * len(lanes))
    ax = fig.add_subplot()
    layers = [
        (tracked, 0.42, "0.85", "tracked arc"),
        *_screened_layers(excl, r.get("screening", {}).get("false_alarm_per_block")),
        (windows, 0.32, _GREENS[0], "stationary window"),
        (never, 0.32, "#d62728", "never stationary"),
    ]
    handles = []
    for items, half, colour, label in layers:
        verts, _ = _spans(items, lane, t0, half)
        if not len(verts):
            continue
        colours: Any = colour
        if items is windows:
            # alternate shades per lane so that adjacent windows stay distinguishable
            shade = np.zeros(len(items), dtype=int)
            seen: dict[str, int] = {}
            for k in np.argsort([x[1] for x in items], kind="stable"):
                shade[k] = seen.get(items[k][0], 0)
                seen[items[k][0]] = 1 - shade[k]
            colours = np.array(_GREENS)[shade]
        ax.add_collection(PolyCollection(verts, facecolors=colours, linewidths=0))
        handles.append(Patch(facecolor=colour, label=label))
    span_h = (r["data_span"]["stop_gps_s"] - t0) / 3600.0
    ax.set_xlim(min(0.0, (r["data_span"]["start_gps_s"] - t0) / 3600.0), span_h)
    ax.set_ylim(len(lanes) - 0.5, -0.5)
    size = float(np.clip(520.0 / max(len(lanes), 1), 4.5, 8.0))
    ax.set_yticks(range(len(lanes)), lanes)
    ax.tick_params(axis="y", length=0, labelsize=size)
    ax.set_ylabel("satellite pair [PRN-PRN]" if pair else "satellite [PRN]")
    ax.set_xlabel("time since data start [h]")
    ax.grid(axis="x", alpha=0.3)
    ax.set_axisbelow(True)
    ax.set_title(
        f"{r['data_span']['n_arcs']} arcs after screening, {w['count']} stationary windows; "
        f"screened out {r.get('screening', {}).get('excluded_s', 0.0) / 3600:.2f} h, never "
        f"stationary {w['never_stationary_s'] / 60:.1f} min",
        fontsize=9,
    )
    legend = fig.legend(
        handles=handles,
        fontsize=7,
        ncol=len(handles),
        loc="upper center",
        frameon=False,
        handlelength=1.2,
        columnspacing=1.0,
    )
    return finish(fig, above=[legend])


def _screened_layers(
    excl: list[dict[str, Any]], false_alarm: float | None
) -> list[tuple[list, float, str, str]]:
    """One layer of screened-out spans per reason, labelled with its count."""
    out = []
    for kind in sorted({e.get("kind", "") for e in excl}):
        items = [
            (e["sat"], e["start_gps_s"], e["stop_gps_s"]) for e in excl if e.get("kind", "") == kind
        ]
        label = f"{kind or 'screened out'} ({len(items)})"
        if kind == "ionosphere" and false_alarm:
            label = f"ionosphere ({len(items)}; p = {false_alarm:g} per block)"
        out.append((items, 0.42, _SCREENED.get(kind, "0.45"), label))
    return out


def fig_df_filter(r: dict[str, Any]) -> Figure | None:
    """Dual-frequency difference before and after the high-pass filter (one arc)."""
    d = r["figures"].get("df_filter")
    if not d:
        return None
    t = (np.asarray(d["t_gps_s"]) - d["t_gps_s"][0]) / 60.0
    fig = new_figure(4.2)
    a1, a2 = fig.subplots(2, 1, sharex=True)
    a1.plot(t, 100 * np.asarray(d["unfiltered_m"]), lw=0.8)
    a1.set_ylabel("L1-L2, mean removed [cm]")
    source = str(r["cutoff"]["source"]).split(" (")[0]
    a1.set_title(
        f"{d['sat']}: before and after the high-pass at f_c = {r['cutoff']['f_c_hz']:.3g} Hz "
        f"({source})",
        fontsize=9,
    )
    a2.plot(t, 1000 * np.asarray(d["filtered_m"]), lw=0.6, color="C1")
    a2.set_ylabel("filtered [mm]")
    a2.set_xlabel("time since arc start [min]")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    return finish(fig)


def fig_mapped(r: dict[str, Any]) -> Figure | None:
    """Elevation-mapped residuals of every arc against time (hours from the data start)."""
    mapped = r["figures"].get("mapped") or []
    if not mapped:
        return None
    t0 = t0_gps_s(r)
    fig = new_figure(3.3)
    ax = fig.add_subplot()
    for m in mapped:
        ax.plot((np.asarray(m["t_gps_s"]) - t0) / 3600, 1000 * np.asarray(m["mapped_m"]), lw=0.4)
    ax.set_ylabel("mapped multipath [mm]")
    ax.set_xlabel("time since data start [h]")
    mp = r["mapping"]
    ax.set_title(
        f"{r['data_span']['n_arcs']} arcs after screening; mapping {mp['source']}: "
        f"a={mp['a']:.3g}, b={mp['b']:.3g}, c={mp['c_deg']:.3g} deg",
        fontsize=9,
    )
    ax.grid(alpha=0.3)
    return finish(fig)


#: Outline colour and legend text of an excluded span by the test that flagged it
#: (``screening.excluded[].test``; "ionosphere": a document from before the field existed).
_TESTS = {
    "block": ("#d62728", "one block's ROTI above its threshold"),
    "persistence": ("#ff7f0e", "15 min improbable (persistence)"),
    "coherence": ("#e377c2", "several satellites in one 5 min (coherence)"),
    "three-frequency": ("#17becf", "three carriers"),
    "ionosphere": ("#d62728", "ionosphere"),
    "limit": ("#9467bd", "beyond the carrier-multipath limit"),
    "length": ("0.3", "short remainder"),
}
_KIND_TEST = {"implausible": "limit", "short remainder": "length"}


def _arr(x: Any) -> np.ndarray:
    """Return a JSON list as a float array (None -> NaN)."""
    return np.asarray([np.nan if v is None else v for v in x], dtype=float)


def _block_ratios(d: dict[str, Any]) -> tuple[list[tuple[str, float, float]], np.ndarray, bool]:
    """Every block as (lane, start, stop), its statistic over its threshold, and which one.

    The statistic is ROTI over its threshold where the series has ROTI (DF),
    else the block's largest absolute value over the carrier-multipath limit.
    """
    items, ratio = [], []
    has_roti = any(np.isfinite(_arr(a["roti_tecu_min"])).any() for a in d["roti"])
    half = 0.5 * ROTI_BLOCK_S
    for a in d["roti"]:
        mid = _arr(a["t_gps_s"])
        items += [(a["sats"], m - half, m + half) for m in mid]
        if has_roti:
            ratio.append(_arr(a["roti_tecu_min"]) / _arr(a["threshold_tecu_min"]))
        else:
            ratio.append(_arr(a.get("value_max_m", [np.nan] * mid.size)) / d["limit_m"])
    return items, np.concatenate(ratio) if ratio else np.zeros(0), has_roti


def _excluded_by_test(excl: list[dict[str, Any]]) -> dict[str, list[tuple[str, float, float]]]:
    """Group the excluded spans (lane, start, stop) by the test that flagged them."""
    out: dict[str, list[tuple[str, float, float]]] = {}
    for e in excl:
        test = e.get("test") or _KIND_TEST.get(e.get("kind", ""), "ionosphere")
        out.setdefault(test, []).append((e["sat"], e["start_gps_s"], e["stop_gps_s"]))
    return out


def _test_label(test: str, n: int, spans: list[dict[str, Any]]) -> str:
    """Legend text of one test: what it is, its span count and false-alarm probability."""
    text = _TESTS.get(test, ("", test))[1]
    p = [e.get("false_alarm") for e in spans if e.get("false_alarm") is not None]
    return f"{text} ({n}" + (f"; p = {max(p):.2g})" if p else ")")


def _lanes_axis(ax: Any, r: dict[str, Any], d: dict[str, Any]) -> Any:
    """Draw the blocks (coloured by statistic / threshold) and the cut spans (by test) in lanes.

    Returns the blocks (for the colour bar), the colour bar's label and the legend handles
    of the tests that flagged the cut spans.
    """
    t0 = t0_gps_s(r)
    excl = [e for e in r.get("screening", {}).get("excluded", []) if "sat" in e]
    items, ratio, has_roti = _block_ratios(d)
    by_test = _excluded_by_test(excl)
    lanes = sorted({s for s, _, _ in items} | {e["sat"] for e in excl}, key=_lane_key)
    lane = {s: k for k, s in enumerate(lanes)}
    verts, _ = _spans(items, lane, t0, 0.3)
    norm = LogNorm(0.1, 10.0)
    blocks = PolyCollection(verts, cmap="coolwarm", norm=norm, linewidths=0)
    blocks.set_array(np.clip(np.where(np.isfinite(ratio), ratio, 1e-3), 0.1, 10.0))
    ax.add_collection(blocks)
    handles = []
    for test, spans in by_test.items():
        colour = _TESTS.get(test, ("0.3", test))[0]
        v, _ = _spans(spans, lane, t0, 0.45)
        ax.add_collection(PolyCollection(v, facecolors="none", edgecolors=colour, linewidths=1.0))
        rows = [e for e in excl if (e.get("test") or "") == test]
        text = _test_label(test, len(spans), rows)
        handles.append(Patch(facecolor="none", edgecolor=colour, label=text))
    ax.set_ylim(len(lanes) - 0.5, -0.5)
    size = float(np.clip(520.0 / max(len(lanes), 1), 4.5, 8.0))
    ax.set_yticks(range(len(lanes)), lanes, fontsize=size)
    ax.tick_params(axis="y", length=0)
    ax.set_ylabel("satellite pair [PRN-PRN]" if r.get("method") == "DA" else "satellite [PRN]")
    ax.grid(alpha=0.3, axis="x")
    label = "ROTI / threshold [-]" if has_roti else "largest |value| / limit [-]"
    return blocks, label, handles


def fig_screening(r: dict[str, Any]) -> Figure | None:
    """Screening per satellite: each block's statistic against its threshold, what was cut and why.

    Top: one lane per satellite (pair for dual-antenna), every 5-min block
    coloured by its ROTI over its threshold (blue below, red above; for a
    series without ROTI, the largest absolute value over the carrier-multipath
    limit); the excluded spans outlined in the colour of the test that flagged
    them, the legend giving each test's span count and false-alarm
    probability (``screening.excluded[].test`` and ``false_alarm``). Blocks
    cut below their own threshold were flagged by a test that pools blocks
    (15 min of one satellite, or several satellites in one slot) or lie in a
    span's guard. Bottom: the largest absolute isolated value of each block
    against the carrier-multipath limit. Time in hours from the data start.
    """
    d = r["figures"].get("screening")
    if not d or not d.get("roti"):
        return None
    n_lanes = len({a["sats"] for a in d["roti"]})
    fig = new_figure(2.6 + LANE_IN * n_lanes)
    ax, ax_v = fig.subplots(
        2, 1, sharex=True, height_ratios=[LANE_IN * n_lanes + 0.9, 1.4], squeeze=True
    )
    blocks, label, handles = _lanes_axis(ax, r, d)
    _limit_axis(ax_v, r, d)
    t0 = t0_gps_s(r)
    ax.set_xlim(
        min(0.0, (r["data_span"]["start_gps_s"] - t0) / 3600.0),
        (r["data_span"]["stop_gps_s"] - t0) / 3600.0,
    )
    scr = r.get("screening", {})
    heading = fig.suptitle(
        f"Screening per satellite and 5-min block: {len(scr.get('excluded', []))} excluded "
        f"spans ({scr.get('excluded_s', 0.0) / 3600:.2f} h)\nthreshold {_threshold_words(r, d)}",
        fontsize=8,
    )
    finish(fig, above=[heading, *_tests_legend(fig, heading, handles)])
    _colour_bar_right(fig, (ax, ax_v), blocks, label)
    return fig


def _tests_legend(fig: Figure, heading: Any, handles: list[Any]) -> list[Any]:
    """Put the legend of the flagging tests under the heading (none without excluded spans)."""
    if not handles:
        return []
    top = heading.get_window_extent(renderer_of(fig)).y0 / (fig.get_figheight() * fig.dpi)
    return [
        fig.legend(
            handles=handles,
            fontsize=6.5,
            loc="upper center",
            bbox_to_anchor=(0.5, top),
            ncol=min(len(handles), 3),
            frameon=False,
            title="excluded spans by the test that flagged them (count; false-alarm probability)",
            title_fontsize=7,
        )
    ]


#: Room the lanes' colour bar takes at the right of the axes (gap, bar, ticks and label), in.
_BAR_GAP_IN, _BAR_W_IN, _BAR_ROOM_IN = 0.1, 0.12, 0.95


def _colour_bar_right(fig: Figure, axes: tuple[Any, Any], mappable: Any, label: str) -> None:
    """Narrow the laid-out axes by the colour bar's room and put the bar beside the top one.

    The grid is placed first (:func:`finish`: a colour bar made with ``ax=`` would give
    the top axes a grid of its own and the placement would miss the bottom one).
    """
    w = fig.get_size_inches()[0]
    for a in axes:
        x0, y0, aw, ah = a.get_position().bounds
        a.set_position((x0, y0, aw - _BAR_ROOM_IN / w, ah))
    x0, y0, aw, ah = axes[0].get_position().bounds
    cax = fig.add_axes((x0 + aw + _BAR_GAP_IN / w, y0, _BAR_W_IN / w, ah))
    fig.colorbar(mappable, cax=cax, label=label, extend="both")


def _threshold_words(r: dict[str, Any], d: dict[str, Any]) -> str:
    """Say what the block threshold is, in a few words, for the title."""
    scr = r.get("screening", {})
    null = scr.get("multipath_null")
    base = d.get("threshold_tecu_min")
    if null and null.get("trusted", True):
        p = (scr.get("block_test") or {}).get("false_alarm", scr.get("false_alarm_per_block"))
        return f"max({base:g} TECU/min, multipath null at p = {p:.2g} per block)"
    if null:
        return f"the multipath null (disturbed) capped by {base:g} TECU/min x m(el)"
    return f"{base:g} TECU/min x m(el)"


def _limit_axis(ax: Any, r: dict[str, Any], d: dict[str, Any]) -> None:
    """Draw the largest absolute isolated value per block against the carrier-multipath limit."""
    t0 = t0_gps_s(r)
    t = (np.concatenate([_arr(a["t_gps_s"]) for a in d["roti"]]) - t0) / 3600.0
    vmax = np.concatenate([_arr(a.get("value_max_m", [])) for a in d["roti"]])
    exc = np.concatenate([np.asarray(a.get("excluded", []), dtype=bool) for a in d["roti"]])
    if vmax.size == t.size and exc.size == t.size:
        ax.semilogy(t[~exc], 100 * vmax[~exc], ".", ms=2, color="tab:blue", label="kept")
        ax.semilogy(t[exc], 100 * vmax[exc], ".", ms=2, color="tab:orange", label="excluded")
    ax.axhline(
        100 * d["limit_m"],
        color="tab:red",
        lw=1,
        label=f"carrier-multipath limit {100 * d['limit_m']:.2f} cm",
    )
    ax.set_ylabel("largest |value| [cm]")
    ax.set_xlabel("time since data start [h]")
    ax.legend(fontsize=6.5, loc="lower right", ncol=3)
    ax.grid(alpha=0.3, which="both")
