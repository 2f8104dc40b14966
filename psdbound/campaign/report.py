"""Campaign outputs: ``campaign.json``, ``campaign.html``, ``network.html``, ``campaign.pdf``.

Beside them, ``days/`` holds each fitted station-day's report (the HTML
report ``fit`` writes, drawn from the day's result document), which the
network page (:mod:`psdbound.campaign.network`) links to.
"""

from __future__ import annotations

import base64
import html
import io
import os
from pathlib import Path
from typing import Any

from psdbound.campaign.network import NETWORK_PAGE, day_report_name, network_page
from psdbound.campaign.run import CampaignResult
from psdbound.errors import InputError
from psdbound.results import json_text
from psdbound.results.headline import check_line

__all__ = ["CAMPAIGN_FILES", "station_lines", "write_campaign"]

CAMPAIGN_FILES = ("campaign.json", "campaign.html", NETWORK_PAGE, "campaign.pdf")
#: Folder of the station-day reports in a campaign folder.
DAYS_FOLDER = "days"


def _figure(doc: dict[str, Any]) -> Any:
    """Return the held-out figure, or None when no day was held out (nothing to draw)."""
    rows = doc["held_out"]
    if not rows:
        return None
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    labels = [f"{r['station']}\n{r['day']}" for r in rows]
    x = range(len(rows))
    axes[0].bar(x, [100 * r["windows_covered_fraction"] for r in rows], color="C0")
    axes[0].axhline(95, color="k", ls=":", lw=1, label="95 % (one-sided 5 % test)")
    axes[0].set_ylabel("windows not above the held-out bound [%]")
    axes[1].bar(x, [r["kf_max_generalized_eigenvalue"] for r in rows], color="C1")
    axes[1].axhline(1.0, color="C3", ls="--", lw=1, label="1: covariance bounded")
    axes[1].set_ylabel("KF max generalised eigenvalue (true / designed)")
    for ax in axes:
        ax.set_xticks(list(x), labels, fontsize=7)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle("each station-day against the bound of the station's other days")
    fig.tight_layout()
    return fig


def _mm(row: dict[str, Any]) -> str:
    """``sigma_GM / tau / sigma_WN`` of a bound row in mm and s."""
    return (
        f"{1e3 * row['sigma_gm_m']:.2f} mm / {row['tau_s']:.1f} s / "
        f"{1e3 * row['sigma_wn_m']:.2f} mm"
    )


def station_lines(st: dict[str, Any]) -> list[str]:
    """Return the text of one station: verdict, pooled bound, excluded days, what is missing.

    Parameters
    ----------
    st : dict
        A ``stations`` row of ``campaign.json``.

    Returns
    -------
    list of str
        Lines without markup (the HTML escapes them, the PDF prints them).
    """
    lines = [f"{st['station']}: {st['verdict']}"]
    if st["n_pooled"]:
        lines.append(
            f"pooled bound over {st['n_pooled']} of {st['n_days']} day(s) "
            f"({', '.join(st['pooled_days'])}): sigma_GM / tau / sigma_WN "
            f"{_mm(st)}"
        )
    lines += [f"reason: {r}" for r in st["verdict_reasons"]]
    for d in st["excluded_days"]:
        lines.append(f"not pooled: {d['day']} ({d['verdict']}): " + "; ".join(d["reasons"]))
    if st.get("comparison_note"):
        lines.append(st["comparison_note"])
    lines.append("rules applied to the pooled bound:")
    lines += [f"  {check_line(c)}" for c in st["verdict_checks"]]
    return lines


def _station_html(doc: dict[str, Any]) -> str:
    items = []
    for st in doc["stations"]:
        head, *rest = station_lines(st)
        items.append(
            f"<li><b>{html.escape(head)}</b><ul>"
            + "".join(f"<li>{html.escape(x)}</li>" for x in rest)
            + "</ul></li>"
        )
    return f"<h2>Stations: pooled bounds and verdicts</h2><ul>{''.join(items)}</ul>"


