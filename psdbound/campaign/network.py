"""The campaign's network page: every station on one page, where it is and how it is bounded.

``network.html`` holds a station map (longitude/latitude from each
station's RINEX header, APPROX POSITION XYZ; a plain scatter with labels, no
map tiles, nothing fetched), a table of the stations that sorts by any
column when its heading is clicked (a few lines of JavaScript in the page),
with the pooled bound (sigma_GM, tau, sigma_WN), the verdict, the held-out
coverage, the days and a link to each station-day's report
(``days/<station>_<day>.html``), and each station's bound over its days.
Everything is in the one file (images as data URIs) except the station-day
reports it links to.
"""

from __future__ import annotations

import base64
import html
import io
import math
from typing import Any

__all__ = ["NETWORK_PAGE", "day_report_name", "network_page", "station_positions"]

#: File name of the network page in a campaign folder.
NETWORK_PAGE = "network.html"


def day_report_name(station: str, day: str) -> str:
    """Return the path of a station-day's report relative to the campaign folder."""
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in f"{station}_{day}")
    return f"days/{safe}.html"


def station_positions(doc: dict[str, Any]) -> dict[str, tuple[float, float]]:
    """Return each station's (latitude, longitude), deg, from its days' headers.

    Parameters
    ----------
    doc : dict
        ``campaign.json`` content.

    Returns
    -------
    dict of str to (float, float)
        Stations whose header gave a position (the first day that has one).
    """
    out: dict[str, tuple[float, float]] = {}
    for d in doc["days"]:
        lat, lon = d.get("lat_deg"), d.get("lon_deg")
        if d["station"] not in out and lat is not None and lon is not None:
            out[d["station"]] = (float(lat), float(lon))
    return out


def _png(fig: Any) -> str:
    """Return a figure as base64 PNG text (and close it)."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return base64.b64encode(buf.getvalue()).decode()


def _map_figure(positions: dict[str, tuple[float, float]]) -> Any:
    """Return the station map: a longitude/latitude scatter with the station names."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    lats = [p[0] for p in positions.values()]
    lons = [p[1] for p in positions.values()]
    ax.scatter(lons, lats, s=40, color="C0", zorder=3)
    for name, (lat, lon) in positions.items():
        ax.annotate(name, (lon, lat), xytext=(5, 5), textcoords="offset points", fontsize=9)
    pad = max(1.0, 0.15 * max(max(lons) - min(lons), max(lats) - min(lats)))
    ax.set_xlim(max(min(lons) - pad, -180.0), min(max(lons) + pad, 180.0))
    ax.set_ylim(max(min(lats) - pad, -90.0), min(max(lats) + pad, 90.0))
    ax.set_aspect(1.0 / max(math.cos(math.radians(sum(lats) / len(lats))), 0.1))
    ax.set_xlabel("longitude [deg]")
    ax.set_ylabel("latitude [deg]")
    ax.set_title("stations (APPROX POSITION XYZ of the RINEX headers, WGS84)")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def _time_figure(doc: dict[str, Any]) -> Any:
    """Return each station's own day bounds over the days, its pooled bound dashed."""
    import datetime as dt

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.dates as mdates
    import matplotlib.pyplot as plt

    panels = (
        ("sigma_gm_m", 1e3, "sigma_GM [mm]"),
        ("tau_s", 1.0, "tau [s]"),
        ("sigma_wn_m", 1e3, "sigma_WN [mm]"),
    )
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.6))
    pooled = {s["station"]: s for s in doc["stations"]}
    dates = [dt.date.fromisoformat(d["day"]) for d in doc["days"]] or [dt.date(2000, 1, 1)]
    first, last = min(dates), max(dates)
    step = max(1, math.ceil(((last - first).days + 1) / 10))  # at most about 10 labels
    for k, station in enumerate(dict.fromkeys(d["station"] for d in doc["days"])):
        days = [d for d in doc["days"] if d["station"] == station and d.get("fitted")]
        x = [dt.date.fromisoformat(d["day"]) for d in days]
        for ax, (key, scale, label) in zip(axes, panels, strict=True):
            ax.plot(x, [scale * d[key] for d in days], "o-", color=f"C{k % 10}", label=station)
            st = pooled.get(station, {})
            if st.get("n_pooled") and st.get(key) is not None:
                ax.axhline(scale * st[key], color=f"C{k % 10}", ls="--", lw=1)
            ax.set_ylabel(label)
    for ax in axes:
        # the days' own span, half a day either side: one day alone would otherwise be
        # widened by matplotlib to years, with a tick per day (thousands of them)
        ax.set_xlim(
            dt.datetime.combine(first, dt.time()) - dt.timedelta(hours=12),
            dt.datetime.combine(last, dt.time()) + dt.timedelta(hours=12),
        )
        ax.xaxis.set_major_locator(mdates.DayLocator(interval=step))
        ax.xaxis.set_major_formatter(mdates.DateFormatter("%Y-%m-%d"))
        ax.set_xlabel("day")
        ax.tick_params(axis="x", labelrotation=30, labelsize=8)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle("each day's own bound (points) and the station's pooled bound (dashed)")
    fig.tight_layout()
    return fig


def _cell(text: str, sort: str | float | None = None) -> str:
    key = "" if sort is None else f" data-sort='{html.escape(str(sort), quote=True)}'"
    return f"<td{key}>{text}</td>"


def _link(href: str, text: str) -> str:
    return (
        f"<a style='white-space:nowrap' href='{html.escape(href, quote=True)}'>"
        f"{html.escape(text)}</a>"
    )


