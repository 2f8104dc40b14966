"""The reflection around this antenna, measured from SNR where the file allows it.

The cutoff validation and the slow component of the error model
(:mod:`psdbound.validation.removed`) need the ground reflector's height and
the reflection's amplitude ratio ``alpha``. A fixed assumption gives every
station the same removed multipath; the SNR of the same file measures both
(GNSS interferometric reflectometry, :mod:`psdbound.validation.reflectors`).

From the accepted arcs of the first carrier's SNR (:data:`MIN_ARCS` at
least): the ground height is the 10th percentile of their heights (the low
reflectors oscillate slowest, so they put the most power below the cutoff)
and ``alpha`` the 90th percentile of their amplitude ratios (conservative
over directions). With fewer accepted arcs, or no SNR in the file, the
configured values are used and said to be assumed.

A low reflector oscillates few times over 5-25 deg (``2 h / lambda`` cycles
per unit ``sin e``: 1.8 cycles for 0.5 m on L1), and the elevation trend then
absorbs part of the oscillation: ``alpha`` comes out low (0.15 for a true 0.2
at 0.5 m, noise-free). When the median height gives fewer than
:data:`MIN_CYCLES` cycles over the range, the analysis is repeated with the
range's top raised until it does (at most :data:`MAX_TOP_DEG`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError

__all__ = ["MIN_ARCS", "SiteReflection", "site_reflection"]

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

    def as_dict(self) -> dict[str, Any]:
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


def site_reflection(
    obs: Any,
    orbit: Any,
    *,
    phase_signal: str,
    system: str,
    receiver_xyz_m: NDArray[np.float64] | None,
    alpha: float,
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

    Returns
    -------
    SiteReflection
    """
    from psdbound.validation.reflectors import reflector_heights

    signal = snr_signal(phase_signal)
    if orbit is None:
        return SiteReflection(
            alpha,
            None,
            False,
            note=f"no orbit for the SNR analysis: alpha {alpha:g} assumed (configuration)",
        )
    try:
        rh = reflector_heights(
            obs, orbit, signal=signal, systems=system, receiver_xyz_m=receiver_xyz_m
        )
        top = _top_for_cycles(rh)
        if top > RANGE_DEG[1]:
            rh = reflector_heights(
                obs,
                orbit,
                signal=signal,
                systems=system,
                receiver_xyz_m=receiver_xyz_m,
                elevation_range_deg=(RANGE_DEG[0], top),
            )
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
    h = float(np.quantile(np.asarray(rh.height_m)[ok], HEIGHT_QUANTILE))
    lo, hi = rh.elevation_range_deg
    a = float(min(np.quantile(np.asarray(rh.alpha)[ok], ALPHA_QUANTILE), 0.99))
    return SiteReflection(
        a,
        h,
        True,
        n,
        k,
        note=(
            f"measured from {k} of {n} {signal} SNR arcs (GNSS-IR, {lo:.3g}-{hi:.3g} deg): ground "
            f"height {h:.2f} m "
            f"(10th percentile; median {rh.median_height_m:.2f} m), alpha {a:.3f} (90th "
            f"percentile; median {rh.median_alpha:.3f})"
        ),
    )