def _own(d: dict[str, Any]) -> str:
    return f"{_mm(d)}, {d['n_windows']} windows" if d["fitted"] else "none"


def _days_html(doc: dict[str, Any]) -> str:
    rows = "".join(
        f"<tr><td>{html.escape(d['station'])}</td><td>{d['day']}</td>"
        f"<td>{html.escape(d['verdict'])}</td><td>{'yes' if d['in_pool'] else 'no'}</td>"
        f"<td>{_own(d)}</td>"
        f"<td>{html.escape(d['nav'])}</td>"
        f"<td>{'<br>'.join(html.escape(r) for r in d['verdict_reasons'])}</td></tr>"
        for d in doc["days"]
    )
    return (
        "<h2>Station-days: the verdict of <code>psdbound fit</code> for each day</h2>"
        "<table><tr><th>station</th><th>day</th><th>verdict</th><th>in pool</th>"
        "<th>own bound sigma_GM / tau / sigma_WN</th><th>navigation file</th>"
        f"<th>reasons</th></tr>{rows}</table>"
    )


def _held_out_html(doc: dict[str, Any], img: str | None) -> str:
    notes = "".join(
        f"<li>{html.escape(st['station'])}: {html.escape(st['comparison_note'])}</li>"
        for st in doc["stations"]
        if st.get("comparison_note")
    )
    out = "<h2>Held-out days</h2>" + (f"<ul>{notes}</ul>" if notes else "")
    if not doc["held_out"]:
        return out
    head = (
        "<tr><th>station</th><th>day</th><th>other days</th><th>held-out bound "
        "sigma_GM / tau / sigma_WN</th><th>windows covered</th><th>worst excess</th>"
        "<th>KF max gen. eigenvalue (windows bounded)</th></tr>"
    )
    body = "".join(
        f"<tr><td>{html.escape(r['station'])}</td><td>{r['day']}</td><td>{r['n_other_days']}</td>"
        f"<td>{_mm(r['bound'])}</td><td>{100 * r['windows_covered_fraction']:.0f} %</td>"
        f"<td>{r['worst_excess_db']:.1f} dB</td><td>{r['kf_max_generalized_eigenvalue']:.2f} "
        f"({100 * r.get('kf_windows_bounded_fraction', float('nan')):.0f} %)</td></tr>"
        for r in doc["held_out"]
    )
    return (
        out + f"<img alt='held-out coverage and KF eigenvalues' "
        f"src='data:image/png;base64,{img}'><table>{head}{body}</table>"
        "<p>Held out: each pooled station-day's windows tested against the pooled bound of "
        "the station's other pooled days (covered: not significantly above it, one-sided "
        "5 %); KF: a 6-satellite static filter designed with that bound against each of the "
        "day's windows as the truth.</p>"
    )


def _page(doc: dict[str, Any], summary: str, img: str | None) -> str:
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>psdbound campaign"
        "</title><style>body{font-family:sans-serif;max-width:1000px;margin:2em auto}"
        "td,th{border:1px solid #ccc;padding:3px 6px;font-size:0.9em;vertical-align:top}"
        "table{border-collapse:collapse}</style></head><body><h1>psdbound campaign: "
        f"{html.escape(doc['verdict'])}</h1><p><a href='{NETWORK_PAGE}'>network page</a>: "
        "every station on a map and in one sortable table, with its reports</p>"
        f"{_station_html(doc)}{_held_out_html(doc, img)}{_days_html(doc)}"
        f"<h2>Summary</h2><pre>{html.escape(summary)}</pre></body></html>"
    )


