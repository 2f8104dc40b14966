"""The reflection around this antenna, measured from SNR where the file allows it.

The cutoff validation and the slow component of the error model
(:mod:`psdbound.validation.removed`) need the ground reflector's height and
the reflection's amplitude ratio ``alpha``. A fixed assumption gives every
station the same removed multipath; the SNR of the same file measures both
(GNSS interferometric reflectometry, :mod:`psdbound.validation.reflectors`).

From the accepted arcs of the first carrier's SNR (:data:`MIN_ARCS` at
least), the reflection modelled is one arc's height and amplitude ratio
together: the arc at the 90th percentile of ``alpha^2 w(h)``, ``w(h)`` the
share of the data's samples where a reflector at that height oscillates
below the cutoff (:func:`removed_weight`: low reflectors oscillate slowest).
Taking the 10th percentile of the heights and the 90th of the ratios apart
pairs a low reflector with a strong one that no arc showed (ZIMM: 0.54 m
with 0.18, removed 12.7 mm as a slow component). With fewer accepted arcs,
or no SNR in the file, the configured values are used and said to be
assumed.

A low reflector oscillates few times over 5-25 deg (``2 h / lambda`` cycles
per unit ``sin e``: 1.8 cycles for 0.5 m on L1), and the elevation trend then
absorbs part of the oscillation: ``alpha`` comes out low (0.15 for a true 0.2
at 0.5 m, noise-free). When the median height gives fewer than
:data:`MIN_CYCLES` cycles over the range, the analysis is repeated with the
range's top raised until it does (at most :data:`MAX_TOP_DEG`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError

__all__ = [
    "MIN_ARCS",
    "SiteReflection",
    "height_tolerance_m",
    "removed_weight",
    "site_reflection",
    "snr_signal",
]

#: Fewest accepted SNR arcs for a measured height and alpha.
MIN_ARCS = 5
#: Quantiles of the accepted arcs taken: low heights, strong reflections.
HEIGHT_QUANTILE, ALPHA_QUANTILE = 0.1, 0.9
#: Fewest oscillation cycles over the elevation range for an unbiased alpha.
MIN_CYCLES = 2.5
#: Highest top of the elevation range used to reach them, degrees.
MAX_TOP_DEG = 60.0
#: The default elevation range, degrees.
RANGE_DEG = (5.0, 25.0)
#: Tolerance of a measured ground height: the larger of an absolute (m) and a relative part
#: (the SNR analysis is biased by up to 4 cm below 1 m and scatters by a few % above).
HEIGHT_TOLERANCE_M, HEIGHT_TOLERANCE = 0.05, 0.05


@dataclass(frozen=True)
class SiteReflection:
    """Ground height and amplitude ratio, measured or assumed.

    Attributes
    ----------
    alpha : float
        Amplitude ratio used.
    ground_height_m : float or None
        Ground reflector height, m (None: not measured; the configured
        geometries apply).
    measured : bool
        Whether both come from the SNR.
    n_arcs, n_accepted : int
        SNR arcs analysed and accepted.
    note : str
        Where the numbers come from, in words.
    """

    alpha: float
    ground_height_m: float | None
    measured: bool
    n_arcs: int = 0
    n_accepted: int = 0
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "alpha": self.alpha,
            "ground_height_m": self.ground_height_m,
            "measured": self.measured,
            "n_arcs": self.n_arcs,
            "n_accepted": self.n_accepted,
            "note": self.note,
        }


def snr_signal(phase_signal: str) -> str:
    """Return the SNR code of a carrier-phase signal (``L1C``: ``S1C``; ``L1``: ``S1``)."""
    return "S" + phase_signal[1:]


def _top_for_cycles(rh: Any) -> float:
    """Return the range's top giving :data:`MIN_CYCLES` cycles at the median height, deg."""
    ok = np.asarray(rh.accepted, dtype=bool)
    if ok.sum() < MIN_ARCS:
        return RANGE_DEG[1]
    h = float(np.median(np.asarray(rh.height_m)[ok]))
    lam = float(np.median(np.asarray(rh.wavelength_m)[ok]))
    s = np.sin(np.radians(RANGE_DEG[0])) + MIN_CYCLES * lam / (2.0 * h)
    top = float(np.degrees(np.arcsin(min(s, 1.0))))
    return min(max(top, RANGE_DEG[1]), MAX_TOP_DEG)


def height_tolerance_m(h_m: float) -> float:
    """Return the tolerance of a ground height measured from the SNR, m.

    Parameters
    ----------
    h_m : float
        The height, m.

    Returns
    -------
    float
        ``max(HEIGHT_TOLERANCE_M, HEIGHT_TOLERANCE h)``.
    """
    return max(HEIGHT_TOLERANCE_M, HEIGHT_TOLERANCE * h_m)


