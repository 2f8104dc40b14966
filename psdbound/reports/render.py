"""HTML and PDF reports from a result document, written atomically."""

from __future__ import annotations

import base64
import io
import os
import textwrap
from pathlib import Path
from typing import Any

import jinja2
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.backends.backend_pdf import PdfPages  # noqa: E402

from psdbound.common.outputs import output_folder  # noqa: E402
from psdbound.reports.figures import FIGURES  # noqa: E402
from psdbound.results import write_document  # noqa: E402

__all__ = ["render_html", "render_pdf", "write_report_folder"]

_METHOD = {
    "DF": "dual-frequency (one antenna, two carriers) multipath",
    "DA": "dual-antenna double-difference multipath",
}


def _figures(r: dict[str, Any]) -> list[tuple[str, Any]]:
    out = []
    for _, caption, func in FIGURES:
        fig = func(r)
        if fig is not None:
            out.append((caption, fig))
    return out


def _validation_note(r: dict[str, Any]) -> str:
    v = r["validation"]
    if v.get("summary"):
        return str(v["summary"])
    return str(v.get("reason", ""))


def _title(r: dict[str, Any]) -> str:
    names = [i["name"] for i in r["provenance"]["inputs"] if i["role"] == "obs"]
    return ", ".join(names) or "result"


def _png(fig: Any) -> str:
    """Base64 PNG of a figure (110 dpi)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    return base64.b64encode(buf.getvalue()).decode()


def render_html(document: dict[str, Any], *, figures: list[tuple[str, Any]] | None = None) -> str:
    """Return the self-contained HTML report (figures inline as PNG) of a result document.

    Parameters
    ----------
    document : dict
        The result document.
    figures : list of (str, Figure), optional
        Captions and figures already drawn (they are left open); by default
        every figure is drawn (and closed) here.

    Returns
    -------
    str
    """
    r = document
    figs = []
    for caption, fig in figures if figures is not None else _figures(r):
        figs.append({"caption": caption, "png": _png(fig)})
        if figures is None:
            plt.close(fig)
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("psdbound.reports", "templates"),
        autoescape=jinja2.select_autoescape(["html", "j2"]),
        undefined=jinja2.StrictUndefined,
    )
    span_h = (r["data_span"]["stop_gps_s"] - r["data_span"]["start_gps_s"]) / 3600.0
    return env.get_template("report.html.j2").render(
        r=r,
        title=_title(r),
        method_long=_METHOD.get(r["method"], r["method"]),
        span_h=span_h,
        figures=figs,
        demo=r.get("demo"),
        validation_note=_validation_note(r),
        coverage=_coverage_text(r["windows"]),
    )


def _coverage_text(w: dict[str, Any]) -> str:
    """Hours and percent of the screened data inside the bound's windows."""
    if w.get("covered_fraction") is None:
        return f"{w['total_duration_s'] / 3600:.2f} h of windows"
    return (f"{w['covered_s'] / 3600:.2f} h of {w['data_s'] / 3600:.2f} h "
            f"({100 * w['covered_fraction']:.1f} %); never stationary "
            f"{w['never_stationary_s'] / 3600:.2f} h")


