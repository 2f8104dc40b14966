"""Report figures, drawn from a result document alone (``result.json``).

Every function takes the result ``dict`` and returns a matplotlib
:class:`~matplotlib.figure.Figure` (Agg backend), or None when the result
holds no data for that figure.
"""

from __future__ import annotations

from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

__all__ = [
    "FIGURES",
    "fig_arcs",
    "fig_df_filter",
    "fig_mapped_windows",
    "fig_psds_bound",
    "fig_tau_search",
    "fig_cutoff_envelope",
    "fig_jacobi_anger",
    "fig_screening",
]


def _t0(r: dict[str, Any]) -> float:
    """Time origin of the figures: the first epoch of the observations."""
    return float(r["figures"].get("t_ref_gps_s", r["data_span"]["start_gps_s"]))


def fig_arcs(r: dict[str, Any]) -> Figure | None:
    """Arc timeline: one bar per arc and satellite (hours from the data start)."""
    arcs = r["figures"].get("arcs") or []
    if not arcs:
        return None
    t0 = _t0(r)
    sats = sorted({a["sat"] for a in arcs})
    fig, ax = plt.subplots(figsize=(9, 0.25 * len(sats) + 1.6))
    for a in arcs:
        y = sats.index(a["sat"])
        ax.plot([(a["t0"] - t0) / 3600, (a["t1"] - t0) / 3600], [y, y], lw=5, solid_capstyle="butt")
    ax.set_yticks(range(len(sats)), sats, fontsize=7)
    ax.set_xlabel("time since data start [h]")
    ax.set_title(f"{len(arcs)} arcs used ({r['method']})")
    ax.grid(axis="x", alpha=0.3)
    fig.tight_layout()
    return fig