def removed_weight(
    elevation_deg: NDArray[np.float64],
    t_gps_s: NDArray[np.float64],
    arc_id: NDArray[np.int64],
    *,
    wavelength_m: float,
    cutoff_hz: float,
) -> Callable[[float], float]:
    """Return ``w(h)``: the share of the data's samples where a ground reflection is below f_c.

    A ground reflection at height ``h`` oscillates at ``2 h |d sin(e) / dt| / lambda``
    Hz; where that is below the cutoff the high-pass removes it. ``w(h)`` is
    the fraction of the data's samples (every arc, its own elevation rate)
    where it is.

    Parameters
    ----------
    elevation_deg, t_gps_s, arc_id : ndarray
        The multipath series' elevations (deg), times (s) and arc labels.
    wavelength_m : float
        Carrier wavelength, m.
    cutoff_hz : float
        The high-pass cutoff, Hz.

    Returns
    -------
    callable
        ``w(h_m) -> float`` in [0, 1].
    """
    rate = np.full(elevation_deg.shape, np.nan)
    for a in np.unique(arc_id):
        k = np.flatnonzero(arc_id == a)
        if k.size > 2:
            rate[k] = np.abs(np.gradient(np.sin(np.radians(elevation_deg[k])), t_gps_s[k]))
    rate = rate[np.isfinite(rate)]

    def weight(h_m: float) -> float:
        return float(np.mean(2.0 * h_m * rate / wavelength_m < cutoff_hz)) if rate.size else 1.0

    return weight


def _analyse(obs: Any, orbit: Any, signal: str, system: str, pos: Any) -> Any:
    """Run the SNR analysis, with the range widened for a low reflector (may raise)."""
    from psdbound.validation.reflectors import reflector_heights

    rh = reflector_heights(obs, orbit, signal=signal, systems=system, receiver_xyz_m=pos)
    top = _top_for_cycles(rh)
    if top > RANGE_DEG[1]:
        rh = reflector_heights(
            obs,
            orbit,
            signal=signal,
            systems=system,
            receiver_xyz_m=pos,
            elevation_range_deg=(RANGE_DEG[0], top),
        )
    return rh


def _choose(
    rh: Any, ok: NDArray[np.bool_], weight: Callable[[float], float] | None
) -> tuple[float, float, str]:
    """Pick the reflection to model: ``(height_m, alpha, how)``."""
    h_all, a_all = np.asarray(rh.height_m)[ok], np.asarray(rh.alpha)[ok]
    if weight is None:
        h = float(np.quantile(h_all, HEIGHT_QUANTILE))
        a = float(np.quantile(a_all, ALPHA_QUANTILE))
        return h, a, "10th percentile of the heights, 90th of the amplitude ratios"
    removed = a_all**2 * np.array([weight(float(x)) for x in h_all])
    i = int(np.argsort(removed)[min(int(np.ceil(ALPHA_QUANTILE * removed.size)), removed.size) - 1])
    return (
        float(h_all[i]),
        float(a_all[i]),
        (
            "the arc at the 90th percentile of alpha^2 x the share of the data the filter "
            "removes at its height"
        ),
    )


def site_reflection(
    obs: Any,
    orbit: Any,
    *,
    phase_signal: str,
    system: str,
    receiver_xyz_m: NDArray[np.float64] | None,
    alpha: float,
    weight: Callable[[float], float] | None = None,
) -> SiteReflection:
    """Measure the ground height and ``alpha`` from the SNR, or fall back to ``alpha``.

    Parameters
    ----------
    obs : Observations
        The observation file (:func:`psdbound.io.read_obs`).
    orbit : OrbitSource or None
        Its orbits.
    phase_signal : str
        The first carrier-phase signal of the series (its SNR is used).
    system : str
        GNSS system letter.
    receiver_xyz_m : ndarray or None
        Receiver position, ECEF m.
    alpha : float
        The configured amplitude ratio (the fallback).
    weight : callable, optional
        :func:`removed_weight`: with it, the arc whose reflection the filter
        removes most (90th percentile of ``alpha^2 w(h)`` over the accepted
        arcs) gives height and ``alpha`` together; without it, the 10th
        percentile of the heights and the 90th of the ratios, apart.

    Returns
    -------
    SiteReflection
    """
    signal = snr_signal(phase_signal)
    if orbit is None:
        return SiteReflection(
            alpha,
            None,
            False,
            note=f"no orbit for the SNR analysis: alpha {alpha:g} assumed (configuration)",
        )
    try:
        rh = _analyse(obs, orbit, signal, system, receiver_xyz_m)
    except InputError as exc:
        return SiteReflection(
            alpha,
            None,
            False,
            note=f"no SNR analysis ({exc}): alpha {alpha:g} assumed (configuration)",
        )
    ok = np.asarray(rh.accepted, dtype=bool)
    n, k = int(ok.size), int(ok.sum())
    if k < MIN_ARCS:
        return SiteReflection(
            alpha,
            None,
            False,
            n,
            k,
            note=(
                f"{k} of {n} {signal} SNR arcs show a ground reflection (at least {MIN_ARCS} "
                f"needed): alpha {alpha:g} and the ground height assumed (configuration, header)"
            ),
        )
    h, a, how = _choose(rh, ok, weight)
    lo, hi = rh.elevation_range_deg
    return SiteReflection(
        min(a, 0.99),
        h,
        True,
        n,
        k,
        note=(
            f"measured from {k} of {n} {signal} SNR arcs (GNSS-IR, {lo:.3g}-{hi:.3g} deg): ground "
            f"height {h:.2f} m, alpha {a:.3f} ({how}; medians {rh.median_height_m:.2f} m, "
            f"{rh.median_alpha:.3f})"
        ),
    )
