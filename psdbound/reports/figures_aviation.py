"""Report figures of the optional code-multipath stage (``result.json`` ``code_multipath``)."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.figure import Figure

from psdbound.reports.figures_base import HALF_PAGE_H_IN, finish, new_figure

__all__ = ["fig_code_qq", "overbound_line"]


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


def fig_code_qq(r: dict[str, Any]) -> Figure | None:
    """Q-Q plot of the code multipath per elevation bin, with each bin's Gaussian overbound.

    Left: sample quantiles (m) against standard-normal quantiles, one colour
    per elevation bin, the overbound ``bias + sigma z`` as a line of the same
    colour. Right: the overbounding sigma and the sample standard deviation
    per bin (m), the inflation factor written on each bin.

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
    fig = new_figure(HALF_PAGE_H_IN)
    ax, ax2 = fig.subplots(1, 2, width_ratios=(1.6, 1.0))
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
    ax.set_ylabel("code multipath quantile [m]")
    ax.grid(alpha=0.3)
    ax.legend(
        fontsize=6.5,
        title="bin: inflation sigma/std, samples n, effective n_eff",
        title_fontsize=6.5,
        loc="upper left",
    )
    mid = [0.5 * sum(b["elevation_deg"]) for b in ob["bins"]]
    width = [0.8 * (b["elevation_deg"][1] - b["elevation_deg"][0]) for b in ob["bins"]]
    ax2.bar(
        mid, [b["sigma"] for b in ob["bins"]], width=width, color="0.75", label="overbound sigma"
    )
    ax2.plot(mid, [b["std"] for b in ob["bins"]], "ko", ms=4, label="sample std")
    for m, b in zip(mid, ob["bins"], strict=True):
        neff = f"\nn_eff={b['n_eff']:.0f}" if b.get("n_eff") is not None else ""
        ax2.annotate(
            f"x{b['inflation']:.2f}\nn={b['n']}{neff}",
            (m, b["sigma"]),
            fontsize=6,
            ha="center",
            va="bottom",
        )
    ax2.set_xlabel("elevation [deg]")
    ax2.set_ylabel("sigma [m]")
    ax2.set_xlim(0, 90)
    ax2.set_ylim(0, 1.25 * max(b["sigma"] for b in ob["bins"]))
    ax2.legend(fontsize=7)
    ax2.grid(alpha=0.3)
    codes = c.get("codes", [])
    kind = "MP combination" if len(codes) == 1 else "ionosphere-free"
    fig.suptitle(
        f"Code multipath {'+'.join(codes)} ({kind}, arc means removed): "
        f"{ob['method']} Gaussian overbound per elevation bin",
        fontsize=9,
    )
    return finish(fig)
