"""Figures of the cutoff selection (matplotlib, Agg backend).

* :func:`plot_series_psd`: one series' LS PSD with its local maxima, upper
  envelope, reference and 40 dB lines and f_c (like thesis figure 4.9).
* :func:`plot_station_envelopes`: every series' envelope of a station-year,
  with the mean and maximum f_c (like thesis figure 4.10, right).
* :func:`plot_residual_curves`: the residual criterion of a station-year:
  every series' residual ionosphere after the fit's high-pass against the
  cutoff, the threshold, the mean and maximum f_c.
* :func:`plot_cutoff_map`: recommended f_c of each station on a plain
  latitude/longitude plot (no coastlines).
* :func:`plot_world_map`: the cutoff map document, one panel per solar
  activity layer (grid cells and reference stations).

Each function writes a PNG atomically (:func:`psdbound.common.atomic_write_bytes`)
and returns its path.
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from psdbound.common import atomic_write_bytes
from psdbound.ionosphere.cutoff import SeriesCutoff
from psdbound.ionosphere.envelope import Envelope, local_maxima

__all__ = [
    "plot_cutoff_map",
    "plot_residual_curves",
    "plot_series_psd",
    "plot_station_envelopes",
    "plot_world_map",
]


def _figure(size: tuple[float, float]):  # noqa: ANN202
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    return Figure(figsize=size, layout="constrained")


def _save(fig, path: str | os.PathLike[str]) -> Path:  # noqa: ANN001
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110)
    return atomic_write_bytes(path, buf.getvalue())


def plot_series_psd(result: SeriesCutoff, path: str | os.PathLike[str], *, title: str = "") -> Path:
    """Plot one series' LS PSD, local maxima, envelope, thresholds and f_c.

    Parameters
    ----------
    result : SeriesCutoff
        A result computed with ``keep_spectrum=True``.
    path : str or path-like
        PNG to write.
    title : str, optional
        Figure title (e.g. satellite and date).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    if result.frequency_hz is None or result.psd_m2_hz is None:
        raise ValueError("the result holds no spectrum; compute it with keep_spectrum=True")
    f, p = result.frequency_hz, result.psd_m2_hz
    fig = _figure((8.0, 5.0))
    ax = fig.add_subplot()
    ax.loglog(f, p, color="0.7", lw=0.4, label="LS PSD (7 sidereal days)")
    i = local_maxima(p)
    ax.loglog(f[i], p[i], "kx", ms=2.5, mew=0.6, label=f"local maxima ({i.size})")
    ax.loglog(f, result.envelope(f), color="tab:green", lw=1.6, label="envelope (quantile fit)")
    if result.criterion == "relative":
        ax.axhline(result.reference_m2_hz, color="tab:red", ls=":", lw=1.0, label="reference")
        drop = result.settings.get("drop_db", 40.0)
        ax.axhline(
            result.threshold_m2_hz, color="tab:red", ls="--", lw=1.2, label=f"{drop:g} dB line"
        )
    ax.axvline(
        result.f_c_hz,
        color="tab:blue",
        lw=1.4,
        label=f"f_c = {result.f_c_hz:.3g} Hz ({result.tau_c_min:.1f} min)",
    )
    top = max(float(np.max(p)), result.reference_m2_hz if result.criterion == "relative" else 0)
    ax.set_ylim(top * 1e-9, top * 10.0)
    ax.set_xlim(f[0], f[-1])
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("one-sided PSD (m$^2$/Hz)")
    ax.set_title(title or "Lomb-Scargle PSD and upper envelope")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return _save(fig, path)


