"""HTML and PDF reports from a result document, written atomically.

How the figures get into both reports
-------------------------------------
Every figure is drawn once and rasterised once, with Agg at :data:`DPI`
(150 dpi) and one A4 text width wide (7.35 in, 1,100 px). The same pixels
serve both reports: the PNG is inlined in the HTML, and the RGB array is
placed unscaled (150 ppi, ``interpolation="none"``: PDF viewers get the
original pixels) on A4 pages, two figures to a page where their heights
fit. The summary page stays vector text (searchable, the SHA-256 copyable).

Measured on the 24 h, 1 Hz result of ``benchmarks/scale_fit.py`` (104
windows, 2 shared cores; ``psdbound report`` wall time, of which about
3.5 s is the CLI's start-up):

* before (figures drawn, PNG at 110 dpi for the HTML, drawn again as vector
  PDF, one figure per portrait page): 13.0-14.3 s; PDF 558 kB, 8 pages;
  HTML 927 kB;
* raster pages (this module): 8.3-9.0 s; PDF 315 kB, 5 pages; HTML 350 kB.
  Rendering alone (figures, HTML, PDF) 4.1 s of CPU instead of 8.2-9.3 s;
* vector pages with two figures each (the same figures saved as vector
  PDF): every figure drawn twice, Agg for the HTML and the PDF renderer for
  the pages: 2.9 s more CPU for this result (2.8 s for the demo), and
  612 kB of figures (334 kB for the demo) against 315 kB (297 kB) raster;
  a vector page of the PSD figure (hundreds of translucent curves) is also
  slow to display.

Other savings: plain-text log tick labels (no mathtext), minor log ticks at
2 and 5 only, figures outside pyplot, and a 256-colour palette PNG (see
:func:`rasterize`).

What is lost is the PDF's resolution independence: at 150 ppi the figures
print at the resolution they were drawn at, and zooming past 200 % shows
pixels. The numbers a reader needs are in the tables (vector text) and in
``result.json``; the figures are for shape, which 150 ppi keeps.
"""

from __future__ import annotations

import base64
import io
import os
import textwrap
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402
from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from PIL import Image  # noqa: E402

from psdbound.reports.figures import FIGURES  # noqa: E402
from psdbound.reports.templating import template  # noqa: E402
from psdbound.results.headline import DO_NOT_USE, headline  # noqa: E402

__all__ = [
    "DPI",
    "RenderedFigure",
    "pack_pages",
    "rasterize",
    "render_html",
    "render_pdf",
    "rendered_figures",
]

#: Resolution of the figures in both reports, dots per inch.
DPI = 150.0
#: A4 portrait, in.
PAGE_IN = (8.27, 11.69)
_MARGIN_X_IN, _TOP_IN, _BOTTOM_IN = 0.45, 0.45, 0.55
_CAPTION_IN, _GAP_IN = 0.28, 0.3
#: Figures per PDF page at most.
PER_PAGE = 2

_METHOD = {
    "DF": "dual-frequency (one antenna, two carriers) multipath",
    "DA": "dual-antenna double-difference multipath",
}


@dataclass(frozen=True, eq=False)
class RenderedFigure:
    """A report figure rasterised once for both reports.

    Attributes
    ----------
    caption : str
        The figure's caption.
    png : bytes
        PNG file (256-colour palette) for the HTML report.
    rgb : ndarray of uint8, shape (height, width, 3)
        The same pixels for the PDF pages.
    dpi : float
        Pixels per inch they were drawn at.
    """

    caption: str
    png: bytes
    rgb: np.ndarray
    dpi: float

    @property
    def size_in(self) -> tuple[float, float]:
        """(width, height) at the drawn size, in."""
        return self.rgb.shape[1] / self.dpi, self.rgb.shape[0] / self.dpi


def rasterize(caption: str, fig: Figure, *, dpi: float = DPI) -> RenderedFigure:
    """Draw a figure once with Agg and return its pixels and PNG (256-colour palette).

    A plot has few colours: the palette (octree, no dithering) changes only
    antialiased edge pixels, by a few levels, and makes the PNG (and the
    PDF's image, which matplotlib then stores indexed) about 3 times smaller.

    Parameters
    ----------
    caption : str
        Caption of the figure.
    fig : Figure
        The figure (left open).
    dpi : float, default :data:`DPI`
        Resolution.

    Returns
    -------
    RenderedFigure
    """
    fig.set_dpi(dpi)
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    img = Image.fromarray(np.asarray(canvas.buffer_rgba())[..., :3]).quantize(
        colors=256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.NONE
    )
    buf = io.BytesIO()
    img.save(buf, format="png")
    return RenderedFigure(caption, buf.getvalue(), np.asarray(img.convert("RGB")), float(dpi))


