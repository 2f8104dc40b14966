"""Report figures of the optional code-multipath stage (``result.json`` ``code_multipath``)."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from psdbound.reports.figures_base import HALF_PAGE_H_IN, finish, new_figure

__all__ = ["fig_code_qq", "fig_overbound_qq", "fig_vpl", "overbound_line"]


def overbound_line(z: np.ndarray, bias: float, sigma: float, method: str) -> np.ndarray:
    """Quantiles of the overbound on a Q-Q plot, unit of the samples.

    Paired: the left bound ``-b + s z`` for ``z < 0`` and the right bound
    ``+b + s z`` for ``z > 0``; otherwise the single Gaussian ``b + s z``.

    Parameters
    ----------
    z : ndarray
        Standard-normal quantiles (dimensionless).
    bias, sigma : float
        The bin's overbound, unit of the samples.
    method : str
        ``"paired"``, ``"two_step"`` or ``"cdf"``.

    Returns
    -------
    ndarray
    """
    z = np.asarray(z, dtype=float)
    if method == "paired":
        return np.where(z < 0, -bias, bias) + sigma * z
    return bias + sigma * z


def fig_overbound_qq(
    overbound: dict[str, Any], qq: dict[str, Any], *, title: str, unit: str = "m"
) -> Figure:
    """Q-Q plot of samples per elevation bin, with each bin's Gaussian overbound.

    Left: sample quantiles against standard-normal quantiles, one colour per
    elevation bin, the overbound (:func:`overbound_line`) as a line of the
    same colour. Right: the overbounding sigma and the sample standard
    deviation per bin, with the inflation factor and the sample sizes
    (``n``, effective ``n_eff``) written on each bin. The ``overbound``
    command's ``overbound_qq.png`` and the fit report's code-multipath
    figure are this one figure.

    Parameters
    ----------
    overbound : dict
        ``method`` and ``bins`` (:meth:`psdbound.aviation.OverboundResult.to_dict`).
    qq : dict
        ``label -> {"z", "x"}`` (:meth:`~psdbound.aviation.OverboundResult.qq_points`).
    title : str
        The figure's title.
    unit : str, default "m"
        Unit of the samples.

    Returns
    -------
    Figure
    """
    fig = new_figure(HALF_PAGE_H_IN)
    ax, ax2 = fig.subplots(1, 2, width_ratios=(1.6, 1.0))
    _qq_panel(ax, overbound, qq, unit)
    _sigma_panel(ax2, overbound["bins"], unit)
    heading = fig.suptitle(title, fontsize=9)
    return finish(fig, above=[heading])


def _qq_panel(ax: Any, ob: dict[str, Any], qq: dict[str, Any], unit: str) -> None:
    """Draw each bin's sample quantiles and its overbound line."""
    for b in ob["bins"]:
        lo, hi = b["elevation_deg"]
        label = f"[{lo:g}, {hi:g}) deg"
        pts = qq.get(label)
        if pts is None:
            continue
        z, x = np.asarray(pts["z"]), np.asarray(pts["x"])
        neff = b.get("n_eff")
        size = f", n {b['n']}" + (f", n_eff {neff:.0f}" if neff is not None else "")
        line = ax.plot(z, x, ".", ms=2.5, label=f"{label}: x{b['inflation']:.2f}{size}")[0]
        ax.plot(
            z,
            overbound_line(z, b["bias"], b["sigma"], ob["method"]),
            "-",
            lw=0.9,
            color=line.get_color(),
        )
    ax.set_xlabel("standard-normal quantile [-]")
    ax.set_ylabel(f"sample quantile [{unit}]")
    ax.grid(alpha=0.3)
    ax.legend(
        fontsize=6.5,
        title="bin: inflation sigma/std, samples n, effective n_eff",
        title_fontsize=6.5,
        loc="upper left",
    )


