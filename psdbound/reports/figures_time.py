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
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from psdbound.reports.figures_base import HALF_PAGE_H_IN, finish, new_figure, t0_gps_s

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


def fig_screening(r: dict[str, Any]) -> Figure | None:
    """Screening: normalised ROTI and the largest isolated value per 5-min block.

    Top: ROTI over its threshold (1 = the threshold); bottom: the largest
    absolute isolated value of each block against the carrier-multipath
    limit. Excluded blocks are orange, kept blocks blue; time in hours from
    the data start.
    """
    d = r["figures"].get("screening")
    if not d or not d.get("roti"):
        return None

    def arr(x: Any) -> np.ndarray:
        return np.asarray([np.nan if v is None else v for v in x], dtype=float)

    t0 = t0_gps_s(r)
    t = np.concatenate([arr(a["t_gps_s"]) for a in d["roti"]])
    t = (t - t0) / 3600.0
    ratio = np.concatenate(
        [arr(a["roti_tecu_min"]) / arr(a["threshold_tecu_min"]) for a in d["roti"]]
    )
    vmax = np.concatenate([arr(a.get("value_max_m", [])) for a in d["roti"]])
    exc = np.concatenate([np.asarray(a.get("excluded", []), dtype=bool) for a in d["roti"]])
    has_roti = bool(np.any(np.isfinite(ratio)))
    fig = new_figure(HALF_PAGE_H_IN - 0.5 if has_roti else 2.6)
    axes = np.atleast_1d(fig.subplots(2 if has_roti else 1, 1, sharex=True, squeeze=False)[:, 0])
    if has_roti:
        ax = axes[0]
        ax.semilogy(t[~exc], ratio[~exc], ".", ms=2.5, color="tab:blue", label="kept")
        ax.semilogy(t[exc], ratio[exc], ".", ms=2.5, color="tab:orange", label="excluded")
        scr = r.get("screening", {})
        what = (
            f"max({d['threshold_tecu_min']:g} TECU/min, multipath null at p = "
            f"{scr.get('false_alarm_per_block'):g} per block)"
            if scr.get("multipath_null")
            else f"{d['threshold_tecu_min']:g} TECU/min x m(el)"
        )
        ax.axhline(1.0, color="tab:red", lw=1, label=f"threshold {what}")
        ax.set_ylabel("ROTI / threshold [-]")
        ax.legend(fontsize=7, loc="upper right", ncol=3)
        ax.grid(alpha=0.3, which="both")
    ax = axes[-1]
    if vmax.size:
        ax.semilogy(t[~exc], 100 * vmax[~exc], ".", ms=2.5, color="tab:blue")
        ax.semilogy(t[exc], 100 * vmax[exc], ".", ms=2.5, color="tab:orange")
    ax.axhline(
        100 * d["limit_m"],
        color="tab:red",
        lw=1,
        label=f"carrier-multipath limit {100 * d['limit_m']:.2f} cm",
    )
    ax.set_ylabel("largest |isolated value| [cm]")
    ax.set_xlabel("time since data start [h]")
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(alpha=0.3, which="both")
    n_exc = len(r.get("screening", {}).get("excluded", d["excluded"]))
    axes[0].set_title(
        f"Screening per satellite and 5-min block: {n_exc} excluded spans "
        f"({r.get('screening', {}).get('excluded_s', 0.0) / 3600:.2f} h)",
        fontsize=9,
    )
    return finish(fig)
