"""Campaign outputs: ``campaign.json``, ``campaign.html`` (table + figure), ``campaign.pdf``."""

from __future__ import annotations

import base64
import html
import io
import json
import os
from pathlib import Path
from typing import Any

from psdbound.campaign.run import CampaignResult
from psdbound.errors import InputError

__all__ = ["CAMPAIGN_FILES", "write_campaign"]

CAMPAIGN_FILES = ("campaign.json", "campaign.html", "campaign.pdf")


def _figure(doc: dict[str, Any]):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = doc["held_out"]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    if not rows:
        for ax in axes:
            ax.text(0.5, 0.5, "no station with two good days: nothing held out", ha="center")
            ax.set_axis_off()
        return fig
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


def _table(doc: dict[str, Any]) -> str:
    head = ("<tr><th>station</th><th>day</th><th>other days</th><th>held-out bound "
            "sigma_GM / tau / sigma_WN</th><th>windows covered</th><th>worst excess</th>"
            "<th>KF max gen. eigenvalue (windows bounded)</th></tr>")  # fmt: skip
    body = "".join(
        f"<tr><td>{html.escape(r['station'])}</td><td>{r['day']}</td><td>{r['n_other_days']}</td>"
        f"<td>{1e3 * r['bound']['sigma_gm_m']:.2f} mm / {r['bound']['tau_s']:.1f} s / "
        f"{1e3 * r['bound']['sigma_wn_m']:.2f} mm</td>"
        f"<td>{100 * r['windows_covered_fraction']:.0f} %</td>"
        f"<td>{r['worst_excess_db']:.1f} dB</td><td>{r['kf_max_generalized_eigenvalue']:.2f} "
        f"({100 * r.get('kf_windows_bounded_fraction', float('nan')):.0f} %)</td>"
        "</tr>"
        for r in doc["held_out"]
    )
    days = "".join(
        f"<tr><td>{html.escape(d['station'])}</td><td>{d['day']}</td><td>"
        + (f"{1e3 * d['sigma_gm_m']:.2f} mm / {d['tau_s']:.1f} s / {1e3 * d['sigma_wn_m']:.2f} mm"
           f", {d['n_windows']} windows, {100 * d['covered_fraction']:.0f} % covered"
           if d["ok"] else "no bound: " + html.escape(d["error"]))
        + "</td></tr>"
        for d in doc["days"]
    )  # fmt: skip
    return (f"<h2>Held-out days</h2><table>{head}{body}</table>"
            f"<h2>Station-days</h2><table><tr><th>station</th><th>day</th><th>own bound</th>"
            f"</tr>{days}</table>")  # fmt: skip


def write_campaign(
    result: CampaignResult, out_dir: str | os.PathLike[str], *, pdf: bool = True
) -> dict[str, Path]:
    """Write ``campaign.json``, ``campaign.html`` and (optionally) ``campaign.pdf`` atomically.

    Parameters
    ----------
    result : CampaignResult
    out_dir : path
        Destination folder: new, empty, or an earlier campaign folder (replaced).
    pdf : bool, default True

    Returns
    -------
    dict of str to Path

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
        if entries and not (entries <= set(CAMPAIGN_FILES) and "campaign.json" in entries):
            raise InputError(
                "output folder holds files that are not a campaign's; choose a new or empty "
                "folder",
                path=out,
            )
    doc = to_jsonable(result.to_dict())
    fig = _figure(doc)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    img = base64.b64encode(buf.getvalue()).decode()
    page = (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>psdbound campaign"
        "</title><style>body{font-family:sans-serif;max-width:1000px;margin:2em auto}"
        "td,th{border:1px solid #ccc;padding:3px 6px;font-size:0.9em}table{border-collapse:"
        "collapse}</style></head><body><h1>psdbound campaign</h1>"
        f"<pre>{html.escape(result.summary())}</pre>"
        f"<img alt='held-out coverage and KF eigenvalues' src='data:image/png;base64,{img}'>"
        f"{_table(doc)}<p>Held out: each station-day's windows tested against the pooled bound"
        " of the station's other days (covered: not significantly above it, one-sided 5 %);"
        " KF: a 6-satellite static filter designed with that bound against the day's own "
        "pooled bound as truth.</p></body></html>"
    )
    with atomic_folder(out, replace=True) as tmp:
        (tmp / "campaign.json").write_text(json.dumps(doc, indent=1, allow_nan=True))
        (tmp / "campaign.html").write_text(page)
        if pdf:
            with PdfPages(tmp / "campaign.pdf") as pp:
                pp.savefig(fig)
    import matplotlib.pyplot as plt

    plt.close(fig)
    names = [n for n in CAMPAIGN_FILES if pdf or n != "campaign.pdf"]
    return {n.split(".")[1]: out / n for n in names}
