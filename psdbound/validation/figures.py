"""Figures of the cutoff validation (matplotlib, Agg canvas, no pyplot state).

* :func:`plot_expansion`: harmonic power against frequency with the cutoff
  line, one row per geometry and model, one column per phase convention,
  first order in red and second order in black (like thesis figures 4.11
  and 5.5, which show the thesis convention only).
* :func:`plot_direct`: cumulative fraction of power against frequency of the
  direct simulations (and the matching expansion for oscillations), with the
  cutoff and the threshold: the verdict is read where the curve crosses
  ``f_c``.

Each returns a :class:`matplotlib.figure.Figure`; :func:`save_figure`
writes it atomically.
"""

from __future__ import annotations

import io
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from psdbound.common import atomic_write_bytes
from psdbound.validation.geometry import CONVENTION_LABELS
from psdbound.validation.results import DirectCheck, ExpansionCheck

__all__ = ["plot_direct", "plot_expansion", "save_figure"]

_RED, _BLACK, _CUT, _SHADE = "#c0392b", "#111111", "#1f5fbf", "#dbe6f7"


def _new_figure(n_rows: int, n_cols: int, width: float, height: float) -> tuple[Figure, np.ndarray]:
    fig = Figure(figsize=(width * n_cols, height * n_rows), layout="constrained")
    FigureCanvasAgg(fig)
    axes = np.atleast_2d(fig.subplots(n_rows, n_cols, squeeze=False))
    return fig, axes


def _x_limit(check: ExpansionCheck, nyquist_hz: float | None) -> float:
    h = check.second
    f = check.frequencies_hz(h)
    p = h.power_rad2 * (h.orders > 0)
    c = np.cumsum(p) / max(p.sum(), 1e-300)
    top = f[min(np.searchsorted(c, 0.9999), f.size - 1)] * 1.08
    top = max(top, 2.0 * check.cutoff_hz)
    return min(top, nyquist_hz) if nyquist_hz else top


