"""Report figures against frequency: PSDs and bound, tau search, cutoff, Jacobi-Anger.

Each function takes the result document and returns a
:class:`~matplotlib.figure.Figure` or None when the document holds no data
for it.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from psdbound.reports.figures_base import finish, new_figure

__all__ = [
    "cutoff_curves",
    "fig_cutoff_envelope",
    "fig_jacobi_anger",
    "fig_psds_bound",
    "fig_tau_search",
]


def _passband_start_hz(r: dict[str, Any]) -> float | None:
    """Lower edge of the bound's band (the filter's passband start), Hz; None without a filter."""
    fc = r["cutoff"].get("f_c_hz")
    if not fc:
        return None
    band = r["bound"].get("band_hz")
    lo = float(band[0]) if band else float(r["figures"]["bound_curve"]["f_hz"][0])
    return max(lo, float(fc))


def fig_psds_bound(r: dict[str, Any]) -> Figure | None:
    """Every window's PSD estimate, the pooled limits and the bound, with Nyquist and the cutoff.

    With a high-pass (dual-frequency), the band below the filter's passband
    is shaded: below f_c the filter removes the signal, between f_c and the
    bound's band start it attenuates it; the bound says nothing there.
    """
    psds = r["figures"].get("psds") or []
    bc = r["figures"].get("bound_curve")
    if not psds or not bc:
        return None
    fig = new_figure(4.8)
    ax = fig.add_subplot()
    f_lo = min(min(p["f_hz"][0] for p in psds if p["f_hz"]), bc["f_hz"][0])
    b = r["bound"]
    _plot_psds_and_bound(ax, psds, bc, b)
    _plot_pooled_limits(ax, b)
    _plot_truth(ax, r)
    nyq = r["sampling"]["nyquist_hz"]
    ax.axvline(nyq, color="k", ls=":", lw=1, label=f"Nyquist {nyq:.3g} Hz")
    x0 = _shade_filter_bands(ax, r, min(f_lo, nyq) / 1.2)
    ax.set_xlim(x0, nyq * 1.2)
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("one-sided PSD [m²/Hz]")
    ax.set_title(
        f"{r['windows']['count']} window PSDs ({b['estimator']}) and the "
        f"{b.get('rule', 'envelope')} bound",
        fontsize=9,
    )
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(alpha=0.3, which="both")
    return finish(fig)


def _plot_psds_and_bound(
    ax: Axes, psds: list[dict[str, Any]], bc: dict[str, Any], b: dict[str, Any]
) -> None:
    """Draw every window's PSD estimate and the bound's curve."""
    for p in psds:
        ax.loglog(p["f_hz"], p["psd_m2_hz"], color="0.6", lw=0.4, alpha=0.6)
    ax.loglog(
        bc["f_hz"],
        bc["psd_m2_hz"],
        color="C3",
        lw=2.2,
        label=f"bound: sigma_GM {100 * b['sigma_gm_m']:.2f} cm, tau {b['tau_s']:.0f} s, "
        f"sigma_WN {100 * b['sigma_wn_m']:.2f} cm",
    )


def _plot_pooled_limits(ax: Axes, b: dict[str, Any]) -> None:
    """Draw the pooled upper limits of every group of windows (none without pooling)."""
    pooled = b.get("pooled")
    if not pooled:
        return
    up = np.atleast_2d(np.asarray(pooled["upper_m2_hz"], dtype=float))
    for k, row in enumerate(up):
        ax.loglog(
            pooled["band_centres_hz"],
            row,
            "v",
            color="C1",
            ms=4,
            label=(
                f"pooled {100 * b['confidence_level']:g} % limits ({pooled['n_groups']} group(s))"
                if k == 0
                else None
            ),
        )


def _plot_truth(ax: Axes, r: dict[str, Any]) -> None:
    """Draw the injected truth of a demo run (nothing for other runs)."""
    truth = r.get("demo", {}).get("truth_curve")
    if not truth:
        return
    ax.loglog(
        truth["f_hz"],
        truth["psd_m2_hz"],
        color="C2",
        lw=1.6,
        ls="--",
        label="injected truth (demo)",
    )


def _shade_filter_bands(ax: Axes, r: dict[str, Any], x0: float) -> float:
    """Mark f_c and shade the bands the high-pass removes or attenuates; return the left x limit.

    ``x0`` is the left limit without a filter; with one it extends to ``f_c / 2``.
    """
    fc = r["cutoff"].get("f_c_hz")
    start = _passband_start_hz(r)
    if not (fc and start):
        return x0
    ax.axvline(fc, color="C0", ls="--", lw=1, label=f"f_c {fc:.3g} Hz")
    x0 = min(x0, fc / 2)
    ax.axvspan(
        x0,
        fc,
        color="0.55",
        alpha=0.25,
        lw=0,
        gid="stopband",
        label="f < f_c: removed by the high-pass (not bounded)",
    )
    if start > fc * 1.0001:
        ax.axvspan(
            fc,
            start,
            color="0.55",
            alpha=0.12,
            lw=0,
            gid="transition",
            label=f"f_c to {start:.3g} Hz: attenuated by the filter, outside the bound's band",
        )
    return x0


def fig_tau_search(r: dict[str, Any]) -> Figure | None:
    """Plot the bound objective (LP optimum) as a function of tau."""
    b = r["bound"]
    if not b.get("tau_grid_s"):
        return None
    fig = new_figure(3.0)
    ax = fig.add_subplot()
    ax.loglog(b["tau_grid_s"], b["objective_grid_m2"], ".-")
    ax.axvline(b["tau_s"], color="C3", ls="--", label=f"optimum tau {b['tau_s']:.1f} s")
    ax.set_xlabel("Gauss-Markov time constant tau [s]")
    ax.set_ylabel(f"{b['objective']} objective [m²]")
    ax.set_title("tightest bound for each tau (linear program)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return finish(fig)


def cutoff_curves(r: dict[str, Any]) -> dict[str, Any] | None:
    """Return the data of the cutoff figure, from whichever fields the document has.

    In order: ``figures.cutoff_envelope`` (full curves: the residual
    criterion's residual against the cutoff, or a Lomb-Scargle PSD with its
    envelope), then the residual criterion at its recorded margins
    (``cutoff.by_margin`` for the map, ``cutoff.computed.by_margin`` for a
    computed cutoff). None for a given or the thesis's cutoff, and without
    a filter (dual-antenna).

    Returns
    -------
    dict or None
        ``{"kind": "residual" | "envelope", ...}`` with the arrays to draw.
    """
    c = r["cutoff"]
    if not c.get("f_c_hz"):
        return None
    d = r["figures"].get("cutoff_envelope")
    if d:
        if "residual_m" in d:
            return {
                "kind": "residual",
                "f_hz": d["f_hz"],
                "residual_m": d["residual_m"],
                "curves": d.get("curves", []),
                "threshold_m": d.get("threshold_m", c.get("criterion", {}).get("threshold_m")),
                "label": d.get("label", "residual ionosphere (criterion)"),
            }
        psd = d.get("psd_m2_hz", d.get("psd"))
        if psd is not None:
            return {
                "kind": "envelope",
                "f_hz": d["f_hz"],
                "psd_m2_hz": psd,
                "envelope_m2_hz": d.get("envelope_m2_hz", d.get("envelope")),
                "maxima_f_hz": d.get("maxima_f_hz"),
                "maxima_psd_m2_hz": d.get("maxima_psd_m2_hz", d.get("maxima_psd")),
                "threshold_m2_hz": d.get("threshold_m2_hz", d.get("threshold")),
                "reference_m2_hz": d.get("reference_m2_hz"),
                "drop_db": d.get("drop_db", 40.0),
            }
    comp = c.get("computed") if isinstance(c.get("computed"), dict) else {}
    rows = c.get("by_margin") or comp.get("by_margin")
    if rows:
        rows = sorted(rows, key=lambda x: x["threshold_m"])
        f = [x.get("f_c_hz", x.get("max_f_c_hz")) for x in rows]
        crit = c.get("criterion") or {}
        thr = crit.get("threshold_m", comp.get("threshold_m"))
        label = (
            "cutoff map at the receiver"
            if c.get("by_margin")
            else f"computed: max over {comp.get('n_series', '?')} series"
        )
        out = {
            "kind": "residual",
            "f_hz": f,
            "residual_m": [x["threshold_m"] for x in rows],
            "threshold_m": thr,
            "label": label,
            "curves": [],
        }
        if all("mean_f_c_hz" in x for x in rows):
            out["mean_f_hz"] = [x["mean_f_c_hz"] for x in rows]
        return out
    return None


def fig_cutoff_envelope(r: dict[str, Any]) -> Figure | None:
    """Plot the cutoff criterion and f_c.

    Residual criterion (the map and computed cutoffs): the residual
    ionosphere RMS the fit's high-pass leaves against the cutoff, the
    criterion's level (``margin_db`` below ``mp_sigma_m``) and f_c, where
    the curve crosses the level. Lomb-Scargle criterion: the PSD, its local
    maxima and upper envelope, the peak - 40 dB line and f_c.
    """
    d = cutoff_curves(r)
    if d is None:
        return None
    c = r["cutoff"]
    fc = float(c["f_c_hz"])
    fig = new_figure(3.9)
    ax = fig.add_subplot()
    if d["kind"] == "residual":
        for cur in d.get("curves") or []:
            rr = np.asarray(cur["residual_m"], dtype=float)
            ok = rr > 0
            ax.loglog(
                np.asarray(cur["f_hz"], dtype=float)[ok],
                1e3 * rr[ok],
                color="0.65",
                lw=0.5,
                alpha=0.5,
            )
        f = np.asarray(d["f_hz"], dtype=float)
        rr = np.asarray(d["residual_m"], dtype=float)
        ok = (rr > 0) & (f > 0)
        ax.loglog(f[ok], 1e3 * rr[ok], "o-", color="C3", ms=3.5, lw=1.5, label=d["label"])
        if d.get("mean_f_hz"):
            ax.loglog(
                np.asarray(d["mean_f_hz"])[ok],
                1e3 * rr[ok],
                "s--",
                color="C1",
                ms=3,
                lw=1,
                label="mean over the series",
            )
        thr = d.get("threshold_m")
        if thr:
            crit = c.get("criterion") or {}
            what = (
                f"{crit['margin_db']:g} dB below {1e3 * crit['mp_sigma_m']:g} mm"
                if "margin_db" in crit and "mp_sigma_m" in crit
                else "criterion"
            )
            ax.axhline(
                1e3 * thr, color="C2", ls=":", lw=1.5, label=f"level {1e3 * thr:.3g} mm ({what})"
            )
        ax.set_xlabel("high-pass cutoff [Hz]")
        ax.set_ylabel("residual ionosphere RMS [mm]")
        ax.set_title(
            "Residual criterion: ionosphere the high-pass leaves, against the cutoff", fontsize=9
        )
    else:
        ax.loglog(d["f_hz"], d["psd_m2_hz"], color="0.5", lw=0.6, label="Lomb-Scargle PSD")
        if d.get("maxima_f_hz") and d.get("maxima_psd_m2_hz"):
            ax.loglog(d["maxima_f_hz"], d["maxima_psd_m2_hz"], "k.", ms=2.5, label="local maxima")
        if d.get("envelope_m2_hz"):
            ax.loglog(d["f_hz"], d["envelope_m2_hz"], color="C3", lw=1.5, label="upper envelope")
        if d.get("reference_m2_hz"):
            ax.axhline(d["reference_m2_hz"], color="C2", ls="--", lw=1, label="reference")
        if d.get("threshold_m2_hz"):
            ax.axhline(
                d["threshold_m2_hz"],
                color="C2",
                ls=":",
                lw=1.5,
                label=f"reference - {d['drop_db']:g} dB",
            )
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel("one-sided PSD [m²/Hz]")
        ax.set_title("Lomb-Scargle PSD of the ionosphere, its envelope and the cutoff", fontsize=9)
    ax.axvline(
        fc,
        color="C0",
        ls="--",
        lw=1.2,
        label=f"f_c {fc:.3g} Hz ({str(c['source']).split(' (')[0]})",
    )
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    return finish(fig)


def fig_jacobi_anger(r: dict[str, Any]) -> Figure | None:
    """Predicted multipath harmonic power vs frequency with the cutoff (both conventions)."""
    d = r["figures"].get("jacobi_anger")
    if not d:
        return None
    cases = d.get("cases", [])
    if not cases:
        return None
    fig = new_figure(2.1 * len(cases) + 0.5)
    axes = fig.subplots(len(cases), 1, squeeze=False, sharex=True)[:, 0]
    fc = r["cutoff"]["f_c_hz"]
    for ax, c in zip(axes, cases, strict=True):
        for conv, style in (("physical", "C3"), ("thesis", "C0")):
            if conv in c:
                ax.semilogx(
                    c[conv]["f_hz"],
                    c[conv]["power"],
                    ".",
                    color=style,
                    ms=3,
                    label=f"{conv}: {100 * c[conv]['fraction_below']:.1f} % below f_c",
                )
        if fc:
            ax.axvline(fc, color="k", ls="--", lw=1)
        ax.set_title(c.get("label", ""), fontsize=8)
        ax.set_ylabel("harmonic power [rad²]")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
    axes[-1].set_xlabel("harmonic frequency [Hz]")
    return finish(fig)