def rendered_figures(r: dict[str, Any]) -> list[RenderedFigure]:
    """Draw and rasterise every figure of a result document (each released once drawn)."""
    out = []
    for _, caption, func in FIGURES:
        fig = func(r)
        if fig is not None:
            out.append(rasterize(caption, fig))
    return out


def _as_rendered(
    r: dict[str, Any], figures: list[tuple[str, Any]] | None, rendered: list[RenderedFigure] | None
) -> list[RenderedFigure]:
    if rendered is not None:
        return rendered
    if figures is not None:
        return [rasterize(caption, fig) for caption, fig in figures]
    return rendered_figures(r)


def _validation_note(r: dict[str, Any]) -> str:
    v = r["validation"]
    if v.get("summary"):
        return str(v["summary"])
    return str(v.get("reason", ""))


def _headline(r: dict[str, Any]) -> list[str]:
    """Page-1 lines of the document (computed for documents written before they were kept)."""
    return list(r.get("headline") or headline(r))


def _title(r: dict[str, Any]) -> str:
    names = [i["name"] for i in r["provenance"]["inputs"] if i["role"] == "obs"]
    return ", ".join(names) or "result"


def render_html(
    document: dict[str, Any],
    *,
    figures: list[tuple[str, Any]] | None = None,
    rendered: list[RenderedFigure] | None = None,
) -> str:
    """Return the self-contained HTML report (figures inline as PNG) of a result document.

    Parameters
    ----------
    document : dict
        The result document.
    figures : list of (str, Figure), optional
        Captions and figures already drawn (rasterised here, left open).
    rendered : list of RenderedFigure, optional
        Figures already rasterised (:func:`rasterize`); by default every
        figure is drawn here.

    Returns
    -------
    str
    """
    r = document
    figs = [
        {"caption": x.caption, "png": base64.b64encode(x.png).decode()}
        for x in _as_rendered(r, figures, rendered)
    ]
    span_h = (r["data_span"]["stop_gps_s"] - r["data_span"]["start_gps_s"]) / 3600.0
    return template("report.html.j2").render(
        r=r,
        title=_title(r),
        method_long=_METHOD.get(r["method"], r["method"]),
        span_h=span_h,
        figures=figs,
        demo=r.get("demo"),
        validation_note=_validation_note(r),
        headline=_headline(r),
    )


def _error_model_text(em: dict[str, Any] | None) -> str:
    """Return the error model's components in one line."""
    if not em:
        return "n/a"
    parts = [
        f"{c['name']} {1000 * c['sigma_m']:.2f} mm"
        + (f" / {c['tau_s']:.1f} s" if c.get("tau_s") else f" ({c['kind']})")
        for c in em["components"]
    ]
    return "; ".join(parts) + " (result.json error_model)"


def _error_model_rows(r: dict[str, Any]) -> list[tuple[str, str]]:
    """Return the error model and its integrity note rows (a not-bounded result has none)."""
    if r["verdict"] != "bounded":
        return [("error model", f"none: not bounded ({DO_NOT_USE})")]
    em = r.get("error_model")
    return [
        ("error model", _error_model_text(em)),
        ("for a protection level", (em or {}).get("integrity_note", "n/a")),
    ]


def _summary_pages(r: dict[str, Any]) -> list[Figure]:
    """Draw the summary, caveats and inputs (vector text; a second page if long)."""
    rows = _summary_rows(r)
    doc = _TextPages()
    doc.text(0.08, 0.025, f"psdbound report: {_title(r)}", fontsize=14, weight="bold")
    doc.text(0.08, 0.035, _METHOD.get(r["method"], r["method"]), fontsize=10)
    _write_headline(doc, r)
    doc.y -= 0.012
    _write_rows(doc, rows)
    doc.y -= 0.012
    doc.text(0.08, 0.025, "Caveats", fontsize=12, weight="bold")
    for wtext in r["warnings"] or ["None."]:
        for line in textwrap.wrap(wtext, 118):
            doc.text(0.08, 0.0125, line, fontsize=7)
        doc.y -= 0.003
    doc.y -= 0.015
    doc.text(0.08, 0.026, "Inputs (SHA-256)", fontsize=12, weight="bold")
    for i in r["provenance"]["inputs"]:
        doc.text(
            0.08,
            0.017,
            f"{i['role']}: {i['name']}  {i['sha256']}",
            fontsize=6.5,
            family="monospace",
        )
    doc.y -= 0.005
    doc.text(
        0.08,
        0.0,
        f"created {r['provenance']['created_utc']}, psdbound "
        f"{r['provenance']['versions']['psdbound']}",
        fontsize=8,
    )
    return doc.pages