def _sigma_panel(ax2: Any, bins: list[dict[str, Any]], unit: str) -> None:
    """Draw the overbounding sigma and the sample std per bin, with inflation and sizes."""
    mid = [0.5 * sum(b["elevation_deg"]) for b in bins]
    width = [0.8 * (b["elevation_deg"][1] - b["elevation_deg"][0]) for b in bins]
    ax2.bar(mid, [b["sigma"] for b in bins], width=width, color="0.75", label="overbound sigma")
    ax2.plot(mid, [b["std"] for b in bins], "ko", ms=4, label="sample std")
    for m, b in zip(mid, bins, strict=True):
        neff = f"\nn_eff={b['n_eff']:.0f}" if b.get("n_eff") is not None else ""
        ax2.annotate(
            f"x{b['inflation']:.2f}\nn={b['n']}{neff}",
            (m, b["sigma"]),
            fontsize=6,
            ha="center",
            va="bottom",
        )
    ax2.set_xlabel("elevation [deg]")
    ax2.set_ylabel(f"sigma [{unit}]")
    ax2.set_xlim(0, 90)
    ax2.set_ylim(0, 1.25 * max(b["sigma"] for b in bins))
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)


def fig_code_qq(r: dict[str, Any]) -> Figure | None:
    """Q-Q plot of the code multipath per elevation bin (:func:`fig_overbound_qq`).

    Parameters
    ----------
    r : dict
        Result document.

    Returns
    -------
    Figure or None
        None when the run computed no code-multipath overbound.
    """
    c = r.get("code_multipath") or {}
    ob, qq = c.get("overbound"), c.get("qq")
    if not ob or not qq:
        return None
    codes = c.get("codes", [])
    kind = "MP combination" if len(codes) == 1 else "ionosphere-free"
    title = (
        f"Code multipath {'+'.join(codes)} ({kind}, arc means removed): "
        f"{ob['method']} Gaussian overbound per elevation bin"
    )
    return fig_overbound_qq(ob, qq, title=title, unit="m")


def fig_vpl(vpl: dict[str, Any]) -> Figure:
    """Vertical protection levels over time, and the satellites in view in a panel of its own.

    Top: VPL_H0, VPL_eph and VPL = max (m) against time since the first
    epoch (h), with the vertical alert limit when given. Bottom: the number
    of satellites above the mask (count), on its own axis: drawn on a second
    axis of the top panel, a count reads as a protection level.

    Parameters
    ----------
    vpl : dict
        ``vpl.json``'s ``vpl`` section (:meth:`psdbound.aviation.VplSeries.to_dict`).

    Returns
    -------
    Figure
    """
    t = np.asarray(vpl["t_gps_s"], dtype=float)
    h = (t - t[0]) / 3600.0

    def arr(key: str) -> np.ndarray:
        return np.array([np.nan if v is None else v for v in vpl[key]], dtype=float)

    fig = new_figure(HALF_PAGE_H_IN)
    ax, ax2 = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    ax.plot(h, arr("vpl_m"), "-", lw=3.0, color="0.75", label="VPL = max")
    ax.plot(h, arr("vpl_h0_m"), "-", lw=0.9, label="VPL_H0")
    ax.plot(h, arr("vpl_eph_m"), "--", lw=0.9, label="VPL_eph")
    val = vpl.get("val_m")
    if val is not None:
        ax.axhline(val, color="r", ls=":", label=f"VAL {val:g} m")
    top = 1.35 * max(np.nanmax(arr("vpl_m"), initial=1.0), val or 0.0)
    o = vpl["options"]
    ax.set(ylim=(0, top), ylabel="vertical protection level [m]")
    ax.set_title(
        f"{o['process']} {o['base_frequency']}, tau {o['tau_gnd_s']:g}/{o['tau_air_s']:g} s, "
        f"x_air {o['x_air_m'] / 1000:g} km",
        fontsize=9,
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", ncols=4)
    n = np.asarray(vpl["n_sats"], dtype=int)
    ax2.step(h, n, where="post", color="0.35", lw=0.9)
    ax2.set(
        ylabel=f"satellites > {vpl['elevation_mask_deg']:g} deg [count]",
        ylim=(0, 1.15 * max(int(n.max()), 4)),
        xlabel=f"time since {vpl['time_gps'][0].replace('T', ' ')} GPS [h]",
    )
    ax2.grid(alpha=0.3)
    return finish(fig)