def fig_df_filter(r: dict[str, Any]) -> Figure | None:
    """Dual-frequency difference before and after the high-pass filter (one arc)."""
    d = r["figures"].get("df_filter")
    if not d:
        return None
    t = (np.asarray(d["t_gps_s"]) - d["t_gps_s"][0]) / 60.0
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 5), sharex=True)
    a1.plot(t, 100 * np.asarray(d["unfiltered_m"]), lw=0.8)
    a1.set_ylabel("L1-L2, mean removed [cm]")
    a1.set_title(
        f"{d['sat']}: before and after the high-pass filter at "
        f"{r['cutoff']['f_c_hz']:.3g} Hz ({r['cutoff']['source']})"
    )
    a2.plot(t, 1000 * np.asarray(d["filtered_m"]), lw=0.6, color="C1")
    a2.set_ylabel("filtered [mm]")
    a2.set_xlabel("time since arc start [min]")
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def fig_mapped_windows(r: dict[str, Any]) -> Figure | None:
    """Plot the mapped residuals of every arc with the stationary windows marked."""
    mapped = r["figures"].get("mapped") or []
    if not mapped:
        return None
    t0 = _t0(r)
    fig, (a1, a2) = plt.subplots(
        2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [3, 2]}
    )
    for m in mapped:
        a1.plot((np.asarray(m["t_gps_s"]) - t0) / 3600, 1000 * np.asarray(m["mapped_m"]),
                lw=0.4)  # fmt: skip
    a1.set_ylabel("mapped multipath [mm]")
    mp = r["mapping"]
    a1.set_title(
        f"elevation-mapped residuals; mapping {mp['source']}: a={mp['a']:.3g}, "
        f"b={mp['b']:.3g}, c={mp['c_deg']:.3g} deg"
    )
    wins = r["windows"]["per_window"]
    for k, w in enumerate(wins):
        a2.plot([(w["t_start_gps_s"] - t0) / 3600, (w["t_stop_gps_s"] - t0) / 3600], [k, k],
                lw=1.2, color="C2")  # fmt: skip
    for u in r["windows"].get("never_stationary", []):
        a2.axvspan((u[2] - t0) / 3600, (u[3] - t0) / 3600, color="C3", alpha=0.15, lw=0)
    a2.set_ylabel("window #")
    a2.set_xlabel("time since data start [h]")
    a2.set_title(
        f"{len(wins)} stationary windows (green); never stationary (red): "
        f"{r['windows']['never_stationary_s'] / 60:.1f} min"
    )
    for a in (a1, a2):
        a.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def fig_psds_bound(r: dict[str, Any]) -> Figure | None:
    """Every window's PSD under the fitted bound, with Nyquist and the cutoff."""
    psds = r["figures"].get("psds") or []
    bc = r["figures"].get("bound_curve")
    if not psds or not bc:
        return None
    fig, ax = plt.subplots(figsize=(9, 5.5))
    for p in psds:
        ax.loglog(p["f_hz"], p["psd_m2_hz"], color="0.6", lw=0.4, alpha=0.6)
    b = r["bound"]
    ax.loglog(bc["f_hz"], bc["psd_m2_hz"], color="C3", lw=2.2,
              label=f"bound: sigma_GM {100 * b['sigma_gm_m']:.2f} cm, tau {b['tau_s']:.0f} s, "
              f"sigma_WN {100 * b['sigma_wn_m']:.2f} cm")  # fmt: skip
    pooled = b.get("pooled")
    if pooled:
        up = np.atleast_2d(np.asarray(pooled["upper_m2_hz"], dtype=float))
        for k, row in enumerate(up):
            ax.loglog(pooled["band_centres_hz"], row, "v", color="C1", ms=5,
                      label=(f"pooled {100 * b['confidence_level']:g} % limits "
                             f"({pooled['n_groups']} group(s))" if k == 0 else None))  # fmt: skip
    truth = r.get("demo", {}).get("truth_curve")
    if truth:
        ax.loglog(truth["f_hz"], truth["psd_m2_hz"], color="C2", lw=1.6, ls="--",
                  label="injected truth (demo)")  # fmt: skip
    nyq = r["sampling"]["nyquist_hz"]
    ax.axvline(nyq, color="k", ls=":", lw=1, label=f"Nyquist {nyq:.3g} Hz")
    fc = r["cutoff"]["f_c_hz"]
    if fc:
        ax.axvline(fc, color="C0", ls="--", lw=1, label=f"f_c {fc:.3g} Hz")
        lo = bc["f_hz"][0]
        if lo > fc:
            ax.axvspan(ax.get_xlim()[0], lo, color="0.85", alpha=0.5, lw=0,
                       label="filter attenuates (not bounded)")  # fmt: skip
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("one-sided PSD [m^2/Hz]")
    ax.set_title(
        f"{len(psds)} window PSDs ({b['estimator']}) and the {b.get('rule', 'envelope')} bound"
    )
    ax.legend(fontsize=8, loc="lower left")
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def fig_tau_search(r: dict[str, Any]) -> Figure | None:
    """Plot the bound objective (LP optimum) as a function of tau."""
    b = r["bound"]
    if not b.get("tau_grid_s"):
        return None
    fig, ax = plt.subplots(figsize=(7, 3.5))
    ax.loglog(b["tau_grid_s"], b["objective_grid_m2"], ".-")
    ax.axvline(b["tau_s"], color="C3", ls="--", label=f"optimum tau {b['tau_s']:.1f} s")
    ax.set_xlabel("tau [s]")
    ax.set_ylabel(f"{b['objective']} objective [m^2]")
    ax.set_title("tightest bound for each tau (linear program)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def fig_cutoff_envelope(r: dict[str, Any]) -> Figure | None:
    """Lomb-Scargle PSD of the ionosphere, its envelope, the 40 dB line and f_c."""
    d = r["figures"].get("cutoff_envelope")
    if not d:
        return None
    fig, ax = plt.subplots(figsize=(9, 5))
    ax.loglog(d["f_hz"], d["psd"], color="0.5", lw=0.6, label="Lomb-Scargle PSD")
    if "maxima_f_hz" in d:
        ax.loglog(d["maxima_f_hz"], d["maxima_psd"], ".", ms=3, label="local maxima")
    if "envelope" in d:
        ax.loglog(d["f_hz"], d["envelope"], color="C3", lw=1.5, label="envelope")
    if "threshold" in d:
        ax.axhline(d["threshold"], color="C2", ls=":", label="peak - 40 dB")
    ax.axvline(r["cutoff"]["f_c_hz"], color="C0", ls="--", label="f_c")
    ax.set_xlabel("frequency [Hz]")
    ax.set_ylabel("PSD")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    return fig


def fig_jacobi_anger(r: dict[str, Any]) -> Figure | None:
    """Predicted multipath harmonic power vs frequency with the cutoff (both conventions)."""
    d = r["figures"].get("jacobi_anger")
    if not d:
        return None
    cases = d.get("cases", [])
    if not cases:
        return None
    fig, axes = plt.subplots(len(cases), 1, figsize=(9, 2.6 * len(cases) + 0.5), squeeze=False)
    fc = r["cutoff"]["f_c_hz"]
    for ax, c in zip(axes[:, 0], cases, strict=True):
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
        ax.set_title(c.get("label", ""), fontsize=9)
        ax.set_ylabel("harmonic power")
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3, which="both")
    axes[-1, 0].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    return fig