class _TextPages:
    """Pages of vector text written top-down at height ``y`` (figure fraction)."""

    def __init__(self) -> None:
        self.pages = [Figure(figsize=PAGE_IN)]
        self.y = 0.95

    def text(self, x: float, dy: float, line: str, **kw: Any) -> None:
        """Write a line at the current height, then move down (a new page when full)."""
        if self.y < 0.03:
            self.pages.append(Figure(figsize=PAGE_IN))
            self.y = 0.95
        self.pages[-1].text(x, self.y, line, **kw)
        self.y -= dy


def _summary_rows(r: dict[str, Any]) -> list[tuple[str, str]]:
    """Return the summary table: (name, value) rows of the bound, cutoff, windows, inputs."""
    b, s, c, w = r["bound"], r["sampling"], r["cutoff"], r["windows"]
    fc = "n/a" if c["f_c_hz"] is None else f"{c['f_c_hz']:.4g} Hz ({c['tau_c_min']:.1f} min)"
    rows = [
        (
            "screening excluded",
            f"{r['screening']['excluded_s'] / 3600:.2f} h "
            f"({100 * r['screening']['excluded_fraction']:.1f} %)",
        ),
        ("sigma_GM", f"{100 * b['sigma_gm_m']:.3f} cm"),
        ("tau_GM", f"{b['tau_s']:.1f} s"),
        ("sigma_WN (per sample)", f"{100 * b['sigma_wn_m']:.3f} cm at {s['interval_s']:g} s"),
        *_error_model_rows(r),
        (
            "total variance",
            f"{b['total_variance_m2']:.4g} m^2 ({b['objective']}, "
            f"{b.get('rule', 'envelope')} rule, {b['estimator']} PSDs)",
        ),
        ("cutoff f_c", f"{fc}; source: {c['source']}"),
        ("sampling / Nyquist", f"{s['interval_s']:g} s / {s['nyquist_hz']:.4g} Hz"),
        (
            "windows",
            f"{w['count']} ({w.get('covered_s', w['total_duration_s']) / 3600:.2f} h), "
            f"never stationary {w['never_stationary_s'] / 60:.1f} min",
        ),
        (
            "mapping",
            f"{r['mapping']['source']}: a={r['mapping']['a']:.3g}, "
            f"b={r['mapping']['b']:.3g}, c={r['mapping']['c_deg']:.3g} deg",
        ),
        (
            "thesis cutoff criterion",
            f"{r['validation'].get('verdict')} (reported, not a verdict rule)",
        ),
    ]
    cm = r.get("code_multipath")
    if cm:
        ob = (cm.get("overbound") or {}).get("bins", [])
        text_ob = "; ".join(
            f"{b['elevation_deg'][0]:g}-{b['elevation_deg'][1]:g} deg: "
            f"sigma {100 * b['sigma']:.1f} cm (x{b['inflation']:.2f})"
            for b in ob
        ) or str(cm.get("status"))
        rows.append((f"code multipath {'+'.join(cm.get('codes', []))}", text_ob))
    return rows


def _write_headline(doc: _TextPages, r: dict[str, Any]) -> None:
    """Write the headline lines every output starts with (failures in red)."""
    for k, line in enumerate(_headline(r)):  # page 1 as in every output
        bad = line.endswith(" FAIL") or line.startswith(("VERDICT: NOT", "reason: "))
        wrapped = textwrap.wrap(line.strip(), 72 if k == 0 else 118) or [""]
        for part in wrapped:
            doc.text(
                0.1 if line.startswith("  ") else 0.08,
                0.018 if k == 0 else 0.0112,
                part,
                fontsize=11 if k == 0 else 7,
                weight="bold" if k == 0 else "normal",
                color="#b00020" if bad else ("#176d2a" if k == 0 else "black"),
            )


