"""Rate of TEC (ROT) and the Rate of TEC Index (ROTI) from the geometry-free phase.

The geometry-free carrier combination ``L_a - L_b`` (metres) of two signals
of frequencies ``f_a > f_b`` holds the slant ionosphere::

    L_a - L_b = k STEC + const,   k = 40.3e16 (1/f_b^2 - 1/f_a^2)  m/TECU

(``40.3 m^3/s^2`` the ionospheric refraction constant, 1 TECU = 1e16
electrons/m^2; 0.105 m/TECU for GPS L1/L2). ROT is its time derivative in
TECU/min between consecutive samples, and ROTI the standard deviation of ROT
over a block (Pi et al., 1997).

ROTI depends on the sampling rate and on the block length (Jacobsen, 2014),
so psdbound always computes it the way the IGS ROTI product and Pi et al. do:
ROT from samples 30 s apart (data at a higher rate are decimated, data at a
lower rate keep their own interval), ROTI over consecutive 5-min blocks.
Values are therefore comparable with published thresholds whatever the
observation interval.

References
----------
Pi, X., Mannucci, A. J., Lindqwister, U. J., Ho, C. M. (1997). Monitoring of
global ionospheric irregularities using the worldwide GPS network.
Geophysical Research Letters 24(18), 2283-2286.

Jacobsen, K. S. (2014). The impact of different sampling rates and
calculation time intervals on ROTI values. Journal of Space Weather and Space
Climate 4, A33. doi:10.1051/swsc/2014031

Cherniak, I., Krankowski, A., Zakharenkova, I. (2018). ROTI maps: a new IGS
ionospheric product characterizing the ionospheric irregularities occurrence.
GPS Solutions 22, 69.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError

__all__ = [
    "IONO_CONSTANT_M3_S2",
    "ROT_INTERVAL_S",
    "ROTI_BLOCK_S",
    "RotiBlocks",
    "geometry_free_m_per_tecu",
    "rate_of_tec",
    "roti_blocks",
]

#: Ionospheric refraction constant, m^3/s^2 (phase advance 40.3 STEC / f^2).
IONO_CONSTANT_M3_S2 = 40.3
#: Sampling of ROT, s (Pi et al. 1997; IGS ROTI product).
ROT_INTERVAL_S = 30.0
#: ROTI block length, s (Pi et al. 1997; IGS ROTI product).
ROTI_BLOCK_S = 300.0
_TECU = 1e16


def geometry_free_m_per_tecu(f_a_hz: float, f_b_hz: float) -> float:
    """Metres of ``L_a - L_b`` per TECU of slant TEC.

    Parameters
    ----------
    f_a_hz, f_b_hz : float
        Carrier frequencies of the two phases, Hz (``f_a > f_b`` gives a
        positive factor).

    Returns
    -------
    float
        ``40.3e16 (1/f_b^2 - 1/f_a^2)``, m/TECU.
    """
    if not (f_a_hz > 0 and f_b_hz > 0) or f_a_hz == f_b_hz:
        raise InputError(f"need two different positive frequencies, got {f_a_hz}, {f_b_hz} Hz")
    return IONO_CONSTANT_M3_S2 * _TECU * (1.0 / f_b_hz**2 - 1.0 / f_a_hz**2)


def rate_of_tec(
    t_gps_s: ArrayLike, gf_m: ArrayLike, m_per_tecu: float, *, interval_s: float = ROT_INTERVAL_S
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """ROT of one continuous arc, TECU/min, on samples ``interval_s`` apart.

    Parameters
    ----------
    t_gps_s : array_like
        Sample times of the arc, s (increasing, no cycle slip inside).
    gf_m : array_like
        Geometry-free phase ``L_a - L_b``, metres.
    m_per_tecu : float
        From :func:`geometry_free_m_per_tecu`.
    interval_s : float, default 30
        ROT sampling; data at a higher rate are decimated to it (samples
        whose time is a multiple of it), data at a lower rate keep theirs.

    Returns
    -------
    t_mid_gps_s : ndarray
        Mid-times of the differences, s.
    rot_tecu_min : ndarray
        ``(STEC[k+1] - STEC[k]) / (t[k+1] - t[k])`` in TECU/min.
    """
    t = np.asarray(t_gps_s, dtype=float)
    g = np.asarray(gf_m, dtype=float)
    if t.size != g.size:
        raise InputError(f"times ({t.size}) and values ({g.size}) differ in length")
    if t.size < 2:
        return np.zeros(0), np.zeros(0)
    dt = float(np.median(np.diff(t)))
    if dt < interval_s:
        keep = np.abs(np.remainder(t + 0.5 * dt, interval_s) - 0.5 * dt) < 0.5 * dt
        t, g = t[keep], g[keep]
    if t.size < 2:
        return np.zeros(0), np.zeros(0)
    d_t = np.diff(t)
    rot = np.diff(g) / m_per_tecu / (d_t / 60.0)
    return 0.5 * (t[1:] + t[:-1]), rot


@dataclass(frozen=True)
class RotiBlocks:
    """ROTI over consecutive blocks of one arc.

    Attributes
    ----------
    start_gps_s, stop_gps_s : ndarray
        Block limits, s (a block holds the ROT samples with mid-times in
        ``[start, stop)``).
    roti_tecu_min : ndarray
        Standard deviation of ROT in the block, TECU/min (NaN for blocks with
        fewer than half their nominal samples).
    n : ndarray
        ROT samples per block.
    """

    start_gps_s: NDArray[np.float64]
    stop_gps_s: NDArray[np.float64]
    roti_tecu_min: NDArray[np.float64]
    n: NDArray[np.intp]


def roti_blocks(
    t_mid_gps_s: ArrayLike,
    rot_tecu_min: ArrayLike,
    *,
    t0_gps_s: float,
    t1_gps_s: float,
    block_s: float = ROTI_BLOCK_S,
    rot_interval_s: float = ROT_INTERVAL_S,
) -> RotiBlocks:
    """ROTI (standard deviation of ROT) over consecutive blocks covering ``[t0, t1]``.

    Parameters
    ----------
    t_mid_gps_s, rot_tecu_min : array_like
        ROT samples from :func:`rate_of_tec`.
    t0_gps_s, t1_gps_s : float
        Span of the arc, s; blocks start at ``t0`` and the last one ends at
        or after ``t1``.
    block_s : float, default 300
        Block length, s.
    rot_interval_s : float, default 30
        Nominal ROT spacing, s (for the half-full rule).

    Returns
    -------
    RotiBlocks
    """
    tm = np.asarray(t_mid_gps_s, dtype=float)
    r = np.asarray(rot_tecu_min, dtype=float)
    n_blocks = max(1, int(np.ceil((t1_gps_s - t0_gps_s) / block_s - 1e-9)))
    start = t0_gps_s + block_s * np.arange(n_blocks)
    idx = np.clip(((tm - t0_gps_s) // block_s).astype(int), 0, n_blocks - 1)
    n = np.bincount(idx, minlength=n_blocks)
    s1 = np.bincount(idx, weights=r, minlength=n_blocks)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = s1 / n
        dev = r - mean[idx]  # two passes: no cancellation for large constant rates
        var = np.bincount(idx, weights=dev * dev, minlength=n_blocks) / n
    nominal = max(1.0, block_s / max(rot_interval_s, 1e-9))
    roti = np.where(n >= max(2, 0.5 * nominal), np.sqrt(var), np.nan)
    return RotiBlocks(start, start + block_s, roti, n.astype(np.intp))
