"""Report figures and the PDF layout (issue 19, item 3)."""

from __future__ import annotations

import copy
import html as htmllib
import math
import re
import time

import numpy as np
import pytest
from matplotlib.collections import PolyCollection

import psdbound
from psdbound.reports import render, write_report_folder
from psdbound.reports.figure_data import cutoff_figure
from psdbound.reports.figures import (
    FIGURES,
    fig_cutoff_envelope,
    fig_psds_bound,
    fig_windows,
)
from psdbound.reports.figures_base import FULL_PAGE_H_IN, HALF_PAGE_H_IN

UNIT = re.compile(r"\[[^\]]+\]")


@pytest.fixture(scope="module")
def demo_doc():
    return psdbound.fit().document


def _with_map_curve(doc):
    """The demo document with the residual criterion at the map's margins (cutoff.by_margin)."""
    d = copy.deepcopy(doc)
    fc = d["cutoff"]["f_c_hz"]
    d["cutoff"]["by_margin"] = [
        {
            "margin_db": m,
            "threshold_m": 1e-3 * 10 ** (-m / 20),
            "f_c_hz": fc * 10 ** ((m - 40) / 60),
        }
        for m in (20.0, 30.0, 40.0, 50.0)
    ]
    return d


def _pdf_pages(path) -> int:
    return len(re.findall(rb"/Type\s*/Page[^s]", path.read_bytes()))


def _all_figures(doc):
    out = []
    for key, _, func in FIGURES:
        fig = func(doc)
        if fig is not None:
            out.append((key, fig))
    return out


def test_pdf_two_figures_per_page(demo_doc, tmp_path):
    rendered = render.rendered_figures(demo_doc)
    assert len(rendered) >= 6
    heights = [f.size_in[1] for f in rendered]
    assert all(h <= HALF_PAGE_H_IN + 1e-6 for h in heights), heights  # the demo: all half-page
    assert all(abs(f.size_in[0] - 7.35) < 0.01 for f in rendered)  # one text width, unscaled
    pdf = render.render_pdf(demo_doc, tmp_path / "r.pdf", rendered=rendered)
    n_summary = len(render._summary_pages(demo_doc))
    assert n_summary == 1
    assert _pdf_pages(pdf) == n_summary + math.ceil(len(rendered) / 2)  # then two to a page
    html = render.render_html(demo_doc, rendered=rendered)
    assert html.count("data:image/png;base64,") == len(rendered)


def test_pack_pages():
    assert render.pack_pages([4.0, 4.0, 4.0]) == [[0, 1], [2]]
    assert render.pack_pages([8.0, 3.0, 3.0, 9.5]) == [[0], [1, 2], [3]]
    assert render.pack_pages([3.0, 3.0, 3.0], per_page=3) == [[0, 1, 2]]


def test_write_report_folder_small_pdf(demo_doc, tmp_path):
    paths = write_report_folder(demo_doc, tmp_path / "out")
    size = paths["pdf"].stat().st_size
    assert 100_000 < size < 2_000_000
    assert paths["pdf"].read_bytes()[:5] == b"%PDF-"


