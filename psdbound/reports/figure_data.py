"""The data every report figure is drawn from, built from the stage results.

The fit writes this into ``result.json`` (section ``figures``) so that a
report can be redrawn from the file alone (``psdbound report``). Long series
are decimated (at most ``MAX_POINTS`` per arc) and PSDs log-binned to their
maxima (at most ``MAX_PSD_POINTS`` each: a faithful upper outline).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "MAX_POINTS",
    "MAX_PSD_POINTS",
    "SKY_CELL_DEG",
    "cutoff_figure",
    "figure_data",
    "psd_outline",
    "sky_cells",
]

MAX_POINTS = 1500
#: Points of all arcs of the mapped-series figure together, and the least per arc.
MAX_TOTAL_POINTS = 30000
MIN_ARC_POINTS = 200
MAX_PSD_POINTS = 300
#: Sky cells: azimuth and elevation widths, degrees.
SKY_CELL_DEG = (10.0, 5.0)


def _decimate(n: int, limit: int = MAX_POINTS) -> slice:
    return slice(None, None, max(1, int(np.ceil(n / limit))))


def psd_outline(
    f_hz: NDArray[np.float64], psd_m2_hz: NDArray[np.float64], n: int = MAX_PSD_POINTS
) -> tuple[list[float], list[float]]:
    """Log-binned maxima of a PSD (an upper outline for plotting).

    Parameters
    ----------
    f_hz : ndarray
        Increasing frequencies, Hz (> 0).
    psd_m2_hz : ndarray
        PSD values, m^2/Hz.
    n : int
        Number of log-spaced bins.

    Returns
    -------
    f_hz, psd_m2_hz : list of float
        At most ``n`` points: in each bin, the frequency and value of the maximum.
    """
    f = np.asarray(f_hz, dtype=float)
    s = np.asarray(psd_m2_hz, dtype=float)
    if f.size <= n:
        return f.tolist(), s.tolist()
    edges = np.geomspace(f[0], f[-1] * (1 + 1e-12), n + 1)
    idx = np.clip(np.searchsorted(edges, f, side="right") - 1, 0, n - 1)
    ff, ss = [], []
    for k in np.unique(idx):
        sel = idx == k
        j = np.argmax(s[sel])
        ff.append(float(f[sel][j]))
        ss.append(float(s[sel][j]))
    return ff, ss


def _arcs(series: Any, arcs: Any) -> list[dict[str, Any]]:
    if arcs is not None:
        return [
            {
                "sat": a.sat,
                "t0": float(a.t_gps_s[0]),
                "t1": float(a.t_gps_s[-1]),
                "kept": True,
                "start_reason": a.start_reason,
            }
            for a in arcs
        ]
    return [
        {
            "sat": a.sats,
            "t0": float(a.t_gps_s[0]),
            "t1": float(a.t_gps_s[-1]),
            "kept": True,
            "start_reason": "",
        }
        for a in series.arcs()
    ]


def _df_filter(series: Any) -> dict[str, Any] | None:
    """Return the DF difference before/after filtering, for the longest arc."""
    if series.unfiltered_m is None or series.n_arcs == 0:
        return None
    k = int(np.argmax([a.duration_s for a in series.arcs()]))
    av = series.arc(k)
    sl = _decimate(av.t_gps_s.size)
    return {
        "sat": av.sats,
        "t_gps_s": av.t_gps_s[sl],
        "unfiltered_m": av.unfiltered_m[sl],
        "filtered_m": (av.value_m / series.scaling)[sl],
    }


def _mapped(series: Any, windows: Any) -> list[dict[str, Any]]:
    """Every arc's mapped series, decimated to share ``MAX_TOTAL_POINTS`` by length.

    Values are rounded for plotting (0.1 s, 0.01 mm, 0.01 deg): a 24 h, 1 Hz
    day would otherwise put megabytes of full-precision digits into result.json.
    """
    bounds = list(series.arc_bounds())
    total = max(1, sum(hi - lo for lo, hi in bounds))
    out = []
    for k, (lo, hi) in enumerate(bounds):
        limit = min(MAX_POINTS, max(MIN_ARC_POINTS, int(MAX_TOTAL_POINTS * (hi - lo) / total)))
        sl = _decimate(hi - lo, limit)
        out.append(
            {
                "arc": k,
                "sats": series.arc_sats[k],
                "t_gps_s": np.round(series.t_gps_s[lo:hi][sl], 1),
                "mapped_m": np.round(windows.mapped_m[lo:hi][sl], 5),
                "elevation_deg": np.round(series.elevation_deg[lo:hi][sl], 2),
            }
        )
    return out


#: Series curves of the cutoff figure kept at most, and points per curve.
MAX_CUTOFF_CURVES = 200
MAX_CUTOFF_POINTS = 120


def cutoff_figure(d: dict[str, Any]) -> dict[str, Any]:
    """Check and thin the data of the cutoff figure (``figures.cutoff_envelope``).

    Two forms (every array a list of float of one length per curve):

    Residual criterion (map or computed cutoff):
        ``f_hz`` (Hz) and ``residual_m`` (m): the residual ionosphere RMS in
        the fit's series after the high-pass at each cutoff (for a station
        year the maximum over its series: the curve f_c is read from);
        ``threshold_m`` (m, the criterion's level); optional ``curves``
        (list of ``{"f_hz", "residual_m"}``, one per series, drawn grey) and
        ``label`` (str, what the main curve is).
    Lomb-Scargle (relative) criterion:
        ``f_hz`` (Hz), ``psd_m2_hz`` (m^2/Hz), ``envelope_m2_hz`` (m^2/Hz, on
        ``f_hz``), optional ``maxima_f_hz`` / ``maxima_psd_m2_hz``,
        ``reference_m2_hz`` and ``threshold_m2_hz`` (m^2/Hz, the reference
        less ``drop_db``, default 40 dB).

    Parameters
    ----------
    d : dict
        The figure data as the cutoff source gives it.

    Returns
    -------
    dict
        The same data; at most :data:`MAX_CUTOFF_CURVES` series curves of
        :data:`MAX_CUTOFF_POINTS` points each.

    Raises
    ------
    ValueError
        Neither form, or arrays of different lengths.
    """
    out = dict(d)
    if "residual_m" in d:
        pairs = [("f_hz", "residual_m")]
    elif "psd_m2_hz" in d or "psd" in d:
        pairs = [("f_hz", "psd_m2_hz" if "psd_m2_hz" in d else "psd")]
        if "envelope_m2_hz" in d:
            pairs.append(("f_hz", "envelope_m2_hz"))
    else:
        raise ValueError(
            "cutoff figure data needs residual_m (residual criterion) or psd_m2_hz (Lomb-Scargle)"
        )
    for fk, vk in pairs:
        if len(d[fk]) != len(d[vk]):
            raise ValueError(f"cutoff figure: {fk} and {vk} differ in length")
    curves = []
    for c in list(d.get("curves") or [])[:MAX_CUTOFF_CURVES]:
        sl = _decimate(len(c["f_hz"]), MAX_CUTOFF_POINTS)
        curves.append(
            {
                "f_hz": np.asarray(c["f_hz"], dtype=float)[sl],
                "residual_m": np.asarray(c["residual_m"], dtype=float)[sl],
            }
        )
    if curves:
        out["curves"] = curves
    return out


def _jacobi_anger(expansion: Iterable[Any]) -> dict[str, Any]:
    cases: dict[str, dict[str, Any]] = {}
    for chk in expansion:
        h = chk.second
        f_hz = np.asarray(h.orders, dtype=float) * chk.rate.frequency_hz
        keep = slice(0, 2000)
        case = cases.setdefault(
            chk.geometry.label,
            {
                "label": f"{chk.geometry.label}, rate {chk.rate.name} "
                f"({chk.rate.frequency_hz:.3g} Hz), alpha {chk.alpha:g}"
            },
        )
        case[chk.convention] = {
            "f_hz": f_hz[keep],
            "power": np.asarray(h.power_rad2)[keep],
            "fraction_below": chk.fraction_below_cutoff,
            "z": chk.z,
        }
    return {"cases": list(cases.values())}


def sky_cells(
    series: Any, arcs: Any, cell_deg: tuple[float, float] = SKY_CELL_DEG
) -> dict[str, Any] | None:
    """RMS of the isolated multipath in azimuth-elevation cells (the sky view).

    Parameters
    ----------
    series : MultipathSeries
        The screened isolated multipath (one satellite per arc).
    arcs : ArcSet or None
        Tracking arcs with azimuths (dual-frequency); None: no sky view.
    cell_deg : (float, float), default (10, 5)
        Cell width in azimuth and elevation, degrees.

    Returns
    -------
    dict or None
        ``az_edges_deg``, ``el_edges_deg``, ``rms_m`` (elevation x azimuth,
        None where empty), ``count`` (samples per cell) and ``n_samples``;
        None without azimuths.
    """
    if arcs is None or series.n_arcs == 0:
        return None
    d_az, d_el = cell_deg
    az_e, el_e = np.arange(0.0, 360.0 + d_az / 2, d_az), np.arange(0.0, 90.0 + d_el / 2, d_el)
    ss = np.zeros((el_e.size - 1, az_e.size - 1))
    n = np.zeros_like(ss)
    for k, (lo, hi) in enumerate(series.arc_bounds()):
        az = arcs.azimuth_at(series.arc_sats[k], series.t_gps_s[lo:hi])
        el, v = series.elevation_deg[lo:hi], series.value_m[lo:hi]
        ok = np.isfinite(az) & np.isfinite(el) & np.isfinite(v)
        i = np.clip((el[ok] // d_el).astype(int), 0, el_e.size - 2)
        j = np.clip((np.mod(az[ok], 360.0) // d_az).astype(int), 0, az_e.size - 2)
        np.add.at(ss, (i, j), v[ok] ** 2)
        np.add.at(n, (i, j), 1.0)
    if not n.any():
        return None
    with np.errstate(invalid="ignore", divide="ignore"):
        rms = np.sqrt(ss / n)
    return {
        "az_edges_deg": az_e,
        "el_edges_deg": el_e,
        "rms_m": [
            [None if c == 0 else float(x) for x, c in zip(r, cr, strict=True)]
            for r, cr in zip(rms, n, strict=True)
        ],
        "count": n.astype(int),
        "n_samples": int(n.sum()),
    }


def figure_data(
    *,
    series: Any,
    arcs: Any,
    windows: Any,
    bound_results: Any,
    t_ref_gps_s: float,
    interval_s: float,
    cutoff_info: dict[str, Any] | None = None,
    validation_report: Any = None,
    screening: Any = None,
) -> dict[str, Any]:
    """Build the ``figures`` section of a result document.

    Parameters
    ----------
    series : MultipathSeries
        The isolated multipath.
    arcs : ArcSet or None
        Tracking arcs (dual-frequency); None to draw the series' arcs.
    windows : WindowSet
        Stationary windows (with the mapped series).
    bound_results : BoundResults
        Window PSDs and the bound.
    t_ref_gps_s : float
        Time origin of the time axes, GPS seconds.
    interval_s : float
        Sampling interval, s (the bound curve stops at Nyquist).
    cutoff_info : dict, optional
        Cutoff details (``CutoffChoice.info``); its ``"figure"`` entry, when
        present, becomes ``figures.cutoff_envelope`` (see :func:`cutoff_figure`).
    validation_report : ValidationReport, optional
        Cutoff validation; its expansions give the Jacobi-Anger figure.
    screening : Screening, optional
        ROTI per arc, excluded spans and the plausibility limit.

    Returns
    -------
    dict
        Figure name -> plain data (arrays as numpy or lists).
    """
    figures: dict[str, Any] = {"arcs": _arcs(series, arcs), "t_ref_gps_s": float(t_ref_gps_s)}
    df = _df_filter(series)
    if df is not None:
        figures["df_filter"] = df
    figures["mapped"] = _mapped(series, windows)
    sky = sky_cells(series, arcs)
    if sky is not None:
        figures["sky"] = sky
    psd_fig = []
    for p in bound_results.psds:
        ff, ss = psd_outline(np.asarray(p.f_hz), np.asarray(p.psd_m2_hz))
        psd_fig.append({"f_hz": ff, "psd_m2_hz": ss})
    figures["psds"] = psd_fig
    b = bound_results.bound
    f_grid = np.geomspace(b.f_min_hz, 0.5 / interval_s, 400)
    figures["bound_curve"] = {"f_hz": f_grid, "psd_m2_hz": b.psd(f_grid)}
    if cutoff_info and cutoff_info.get("figure"):
        figures["cutoff_envelope"] = cutoff_figure(cutoff_info["figure"])
    if validation_report is not None:
        figures["jacobi_anger"] = _jacobi_anger(validation_report.expansion)
    if screening is not None:
        figures["screening"] = {
            "roti": screening.roti,
            "threshold_tecu_min": screening.options.roti_threshold_tecu_min,
            "limit_m": screening.limit_m,
            "excluded": [[e.start_gps_s, e.stop_gps_s, e.kind] for e in screening.excluded],
        }
    return figures