def _write_rows(doc: _TextPages, rows: list[tuple[str, str]]) -> None:
    """Write the summary table: the name left, the value (wrapped) right."""
    for k, v in rows:
        long = len(v) > 3 * 55  # long statements in a smaller face, so page 1 holds them
        lines = textwrap.wrap(v, 68 if long else 55) or [""]
        doc.pages[-1].text(0.08, doc.y, k, fontsize=9)
        for j, line in enumerate(lines):
            step = (0.0115 if long else 0.014) if j < len(lines) - 1 else 0.0165
            doc.text(0.42, step, line, fontsize=7.5 if long else 9)


def pack_pages(heights_in: list[float], *, per_page: int = PER_PAGE) -> list[list[int]]:
    """Group figures onto A4 pages in order: as many as fit, at most ``per_page``.

    Parameters
    ----------
    heights_in : list of float
        Height of each figure as placed, in.
    per_page : int, default :data:`PER_PAGE`
        Most figures on one page.

    Returns
    -------
    list of list of int
        Indices of the figures on each page.
    """
    room = PAGE_IN[1] - _TOP_IN - _BOTTOM_IN
    pages: list[list[int]] = []
    used = room + 1.0
    for k, h in enumerate(heights_in):
        need = _CAPTION_IN + h + (_GAP_IN if pages and pages[-1] else 0.0)
        if pages and len(pages[-1]) < per_page and used + need <= room + 1e-9:
            pages[-1].append(k)
            used += need
        else:
            pages.append([k])
            used = _CAPTION_IN + h
    return pages


def _placed_size(fig: RenderedFigure) -> tuple[float, float]:
    """Size of a figure on the page: as drawn, shrunk only if it exceeds the page."""
    w, h = fig.size_in
    room_w = PAGE_IN[0] - 2 * _MARGIN_X_IN
    room_h = PAGE_IN[1] - _TOP_IN - _BOTTOM_IN - _CAPTION_IN
    scale = min(1.0, room_w / w, room_h / h)
    return w * scale, h * scale


def _figure_page(figs: list[tuple[int, RenderedFigure]], footer: str) -> Figure:
    """One A4 page with its figures (numbered captions above them), pixels unscaled."""
    pw, ph = PAGE_IN
    page = Figure(figsize=PAGE_IN)
    y = ph - _TOP_IN
    for number, fig in figs:
        w, h = _placed_size(fig)
        page.text(
            _MARGIN_X_IN / pw,
            (y - 0.2) / ph,
            f"Figure {number}. {fig.caption}",
            fontsize=9.5,
            weight="bold",
        )
        y -= _CAPTION_IN + h
        ax = page.add_axes((_MARGIN_X_IN / pw, y / ph, w / pw, h / ph))
        ax.imshow(fig.rgb, interpolation="none", aspect="auto")
        ax.set_axis_off()
        y -= _GAP_IN
    page.text(0.5, 0.25 / ph, footer, fontsize=7, ha="center", color="0.4")
    return page


def render_pdf(
    document: dict[str, Any],
    path: str | os.PathLike[str],
    *,
    figures: list[tuple[str, Any]] | None = None,
    rendered: list[RenderedFigure] | None = None,
) -> Path:
    """Write the PDF report (summary and caveats page, then the figures) of a result document.

    The figures go onto A4 pages in report order, at their drawn size, two
    to a page where they fit (:func:`pack_pages`), numbered like the HTML.

    Parameters
    ----------
    document : dict
        The result document.
    path : str or path-like
        The PDF file.
    figures : list of (str, Figure), optional
        Captions and figures already drawn (rasterised here, left open).
    rendered : list of RenderedFigure, optional
        Figures already rasterised (the HTML's pixels); by default every
        figure is drawn here.

    Returns
    -------
    Path
    """
    from matplotlib.backends.backend_pdf import PdfPages  # deferred: not needed with --no-pdf

    r = document
    p = Path(path)
    figs = _as_rendered(r, figures, rendered)
    pages = pack_pages([_placed_size(f)[1] for f in figs])
    title = f"psdbound report: {_title(r)}"
    with PdfPages(p, metadata={"Title": title, "Creator": "psdbound", "CreationDate": None}) as pdf:
        summary = _summary_pages(r)
        for page in summary:
            pdf.savefig(page)
        first, total = len(summary) + 1, len(summary) + len(pages)
        for n, idx in enumerate(pages, start=first):
            footer = f"{title} - page {n} of {total}"
            pdf.savefig(_figure_page([(k + 1, figs[k]) for k in idx], footer))
    return p