def _synthetic_windows_doc(n_lanes=40, n_windows=1000, seed=1):
    """A document with 1,000 windows in 40 satellite lanes over 24 h (what the figure reads)."""
    rng = np.random.default_rng(seed)
    t0 = 1.3e9
    sats = [f"G{k:02d}" if k <= 32 else f"E{k - 32:02d}" for k in range(1, n_lanes + 1)]
    per_lane = n_windows // n_lanes
    arcs, wins, never, excluded, mapped = [], [], [], [], []
    for k, s in enumerate(sats):
        start = t0 + rng.uniform(0, 3 * 3600)
        arcs.append(
            {"sat": s, "t0": start, "t1": start + 20 * 3600, "kept": True, "start_reason": ""}
        )
        mapped.append(
            {"arc": k, "sats": s, "t_gps_s": [start, start + 20 * 3600], "mapped_m": [0.0, 0.0]}
        )
        t = start
        for _ in range(per_lane):
            d = rng.uniform(600, 2400)
            wins.append({"arc": k, "sats": s, "t_start_gps_s": t, "t_stop_gps_s": t + d})
            t += d
        never.append([k, s, t, t + 1800.0])
        excluded.append(
            {
                "sat": s,
                "start_gps_s": t + 1800.0,
                "stop_gps_s": t + 2700.0,
                "kind": "ionosphere" if k % 2 else "short remainder",
            }
        )
    return {
        "method": "DF",
        "data_span": {"start_gps_s": t0, "stop_gps_s": t0 + 86400.0, "n_arcs": len(mapped)},
        "windows": {
            "count": len(wins),
            "per_window": wins,
            "never_stationary": never,
            "never_stationary_s": 1800.0 * len(never),
        },
        "screening": {"excluded": excluded, "excluded_s": 900.0 * len(excluded)},
        "figures": {"t_ref_gps_s": t0, "arcs": arcs, "mapped": mapped},
    }, sats


def test_window_figure_with_1000_windows():
    doc, sats = _synthetic_windows_doc()
    t = time.perf_counter()
    fig = fig_windows(doc)
    rf = render.rasterize("windows", fig)
    assert time.perf_counter() - t < 20.0
    assert rf.size_in[1] <= FULL_PAGE_H_IN + 1e-6
    ax = fig.axes[0]
    assert [x.get_text() for x in ax.get_yticklabels()] == sats  # one lane per satellite
    assert ax.get_xlabel() == "time since data start [h]"
    assert ax.get_xlim()[1] == pytest.approx(24.0)
    # one collection per layer (not one artist per window); the windows' has 1000 bars
    polys = [c for c in ax.collections if isinstance(c, PolyCollection)]
    assert len(polys) == 5 and max(len(c.get_paths()) for c in polys) == 1000
    # the never-stationary spans are drawn only in their own lane
    red = [
        c for c in polys if np.allclose(c.get_facecolor()[0][:3], (0.839, 0.153, 0.157), atol=0.01)
    ]
    assert len(red) == 1
    for k, path in enumerate(red[0].get_paths()):
        y = path.vertices[:, 1]
        assert k - 0.5 < y.min() and y.max() < k + 0.5
    title = ax.get_title()
    assert "40 arcs after screening" in title and "1000 stationary windows" in title
    legend = [x.get_text() for x in fig.legends[0].get_texts()]
    # the screened-out spans by why they were excluded, counted
    assert {
        "stationary window",
        "never stationary",
        "ionosphere (20)",
        "short remainder (20)",
    } <= set(legend)


def test_psd_figure_shades_the_band_below_fc(demo_doc):
    fig = fig_psds_bound(demo_doc)
    ax = fig.axes[0]
    fc = demo_doc["cutoff"]["f_c_hz"]
    spans = {p.get_gid(): p for p in ax.patches if p.get_gid() in ("stopband", "transition")}
    assert "stopband" in spans
    stop = spans["stopband"]  # an axvspan: a rectangle in data x, axes y
    assert stop.get_x() + stop.get_width() == pytest.approx(fc)
    assert stop.get_x() <= ax.get_xlim()[0] * 1.0001  # from the left edge of the plot
    band_lo = demo_doc["bound"]["band_hz"][0]
    if band_lo > fc:
        assert "transition" in spans
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("removed by the high-pass" in s for s in labels)
    # dual-antenna: no filter, no shading
    da = copy.deepcopy(demo_doc)
    da["method"], da["cutoff"] = (
        "DA",
        {"f_c_hz": None, "source": "not applicable", "tau_c_min": None},
    )
    ax = fig_psds_bound(da).axes[0]
    assert not [p for p in ax.patches if p.get_gid() in ("stopband", "transition")]