def plot_expansion(checks: Sequence[ExpansionCheck], *, nyquist_hz: float | None = None) -> Figure:
    """Harmonic power of the expansions against frequency, with ``f_c``.

    Parameters
    ----------
    checks : sequence of ExpansionCheck
        Typically both conventions of each geometry.
    nyquist_hz : float, optional
        Right edge of the frequency axis (the thesis uses 1/24 Hz); default:
        where 99.99 % of the power is reached.

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not checks:
        raise ValueError("nothing to plot")
    rows = list(dict.fromkeys((c.model, c.geometry.label) for c in checks))
    cols = list(dict.fromkeys(c.convention for c in checks))
    fig, axes = _new_figure(len(rows), len(cols), 5.2, 3.2)
    for c in checks:
        ax = axes[rows.index((c.model, c.geometry.label)), cols.index(c.convention)]
        total = max(c.first.variance_rad2, 1e-300)
        for h, color, name, mark in (
            (c.first, _RED, "1st order", "o"),
            (c.second, _BLACK, f"1st+2nd order (alpha={c.alpha:g})", "."),
        ):
            keep = h.orders > 0
            f = c.frequencies_hz(h)[keep]
            p = h.power_rad2[keep] / total
            ax.vlines(f, 0.0, p, color=color, lw=0.6, alpha=0.7)
            ax.plot(f, p, mark, color=color, ms=2.5 if mark == "o" else 2.0, label=name)
        ax.axvspan(0.0, c.cutoff_hz, color=_SHADE, zorder=0)
        ax.axvline(c.cutoff_hz, color=_CUT, ls="--", lw=1.0, label=f"f_c = {c.cutoff_hz:.3g} Hz")
        ax.set_xlim(0.0, _x_limit(c, nyquist_hz))
        ax.set_ylim(bottom=0.0)
        osc = ""
        if c.model == "oscillation":
            osc = f", theta={c.theta0_deg:g}+-{c.amplitude_deg:g} deg"
        ax.set_title(
            f"{c.geometry.label} {c.model} ({c.rate.name}{osc})\n{c.convention}: z = {c.z:.1f} rad",
            fontsize=8,
        )
        ax.text(
            0.98,
            0.95,
            f"below f_c: {100 * c.fraction_first_order:.2f} % (1st), "
            f"{100 * c.fraction_second_order:.2f} % (2nd)\n"
            f"threshold {100 * c.threshold:g} %: {'pass' if c.passed else 'FAIL'}",
            transform=ax.transAxes,
            ha="right",
            va="top",
            fontsize=7,
            bbox={"fc": "white", "ec": "0.7", "alpha": 0.9},
        )
        ax.set_xlabel("frequency (Hz)", fontsize=8)
        ax.set_ylabel("harmonic power / total power", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6, loc="center right")
    for j, conv in enumerate(cols):
        axes[-1, j].annotate(
            CONVENTION_LABELS[conv],
            (0.5, -0.32),
            xycoords="axes fraction",
            ha="center",
            fontsize=7,
            color="0.3",
        )
    fig.suptitle("Cutoff validation by Jacobi-Anger expansion", fontsize=10)
    return fig


def _cumulative(f: np.ndarray, p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    keep = f > 0
    f, p = f[keep], p[keep]
    c = np.cumsum(p)
    return f, c / max(c[-1] if c.size else 0.0, 1e-300)


def plot_direct(checks: Sequence[DirectCheck], expansion: Sequence[ExpansionCheck] = ()) -> Figure:
    """Cumulative power fraction of the direct simulations, with ``f_c``.

    Parameters
    ----------
    checks : sequence of DirectCheck
        Direct simulations; one panel per geometry and convention.
    expansion : sequence of ExpansionCheck, optional
        Oscillation expansions to overlay (matched on geometry and
        convention).

    Returns
    -------
    matplotlib.figure.Figure
    """
    if not checks:
        raise ValueError("nothing to plot")
    keys = list(dict.fromkeys((c.geometry.label, c.convention) for c in checks))
    n_cols = 2 if len(keys) > 1 else 1
    n_rows = (len(keys) + n_cols - 1) // n_cols
    fig, axes = _new_figure(n_rows, n_cols, 5.2, 3.2)
    for k, key in enumerate(keys):
        ax = axes[k // n_cols, k % n_cols]
        group = [c for c in checks if (c.geometry.label, c.convention) == key]
        sats = [c for c in group if c.source == "satellite"]
        for c in sats:
            f, cum = _cumulative(c.frequencies_hz, c.psd_rad2_hz)
            ax.semilogx(f, cum, color="0.55", lw=0.5, alpha=0.6)
        if sats:
            fr = np.array([c.fraction_below_cutoff for c in sats])
            ax.plot([], [], color="0.55", lw=0.8, label=f"{len(sats)} satellite passes")
            ax.plot(
                [], [], " ", label=f"median {100 * np.median(fr):.1f} %, max {100 * fr.max():.1f} %"
            )
        for c in group:
            if c.source == "satellite":
                continue
            f, cum = _cumulative(c.frequencies_hz, c.psd_rad2_hz)
            ax.semilogx(f, cum, color=_BLACK, lw=1.2, label=f"direct: {c.label}")
        for e in expansion:
            if (e.geometry.label, e.convention) != key or e.model != "oscillation":
                continue
            f, cum = _cumulative(e.frequencies_hz(), e.second.power_rad2)
            ax.step(
                f, cum, where="post", color=_RED, lw=1.0, ls="--", label="expansion (2nd order)"
            )
        c0 = group[0]
        ax.axvline(c0.cutoff_hz, color=_CUT, ls="--", lw=1.0, label=f"f_c = {c0.cutoff_hz:.3g} Hz")
        ax.axhline(
            c0.threshold,
            color="#7f8c8d",
            ls=":",
            lw=1.0,
            label=f"threshold {100 * c0.threshold:g} %",
        )
        ax.set_ylim(0.0, 1.02)
        ax.set_title(f"{key[0]}, {key[1]} convention (alpha={c0.alpha:g})", fontsize=8)
        ax.set_xlabel("frequency (Hz)", fontsize=8)
        ax.set_ylabel("fraction of power below f", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=6, loc="upper left")
    for k in range(len(keys), n_rows * n_cols):
        axes[k // n_cols, k % n_cols].set_visible(False)
    fig.suptitle("Direct simulation of the exact phase error", fontsize=10)
    return fig


def save_figure(fig: Figure, path: str | os.PathLike[str], *, dpi: int = 130) -> Path:
    """Write a figure as PNG atomically (:func:`psdbound.common.atomic_write_bytes`).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    path : str or path-like
        Destination ``.png``.
    dpi : int, default 130
        Resolution.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return atomic_write_bytes(path, buf.getvalue())