def _row(
    st: dict[str, Any],
    doc: dict[str, Any],
    pos: tuple[float, float] | None,
    reports: dict[tuple[str, str], str],
) -> str:
    """One station's table row: position, verdict, pooled bound, held-out coverage, days."""
    name = st["station"]
    held = [r["windows_covered_fraction"] for r in doc["held_out"] if r["station"] == name]
    days = [d for d in doc["days"] if d["station"] == name]
    links = " ".join(
        _link(reports[(name, d["day"])], d["day"])
        if (name, d["day"]) in reports
        else f"{d['day']} (no report)"
        for d in days
    )
    bound = st.get("n_pooled") and st.get("sigma_gm_m") is not None

    def num(key: str, scale: float, fmt: str) -> str:
        return _cell(format(scale * st[key], fmt), scale * st[key]) if bound else _cell("-", -1)

    return (
        "<tr>"
        + "".join(
            [
                _cell(html.escape(name), name),
                _cell("-" if pos is None else f"{pos[0]:.4f}", "" if pos is None else pos[0]),
                _cell("-" if pos is None else f"{pos[1]:.4f}", "" if pos is None else pos[1]),
                _cell(html.escape(st["verdict"]), st["verdict"]),
                num("sigma_gm_m", 1e3, ".2f"),
                num("tau_s", 1.0, ".1f"),
                num("sigma_wn_m", 1e3, ".2f"),
                _cell(
                    f"{100 * min(held):.0f} % (worst of {len(held)})" if held else "-",
                    min(held) if held else -1,
                ),
                _cell(f"{st['n_pooled']} of {st['n_days']}", st["n_days"]),
                _cell(links),
            ]
        )
        + "</tr>"
    )


#: Clicking a heading sorts the table by it (numbers by their value), again: reversed.
_SORT_JS = """
document.querySelectorAll('table.sortable th').forEach(function (th, col) {
  th.addEventListener('click', function () {
    var body = th.closest('table').tBodies[0];
    var rows = Array.prototype.slice.call(body.rows);
    var up = th.getAttribute('aria-sort') !== 'ascending';
    th.closest('tr').querySelectorAll('th').forEach(function (h) {
      h.removeAttribute('aria-sort');
    });
    th.setAttribute('aria-sort', up ? 'ascending' : 'descending');
    function key(r) {
      var c = r.cells[col], v = c.getAttribute('data-sort');
      if (v === null) { v = c.textContent; }
      var n = parseFloat(v);
      return isNaN(n) || String(n) !== String(parseFloat(v)) ? v.toLowerCase() : n;
    }
    rows.sort(function (a, b) {
      var x = key(a), y = key(b);
      if (typeof x !== typeof y) { x = String(x); y = String(y); }
      return (x < y ? -1 : x > y ? 1 : 0) * (up ? 1 : -1);
    });
    rows.forEach(function (r) { body.appendChild(r); });
  });
});
"""

_HEAD = (
    "station",
    "latitude [deg]",
    "longitude [deg]",
    "verdict",
    "sigma_GM [mm]",
    "tau [s]",
    "sigma_WN [mm]",
    "held-out windows covered",
    "days pooled",
    "station-day reports",
)


def network_page(doc: dict[str, Any], reports: dict[tuple[str, str], str]) -> str:
    """Return the network page's HTML.

    Parameters
    ----------
    doc : dict
        ``campaign.json`` content (stations, days with header positions, held-out rows).
    reports : dict of (str, str) to str
        ``(station, day)`` -> the station-day report's path relative to the page.

    Returns
    -------
    str
        A self-contained page (images embedded; links only to ``reports``
        and ``campaign.html``).
    """
    positions = station_positions(doc)
    rows = "".join(_row(st, doc, positions.get(st["station"]), reports) for st in doc["stations"])
    head = "".join(f"<th title='click to sort'>{h}</th>" for h in _HEAD)
    map_img = (
        f"<img id='station-map' alt='station map' src='data:image/png;base64,"
        f"{_png(_map_figure(positions))}'>"
        if positions
        else "<p>No station header gives a position (APPROX POSITION XYZ).</p>"
    )
    time_img = (
        "<img id='bound-over-time' alt='bound over time' src='data:image/png;base64,"
        f"{_png(_time_figure(doc))}'>"
        if any(d.get("fitted") for d in doc["days"])
        else "<p>No day was fitted.</p>"
    )
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>psdbound network"
        "</title><style>body{font-family:sans-serif;max-width:1100px;margin:2em auto}"
        "td,th{border:1px solid #ccc;padding:3px 6px;font-size:0.9em;vertical-align:top}"
        "th{cursor:pointer;background:#f3f3f3}th[aria-sort=ascending]::after{content:' \\25B2'}"
        "th[aria-sort=descending]::after{content:' \\25BC'}table{border-collapse:collapse}"
        "img{max-width:100%}</style></head><body>"
        f"<h1>psdbound network: {len(doc['stations'])} station(s), campaign verdict "
        f"{html.escape(doc['verdict'])}</h1><p><a href='campaign.html'>campaign report</a> "
        "(every station-day, the held-out tests, the summary)</p>"
        f"<h2>Where the stations are</h2>{map_img}"
        "<h2>Stations</h2><p>Pooled bound of each station's bounded days; held out: the "
        "smallest share of a day's windows not above the bound of the station's other days. "
        "Click a heading to sort.</p>"
        f"<table class='sortable' id='stations'><thead><tr>{head}</tr></thead>"
        f"<tbody>{rows}</tbody></table>"
        f"<h2>Bound over time</h2>{time_img}"
        f"<script>{_SORT_JS}</script></body></html>"
    )