def _check_units(key, fig):
    axes = [a for a in fig.axes if a.get_visible()]
    assert axes, key
    assert any(a.get_xlabel() for a in axes), key
    for a in axes:
        assert a.get_ylabel(), f"{key}: an axis without a label"
        for label in (a.get_xlabel(), a.get_ylabel()):
            if label:
                assert UNIT.search(label), f"{key}: {label!r} has no [unit]"


def test_every_axis_has_a_unit(demo_doc):
    doc = _with_map_curve(demo_doc)
    figs = _all_figures(doc)
    keys = [k for k, _ in figs]
    assert {
        "windows",
        "df_filter",
        "screening",
        "mapped",
        "psds",
        "tau",
        "cutoff",
        "jacobi_anger",
    } <= set(keys)
    for key, fig in figs:
        _check_units(key, fig)
    ls = copy.deepcopy(demo_doc)
    f = np.geomspace(1e-5, 1e-2, 50)
    ls["figures"]["cutoff_envelope"] = {
        "f_hz": f.tolist(),
        "psd_m2_hz": (1e-2 / f).tolist(),
        "envelope_m2_hz": (2e-2 / f).tolist(),
        "threshold_m2_hz": 1e-1,
    }
    _check_units("cutoff (Lomb-Scargle)", fig_cutoff_envelope(ls))


def test_cutoff_figure_appears_when_its_fields_are_present(demo_doc, tmp_path):
    if not (demo_doc["cutoff"].get("by_margin") or demo_doc["figures"].get("cutoff_envelope")):
        assert fig_cutoff_envelope(demo_doc) is None  # map cutoff without its curve: no figure
    # the map's residual criterion at its margins (cutoff.by_margin)
    doc = _with_map_curve(demo_doc)
    fig = fig_cutoff_envelope(doc)
    ax = fig.axes[0]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(s.startswith("f_c ") for s in labels) and any("level" in s for s in labels)
    assert ax.get_ylabel() == "residual ionosphere RMS [mm]"
    html = render.render_html(doc)
    assert "Cutoff criterion and f_c" in html
    # a computed cutoff: its summary's by_margin (max and mean over the series)
    comp = copy.deepcopy(demo_doc)
    comp["cutoff"]["computed"] = {
        "n_series": 84,
        "threshold_m": 1e-5,
        "by_margin": [
            {
                "margin_db": m,
                "threshold_m": 1e-3 * 10 ** (-m / 20),
                "mean_f_c_hz": 5e-4 * 10 ** ((m - 40) / 60),
                "max_f_c_hz": 1.5e-3 * 10 ** ((m - 40) / 60),
            }
            for m in (20.0, 40.0, 50.0)
        ],
    }
    assert len(fig_cutoff_envelope(comp).axes[0].get_lines()) >= 3
    # full curves from the pipeline (figures.cutoff_envelope via cutoff_info["figure"])
    f = np.geomspace(1e-4, 0.05, 300)
    raw = {
        "f_hz": f,
        "residual_m": 1e-9 / f**1.5,
        "threshold_m": 1e-5,
        "label": "max over 3",
        "curves": [{"f_hz": f, "residual_m": 0.5e-9 / f**1.5}] * 3,
    }
    data = cutoff_figure(raw)
    assert len(data["curves"]) == 3 and len(data["curves"][0]["f_hz"]) <= 120
    full = copy.deepcopy(demo_doc)
    full["figures"]["cutoff_envelope"] = data
    ax = fig_cutoff_envelope(full).axes[0]
    assert len(ax.get_lines()) >= 5  # 3 series, the max, the level (and f_c)
    with pytest.raises(ValueError):
        cutoff_figure({"f_hz": [1.0]})
    # no cutoff (dual-antenna): no figure
    da = copy.deepcopy(doc)
    da["cutoff"] = {"f_c_hz": None, "source": "not applicable", "tau_c_min": None}
    assert fig_cutoff_envelope(da) is None