def plot_station_envelopes(
    envelopes: Sequence[Envelope],
    f_c_hz: Sequence[float],
    path: str | os.PathLike[str],
    *,
    f_range_hz: tuple[float, float],
    title: str = "",
    normalise: bool = True,
    reference_m2_hz: Sequence[float] | None = None,
) -> Path:
    """Overlay every series' envelope with the mean and maximum f_c.

    Parameters
    ----------
    envelopes : sequence of Envelope
        One per series.
    f_c_hz : sequence of float
        The series' cutoffs, Hz.
    path : str or path-like
        PNG to write.
    f_range_hz : (float, float)
        Frequency axis range, Hz.
    title : str, optional
        Figure title.
    normalise : bool, default True
        Show each envelope in dB relative to its series' reference level
        (``reference_m2_hz``) or, without one, to the envelope's own peak:
        what the relative criterion compares.
    reference_m2_hz : sequence of float, optional
        Per-series reference levels of the relative criterion.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    fig = _figure((8.0, 5.0))
    ax = fig.add_subplot()
    f = np.geomspace(f_range_hz[0], f_range_hz[1], 600)
    for k, env in enumerate(envelopes):
        e = env.log10(f)
        inside = (f >= env.f_min_hz) & (f <= env.f_max_hz)
        ref = 0.0
        if normalise and reference_m2_hz is not None and np.isfinite(reference_m2_hz[k]):
            ref = float(np.log10(reference_m2_hz[k]))
        elif normalise and inside.any():
            ref = float(e[inside].max())
        ax.semilogx(f[inside], 10.0 * (e[inside] - ref), color="tab:green", lw=0.4, alpha=0.5)
    fc = np.asarray(f_c_hz, dtype=float)
    if normalise:
        ax.axhline(-40.0, color="tab:red", ls="--", lw=1.2, label="-40 dB (relative criterion)")
        ax.set_ylim(-80, 10)
    ax.axvline(np.mean(fc), color="tab:blue", lw=1.2, label=f"mean f_c {np.mean(fc):.3g} Hz")
    ax.axvline(np.max(fc), color="tab:purple", lw=1.4, label=f"max f_c {np.max(fc):.3g} Hz")
    ax.axvline(np.min(fc), color="tab:cyan", lw=1.0, label=f"min f_c {np.min(fc):.3g} Hz")
    ax.set_xlabel("frequency (Hz)")
    ax.set_ylabel("envelope relative to reference (dB)" if normalise else "log10 envelope")
    ax.set_title(title or f"Upper envelopes of {len(envelopes)} series")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    return _save(fig, path)


def plot_residual_curves(
    curves: Sequence[tuple[Sequence[float], Sequence[float]]],
    f_c_hz: Sequence[float],
    threshold_m: float,
    path: str | os.PathLike[str],
    *,
    reference_hz: float | None = None,
    title: str = "",
) -> Path:
    """Residual ionosphere after the fit's high-pass against the cutoff, every series.

    Parameters
    ----------
    curves : sequence of (frequencies, residuals)
        Per series, the scanned cutoffs (Hz) and residual RMS (m).
    f_c_hz : sequence of float
        Per series, its cutoff, Hz (the mean and maximum are drawn).
    threshold_m : float
        The criterion's threshold, m.
    path : str or path-like
        PNG to write.
    reference_hz : float, optional
        A cutoff to mark for comparison (e.g. the thesis's 9.55e-4 Hz).
    title : str, optional
        Figure title.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    fig = _figure((8.0, 5.0))
    ax = fig.add_subplot()
    for f, r in curves:
        r = np.asarray(r, dtype=float)
        ok = r > 0
        ax.loglog(np.asarray(f, dtype=float)[ok], 1e3 * r[ok], color="0.6", lw=0.5, alpha=0.5)
    ax.axhline(1e3 * threshold_m, color="r", lw=1.2, label=f"threshold {1e3 * threshold_m:.3g} mm")
    fc = np.asarray(f_c_hz, dtype=float)
    ax.axvline(fc.mean(), color="b", ls="--", lw=1, label=f"mean f_c {fc.mean():.3g} Hz")
    ax.axvline(fc.max(), color="b", lw=1.5, label=f"max f_c {fc.max():.3g} Hz (recommended)")
    if reference_hz is not None:
        ax.axvline(reference_hz, color="k", ls=":", lw=1, label=f"thesis {reference_hz:.3g} Hz")
    ax.set_xlabel("high-pass cutoff f_c (Hz)")
    ax.set_ylabel("residual ionosphere RMS in the fit's series (mm)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title or "Residual criterion")
    return _save(fig, path)


def plot_cutoff_map(
    names: Sequence[str],
    lat_deg: Sequence[float],
    lon_deg: Sequence[float],
    f_c_hz: Sequence[float],
    path: str | os.PathLike[str],
    *,
    title: str = "",
) -> Path:
    """World scatter of recommended cutoff frequencies (plain lat/lon axes).

    Parameters
    ----------
    names : sequence of str
        Station names (annotated).
    lat_deg, lon_deg : sequence of float
        Station positions, degrees.
    f_c_hz : sequence of float
        Recommended cutoff per station, Hz (colour, log scale).
    path : str or path-like
        PNG to write.
    title : str, optional
        Figure title.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    from matplotlib.colors import LogNorm

    fig = _figure((10.0, 5.4))
    ax = fig.add_subplot()
    fc = np.asarray(f_c_hz, dtype=float)
    ok = np.isfinite(fc) & (fc > 0)
    norm = LogNorm(vmin=fc[ok].min(), vmax=fc[ok].max()) if ok.any() else None
    sc = ax.scatter(
        np.asarray(lon_deg)[ok],
        np.asarray(lat_deg)[ok],
        c=fc[ok],
        cmap="viridis",
        norm=norm,
        s=70,
        edgecolors="k",
    )
    for n, la, lo, v in zip(names, lat_deg, lon_deg, fc, strict=True):
        label = f"{n}\n{v:.2e}" if np.isfinite(v) else f"{n}\n(no data)"
        ax.annotate(label, (lo, la), xytext=(4, 4), textcoords="offset points", fontsize=7)
    ax.set_xlim(-180, 180)
    ax.set_ylim(-90, 90)
    ax.set_xticks(range(-180, 181, 60))
    ax.set_yticks(range(-90, 91, 30))
    ax.set_xlabel("longitude (deg)")
    ax.set_ylabel("latitude (deg)")
    ax.grid(True, alpha=0.3)
    ax.set_aspect("equal")
    if ok.any():
        fig.colorbar(sc, ax=ax, label="recommended f_c (Hz)", shrink=0.8)
    ax.set_title(title or "Ionosphere high-pass cutoff by station")
    return _save(fig, path)


def plot_world_map(doc: dict, path: str | os.PathLike[str]) -> Path:
    """Plot the cutoff map: one panel per layer, grid nodes shaded, stations marked.

    Parameters
    ----------
    doc : dict
        A map document (:func:`psdbound.ionosphere.worldmap.load_map`).
    path : str or path-like
        PNG to write.

    Returns
    -------
    pathlib.Path
        The file written.
    """
    from matplotlib.colors import LogNorm

    layers = doc["layers"]
    lat = np.asarray(doc["grid"]["lat_deg"], dtype=float)
    lon = np.asarray(doc["grid"]["lon_deg"], dtype=float)
    dlat, dlon = doc["grid"]["lat_step_deg"], doc["grid"]["lon_step_deg"]
    fields = [np.array(la["grid"]["recommended_f_c_hz"], dtype=float) for la in layers]
    every = np.concatenate([f[np.isfinite(f)] for f in fields])
    norm = LogNorm(vmin=every.min(), vmax=every.max())
    fig = _figure((10.0, 4.6 * len(layers)))
    for k, (layer, f) in enumerate(zip(layers, fields, strict=True)):
        ax = fig.add_subplot(len(layers), 1, k + 1)
        # cells are centred on the nodes; repeat the first column past 180 deg (periodic)
        lon_w = np.append(lon, lon[0] + 360.0)
        f_w = np.hstack([f, f[:, :1]])
        edges_lon = np.append(lon_w - dlon / 2, lon_w[-1] + dlon / 2)
        edges_lat = np.append(lat - dlat / 2, lat[-1] + dlat / 2)
        mesh = ax.pcolormesh(edges_lon, edges_lat, f_w, norm=norm, cmap="viridis", shading="flat")
        for st in layer["stations"]:
            v = st["recommended_f_c_hz"]
            ax.scatter(
                [st["lon_deg"]],
                [st["lat_deg"]],
                c=[v],
                norm=norm,
                cmap="viridis",
                edgecolors="w",
                s=45,
            )
            ax.annotate(
                st["name"],
                (st["lon_deg"], st["lat_deg"]),
                xytext=(3, 3),
                textcoords="offset points",
                fontsize=6,
                color="w",
            )
        ax.set_xlim(-180, 180)
        ax.set_ylim(-90, 90)
        ax.set_aspect("equal")
        ax.set_ylabel("latitude (deg)")
        ax.set_title(
            f"{layer['name']} ({layer['year']}, F10.7 {layer['f107_sfu']:.0f} sfu): recommended "
            f"f_c, {doc['criterion']['name']} criterion"
        )
        fig.colorbar(mesh, ax=ax, label="f_c (Hz)", shrink=0.85)
    ax.set_xlabel("longitude (deg)")
    return _save(fig, path)