def _summary_page(r: dict[str, Any]):
    b, s, c, w = r["bound"], r["sampling"], r["cutoff"], r["windows"]
    fc = "n/a" if c["f_c_hz"] is None else f"{c['f_c_hz']:.4g} Hz ({c['tau_c_min']:.1f} min)"
    rows = [
        ("VERDICT", r["verdict"] + "".join(f"; {x}" for x in r["verdict_reasons"])),
        ("screening excluded", f"{r['screening']['excluded_s'] / 3600:.2f} h "
                               f"({100 * r['screening']['excluded_fraction']:.1f} %)"),
        ("sigma_GM", f"{100 * b['sigma_gm_m']:.3f} cm"),
        ("tau_GM", f"{b['tau_s']:.1f} s"),
        ("sigma_WN (per sample)", f"{100 * b['sigma_wn_m']:.3f} cm at {s['interval_s']:g} s"),
        ("N_WN (two-sided)", f"{b['n_wn_two_sided_m2_hz']:.4g} m^2/Hz"),
        ("data covered by the bound", _coverage_text(w)),
        ("confidence", b.get("covers") or "n/a"),
        ("total variance", f"{b['total_variance_m2']:.4g} m^2 ({b['objective']}, "
                           f"{b.get('rule', 'envelope')} rule)"),
        ("PSD estimator", b["estimator"]),
        ("cutoff f_c", f"{fc}; source: {c['source']}"),
        ("sampling / Nyquist", f"{s['interval_s']:g} s / {s['nyquist_hz']:.4g} Hz"),
        ("windows", f"{w['count']} ({w['total_duration_s'] / 3600:.2f} h), never stationary "
                    f"{w['never_stationary_s'] / 60:.1f} min"),
        ("mapping", f"{r['mapping']['source']}: a={r['mapping']['a']:.3g}, "
                    f"b={r['mapping']['b']:.3g}, c={r['mapping']['c_deg']:.3g} deg"),
        ("cutoff validation", str(r["validation"].get("verdict"))),
    ]  # fmt: skip
    fig = plt.figure(figsize=(8.27, 11.69))
    fig.text(0.08, 0.95, f"psdbound report: {_title(r)}", fontsize=14, weight="bold")
    fig.text(0.08, 0.925, _METHOD.get(r["method"], r["method"]), fontsize=10)
    y = 0.88
    for k, v in rows:
        fig.text(0.08, y, k, fontsize=10)
        for j, line in enumerate(textwrap.wrap(v, 55) or [""]):
            fig.text(0.42, y - 0.018 * j, line, fontsize=10)
        y -= 0.028 + 0.018 * (len(textwrap.wrap(v, 55)) - 1 if len(v) > 55 else 0)
    y -= 0.02
    fig.text(0.08, y, "Caveats", fontsize=12, weight="bold")
    y -= 0.03
    for wtext in r["warnings"] or ["None."]:
        for line in textwrap.wrap(wtext, 95):
            fig.text(0.08, y, line, fontsize=8.5)
            y -= 0.02
        y -= 0.008
    y -= 0.02
    fig.text(0.08, y, "Inputs (SHA-256)", fontsize=12, weight="bold")
    y -= 0.028
    for i in r["provenance"]["inputs"]:
        fig.text(0.08, y, f"{i['role']}: {i['name']}", fontsize=8)
        fig.text(0.08, y - 0.016, i["sha256"], fontsize=7, family="monospace")
        y -= 0.04
    fig.text(0.08, 0.03, f"created {r['provenance']['created_utc']}, psdbound "
             f"{r['provenance']['versions']['psdbound']}", fontsize=8)  # fmt: skip
    return fig


def render_pdf(document: dict[str, Any], path: str | os.PathLike[str], *,
               figures: list[tuple[str, Any]] | None = None) -> Path:  # fmt: skip
    """Write the PDF report (summary and caveats page, then every figure) of a result document.

    Parameters
    ----------
    document : dict
        The result document.
    path : str or path-like
        The PDF file.
    figures : list of (str, Figure), optional
        Captions and figures already drawn (their HTML PNGs already made:
        the PDF adds the caption as a title); by default drawn here.

    Returns
    -------
    Path
    """
    r = document
    p = Path(path)
    with PdfPages(p, metadata={"Title": f"psdbound report: {_title(r)}", "Creator": "psdbound",
                               "CreationDate": None}) as pdf:  # fmt: skip
        page = _summary_page(r)
        pdf.savefig(page)
        plt.close(page)
        for caption, fig in figures if figures is not None else _figures(r):
            fig.suptitle(caption, fontsize=10, y=0.995)
            pdf.savefig(fig)
            plt.close(fig)
    return p


def write_report_folder(
    document: dict[str, Any],
    out_dir: str | os.PathLike[str],
    *,
    pdf: bool = True,
    overwrite: bool = False,
    option: str = "output folder",
) -> dict[str, Path]:
    """Write ``result.json``, ``report.html`` (and ``report.pdf``) safely and atomically.

    Everything is written into a temporary folder that is installed only
    when complete: a failed run leaves no half-written folder (and an
    existing folder untouched). An existing ``out_dir`` is replaced only when
    it is empty or a previous psdbound output; any other folder is refused
    unless ``overwrite`` (then psdbound's three files are written into it and
    nothing else is touched); an existing file is always refused (see
    :mod:`psdbound.common.outputs`).

    Parameters
    ----------
    document : dict
        The result document to write and render.
    out_dir : str or path-like
        Destination folder.
    pdf : bool, default True
        Also write the PDF report.
    overwrite : bool, default False
        Allow writing into a folder that is not a psdbound output.
    option : str, default "output folder"
        How to name the destination in messages (the CLI passes ``"--out"``).

    Returns
    -------
    dict of str to Path
        ``{"result": ..., "html": ..., "pdf": ...}``.

    Raises
    ------
    InputError
        The destination is refused (checked before anything is rendered).
    """
    out = Path(out_dir)
    with output_folder(out, overwrite=overwrite, option=option) as tmp:
        write_document(tmp / "result.json", document)
        figures = _figures(document)  # drawn once: PNGs for the HTML, then the PDF pages
        try:
            (tmp / "report.html").write_text(render_html(document, figures=figures))
            if pdf:
                render_pdf(document, tmp / "report.pdf", figures=figures)
        finally:
            for _, fig in figures:
                plt.close(fig)
    paths = {"result": out / "result.json", "html": out / "report.html"}
    if pdf:
        paths["pdf"] = out / "report.pdf"
    return paths