def test_figure_counts_agree_with_the_tables(demo_doc):
    doc = demo_doc
    title = fig_windows(doc).axes[0].get_title()
    assert f"{doc['data_span']['n_arcs']} arcs after screening" in title
    assert f"{doc['windows']['count']} stationary windows" in title
    assert fig_psds_bound(doc).axes[0].get_title().startswith(f"{doc['windows']['count']} window")
    html = render.render_html(doc)
    assert f"{doc['data_span']['n_arcs']} arcs" in html


def _page_one_texts(doc):
    """Every text of the PDF's first page, in order, whitespace-normalised."""
    page = render._summary_pages(doc)[0]
    return " ".join(" ".join(t.get_text() for t in page.texts).split())


@pytest.mark.parametrize("verdict", ["bounded", "not-bounded"])
def test_page_one_is_the_same_in_console_html_pdf_and_json(demo_doc, verdict):
    """Issue 30: the verdict, each rule with its numbers, coverage, looseness, the statement."""
    from psdbound.pipeline.verdict import verdict_checks
    from psdbound.results.headline import headline

    doc = copy.deepcopy(demo_doc)
    if verdict == "not-bounded":  # the physical limit fires (a 19.7 cm "bound")
        doc["bound"]["sigma_gm_m"] = 0.197
        checks = verdict_checks(doc)
        doc["verdict"] = "not-bounded"
        doc["verdict_reasons"] = [c.reason for c in checks if not c.passed]
        doc["verdict_checks"] = [c.to_dict() for c in checks]
        doc["headline"] = headline(doc)
    lines = doc["headline"]
    assert lines == headline(doc)  # the JSON keeps what the document says
    assert len([x for x in lines if x.startswith("  ")]) == len(doc["verdict_checks"]) >= 8
    html = render.render_html(doc, figures=[])
    html_text = htmllib.unescape(html)
    pdf_text = _page_one_texts(doc)
    console = psdbound.FitResults(doc).summary()
    for line in lines:
        assert line.strip() in html_text, line
        assert " ".join(line.split()) in pdf_text, line
        assert line in console
    if verdict == "not-bounded":
        assert lines[0].startswith("VERDICT: NOT-BOUNDED - do not use")
        assert "95 % confidence" not in pdf_text
    else:
        assert any(x.startswith("bound above the pooled data: median") for x in lines)
    # the thesis's criterion is not on page 1: it is labelled as the thesis's, not a rule
    assert "cutoff validation" not in " ".join(lines)
    assert "thesis cutoff criterion" in html


def test_sky_cells_put_each_sample_in_its_azimuth_elevation_cell():
    from types import SimpleNamespace

    from psdbound.reports.figure_data import sky_cells

    t = np.arange(0.0, 600.0, 30.0)
    arcs = SimpleNamespace(azimuth_at=lambda sat, tt: np.full(np.size(tt), 47.0))
    v = np.where(np.arange(t.size) % 2, 0.002, -0.002)  # RMS 2 mm
    series = SimpleNamespace(
        n_arcs=1,
        arc_sats=("G05",),
        t_gps_s=t,
        value_m=v,
        elevation_deg=np.full(t.size, 32.0),
        arc_bounds=lambda: [(0, t.size)],
    )
    d = sky_cells(series, arcs)
    assert d["n_samples"] == t.size and d["count"][6, 4] == t.size  # el 30-35, az 40-50
    assert d["rms_m"][6][4] == pytest.approx(0.002)
    assert sum(x is not None for row in d["rms_m"] for x in row) == 1
    assert sky_cells(series, None) is None  # no azimuths (dual-antenna): no sky view


def test_results_return_their_figures(demo_doc):
    res = psdbound.FitResults(demo_doc)
    sky = res.plot_sky()
    assert sky is not None and sky.axes[0].name == "polar"
    assert "bound sigma at zenith" in sky.axes[0].get_title()
    assert res.plot_psd().axes[0].get_xscale() == "log"
    assert res.plot_windows() is not None and res.plot_screening() is not None
    with pytest.raises(psdbound.InputError, match="choose from"):
        res.plot("skyline")