def fig_screening(r: dict[str, Any]) -> Figure | None:
    """Screening: normalised ROTI and the largest isolated value per 5-min block.

    Top: ROTI over its threshold (1 = the threshold); bottom: the largest
    absolute isolated value of each block against the carrier-multipath
    limit. Excluded blocks are orange, kept blocks blue; time in hours from
    the data start.
    """
    d = r["figures"].get("screening")
    if not d or not d.get("roti"):
        return None

    def arr(x: Any) -> np.ndarray:
        return np.asarray([np.nan if v is None else v for v in x], dtype=float)

    t0 = _t0(r)
    t = np.concatenate([arr(a["t_gps_s"]) for a in d["roti"]])
    t = (t - t0) / 3600.0
    ratio = np.concatenate([arr(a["roti_tecu_min"]) / arr(a["threshold_tecu_min"])
                            for a in d["roti"]])  # fmt: skip
    vmax = np.concatenate([arr(a.get("value_max_m", [])) for a in d["roti"]])
    exc = np.concatenate([np.asarray(a.get("excluded", []), dtype=bool) for a in d["roti"]])
    has_roti = bool(np.any(np.isfinite(ratio)))
    fig, axes = plt.subplots(2 if has_roti else 1, 1, figsize=(9, 5.2 if has_roti else 2.8),
                             sharex=True, squeeze=False)  # fmt: skip
    axes = axes[:, 0]
    if has_roti:
        ax = axes[0]
        ax.semilogy(t[~exc], ratio[~exc], ".", ms=2.5, color="tab:blue", label="kept")
        ax.semilogy(t[exc], ratio[exc], ".", ms=2.5, color="tab:orange", label="excluded")
        ax.axhline(1.0, color="tab:red", lw=1,
                   label=f"threshold {d['threshold_tecu_min']:g} TECU/min x m(el)")  # fmt: skip
        ax.set_ylabel("ROTI / threshold [-]")
        ax.legend(fontsize=7, loc="upper right", ncol=3)
        ax.grid(alpha=0.3, which="both")
    ax = axes[-1]
    if vmax.size:
        ax.semilogy(t[~exc], 100 * vmax[~exc], ".", ms=2.5, color="tab:blue")
        ax.semilogy(t[exc], 100 * vmax[exc], ".", ms=2.5, color="tab:orange")
    ax.axhline(100 * d["limit_m"], color="tab:red", lw=1,
               label=f"carrier-multipath limit {100 * d['limit_m']:.2f} cm")  # fmt: skip
    ax.set_ylabel("largest |isolated value| [cm]")
    ax.set_xlabel("time since data start [h]")
    ax.legend(fontsize=7, loc="lower right")
    ax.grid(alpha=0.3, which="both")
    n_exc = len(d["excluded"])
    axes[0].set_title(f"Screening per satellite and 5-min block: {n_exc} excluded spans",
                      fontsize=10)  # fmt: skip
    fig.tight_layout()
    return fig


#: (key, caption, function) of every report figure, in report order.
FIGURES = (
    ("arcs", "Arc timeline", fig_arcs),
    ("df_filter", "Dual-frequency difference before and after filtering", fig_df_filter),
    ("screening", "Ionosphere screening (ROTI) and excluded spans", fig_screening),
    ("mapped", "Mapped residuals and stationary windows", fig_mapped_windows),
    ("psds", "Every window PSD under the bound", fig_psds_bound),
    ("tau", "Tightness search over tau", fig_tau_search),
    ("cutoff", "Lomb-Scargle envelope and cutoff", fig_cutoff_envelope),
    ("jacobi_anger", "Jacobi-Anger cutoff check", fig_jacobi_anger),
)