def _text_pages(doc: dict[str, Any]) -> list[Any]:
    """Return the PDF's text pages: the verdict, every station and every day, wrapped."""
    import textwrap

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = [f"psdbound campaign: {doc['verdict']}", ""]
    for st in doc["stations"]:
        lines += [*station_lines(st), ""]
    lines.append("station-days (verdict of psdbound fit for each day):")
    for d in doc["days"]:
        lines.append(
            f"{d['station']} {d['day']}: {d['verdict']}"
            f"{'' if d['in_pool'] else ' (not pooled)'}; navigation {d['nav']}"
        )
        lines += [f"  reason: {r}" for r in d["verdict_reasons"]]
    wrapped = [
        w for line in lines for w in (textwrap.wrap(line, 110, subsequent_indent="    ") or [""])
    ]
    pages = []
    for start in range(0, len(wrapped), _LINES_PER_PAGE):
        fig = plt.figure(figsize=(8.27, 11.69))
        fig.text(
            0.05,
            0.97,
            "\n".join(wrapped[start : start + _LINES_PER_PAGE]),
            va="top",
            family="monospace",
            fontsize=7,
        )
        pages.append(fig)
    return pages


_LINES_PER_PAGE = 95


def write_campaign(
    result: CampaignResult, out_dir: str | os.PathLike[str], *, pdf: bool = True
) -> dict[str, Path]:
    """Write the campaign's JSON, HTML pages, station-day reports and PDF atomically.

    Parameters
    ----------
    result : CampaignResult
    out_dir : path
        Destination folder: new, empty, or an earlier campaign folder (replaced).
    pdf : bool, default True

    Returns
    -------
    dict of str to Path
        ``json``, ``html``, ``network`` and (with ``pdf``) ``pdf``.

    Raises
    ------
    InputError
        ``out_dir`` holds files that are not a campaign's.
    """
    from matplotlib.backends.backend_pdf import PdfPages

    from psdbound.common import atomic_folder
    from psdbound.results import to_jsonable

    out = Path(out_dir)
    if out.exists():
        entries = set(os.listdir(out)) if out.is_dir() else {"?"}
        ours = {*CAMPAIGN_FILES, DAYS_FOLDER}
        if entries and not (entries <= ours and "campaign.json" in entries):
            raise InputError(
                "output folder holds files that are not a campaign's; choose a new or empty folder",
                path=out,
            )
    doc = to_jsonable(result.to_dict())
    fig = _figure(doc)
    img = None
    if fig is not None:
        buf = io.BytesIO()
        fig.savefig(buf, format="png", dpi=110)
        img = base64.b64encode(buf.getvalue()).decode()
    pages = [*_text_pages(doc), *([fig] if fig is not None else [])] if pdf else []
    reports = {
        (d["station"], d["day"]): day_report_name(d["station"], d["day"])
        for d, document in zip(doc["days"], result.documents, strict=False)
        if document is not None
    }
    with atomic_folder(out, replace=True) as tmp:
        (tmp / "campaign.json").write_text(json_text(doc))
        (tmp / "campaign.html").write_text(_page(doc, result.summary(), img))
        _write_day_reports(tmp, doc, result.documents)
        (tmp / NETWORK_PAGE).write_text(network_page(doc, reports))
        if pdf:
            with PdfPages(tmp / "campaign.pdf") as pp:
                for page in pages:
                    pp.savefig(page)
    import matplotlib.pyplot as plt

    for f in [*pages, fig]:
        if f is not None:
            plt.close(f)
    names = [n for n in CAMPAIGN_FILES if pdf or n != "campaign.pdf"]
    return {n.split(".")[0] if n == NETWORK_PAGE else n.split(".")[1]: out / n for n in names}


def _write_day_reports(
    folder: Path, doc: dict[str, Any], documents: list[dict[str, Any] | None]
) -> None:
    """Write each fitted station-day's HTML report into ``folder/days``."""
    from psdbound.reports import render_html

    for d, document in zip(doc["days"], documents, strict=False):
        if document is None:
            continue
        path = folder / day_report_name(d["station"], d["day"])
        path.parent.mkdir(exist_ok=True)
        path.write_text(render_html(document))