def _screening_doc():
    """Three satellites of 2 h in 5-min blocks; one span cut per test, with its probability."""
    t0 = 1.3e9
    mids = t0 + 150.0 + 300.0 * np.arange(24)
    roti = {"G02": np.full(24, 0.05), "G10": np.full(24, 0.05), "G07": np.full(24, 0.05)}
    roti["G10"][4:7] = 0.6  # above its threshold of 0.3: the single-block test
    roti["G07"][10:13] = 0.25  # below it: cut by the 15-min persistence test
    entries = [
        {
            "sats": s,
            "t_gps_s": mids.tolist(),
            "roti_tecu_min": r.tolist(),
            "threshold_tecu_min": [0.3] * 24,
            "value_max_m": [0.004] * 24,
            "excluded": [False] * 24,
        }
        for s, r in roti.items()
    ]
    excluded = [
        {
            "sat": "G10",
            "start_gps_s": t0 + 1200.0,
            "stop_gps_s": t0 + 2100.0,
            "kind": "ionosphere",
            "test": "block",
            "false_alarm": 1e-3 / 3,
            "false_alarm_at_threshold": 1e-3 / 3,
        },
        {
            "sat": "G07",
            "start_gps_s": t0 + 3000.0,
            "stop_gps_s": t0 + 3900.0,
            "kind": "ionosphere",
            "test": "persistence",
            "false_alarm": 1e-3 / 3,
            "false_alarm_at_threshold": None,
        },
        {
            "sat": "G07",
            "start_gps_s": t0 + 3900.0,
            "stop_gps_s": t0 + 4200.0,
            "kind": "short remainder",
            "test": "length",
            "false_alarm": None,
            "false_alarm_at_threshold": None,
        },
    ]
    return {
        "method": "DF",
        "data_span": {"start_gps_s": t0, "stop_gps_s": t0 + 7200.0, "n_arcs": 3},
        "screening": {
            "excluded": excluded,
            "excluded_s": 2100.0,
            "multipath_null": {"trusted": True},
            "false_alarm_per_block": 1e-3,
            "block_test": {"false_alarm": 1e-3 / 3},
        },
        "figures": {
            "t_ref_gps_s": t0,
            "screening": {"roti": entries, "threshold_tecu_min": 0.15, "limit_m": 0.077},
        },
    }


def test_screening_figure_shows_per_satellite_what_was_cut_and_why():
    """Issue 29 item 4: lanes per satellite, blocks by statistic / threshold, spans by test."""
    from psdbound.reports.figures_time import fig_screening

    fig = fig_screening(_screening_doc())
    ax = fig.axes[0]
    assert [x.get_text() for x in ax.get_yticklabels()] == ["G02", "G07", "G10"]
    polys = [c for c in ax.collections if isinstance(c, PolyCollection)]
    blocks = polys[0]
    assert len(blocks.get_paths()) == 72  # every block of every satellite
    ratio = np.asarray(blocks.get_array()).reshape(3, 24)  # G02, G10, G07 in document order
    assert ratio[1, 5] == pytest.approx(2.0) and ratio[2, 11] == pytest.approx(0.25 / 0.3)
    # one outline collection per test, in the test's colour, in the satellite's lane
    outlines = {tuple(np.round(c.get_edgecolor()[0][:3], 3)): c for c in polys[1:]}
    assert len(outlines) == 3
    red = outlines[(0.839, 0.153, 0.157)]  # the single-block test
    y = red.get_paths()[0].vertices[:, 1]
    assert 2 - 0.5 < y.min() and y.max() < 2 + 0.5  # G10's lane
    legend = [t.get_text() for t in fig.legends[0].get_texts()]
    assert "one block's ROTI above its threshold (1; p = 0.00033)" in legend
    assert "15 min improbable (persistence) (1; p = 0.00033)" in legend
    assert "short remainder (1)" in legend
    colorbar = [a for a in fig.axes if a.get_ylabel() == "ROTI / threshold [-]"]
    assert len(colorbar) == 1
    assert "multipath null at p = 0.00033 per block" in fig._suptitle.get_text()
