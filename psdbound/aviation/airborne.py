"""Airborne code-error sigma curves and the dual-frequency iono-free factor.

The AAD-A curves of seed 001 eq. (1) and seed 000 eqs. (1)-(3) (GBAS airborne
accuracy designator A; seed 001 credits them to RTCA DO-208 and McGraw et al.
2000): multipath ``0.13 + 0.53 exp(-el / 10 deg)`` m and receiver noise
``0.15 + 0.43 exp(-el / 6.9 deg)`` m. The coefficients and their sources are
in :mod:`psdbound.aviation.standards` (``AAD_A_MULTIPATH``, ``AAD_A_NOISE``).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.aviation.standards import AAD_A_MULTIPATH, AAD_A_NOISE
from psdbound.constants import F_L1_HZ, F_L5_HZ
from psdbound.errors import InputError

__all__ = [
    "iono_free_factor",
    "sigma_air_m",
    "sigma_multipath_airborne_m",
    "sigma_noise_airborne_m",
]


def _elev(elevation_deg: ArrayLike) -> NDArray[np.float64]:
    el = np.asarray(elevation_deg, dtype=float)
    if not np.isfinite(el).all():
        raise InputError("elevations must be finite numbers of degrees")
    return el


# ----------------------------------------------------------------- sigma curves
def sigma_multipath_airborne_m(elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Airborne multipath sigma ``0.13 + 0.53 exp(-el / 10 deg)``, metres.

    Parameters
    ----------
    elevation_deg : array_like
        Elevation, degrees.

    Returns
    -------
    ndarray
    """
    a0, a1, theta0 = AAD_A_MULTIPATH.value
    return a0 + a1 * np.exp(-_elev(elevation_deg) / theta0)


def sigma_noise_airborne_m(elevation_deg: ArrayLike) -> NDArray[np.float64]:
    """Airborne receiver-noise sigma (AAD-A) ``0.15 + 0.43 exp(-el / 6.9 deg)``, metres.

    Parameters
    ----------
    elevation_deg : array_like
        Elevation, degrees.

    Returns
    -------
    ndarray
    """
    a0, a1, theta0 = AAD_A_NOISE.value
    return a0 + a1 * np.exp(-_elev(elevation_deg) / theta0)


def iono_free_factor(f1_hz: float = F_L1_HZ, f2_hz: float = F_L5_HZ) -> float:
    """Noise amplification of the iono-free combination, ``sqrt(f1^4 + f2^4) / |f1^2 - f2^2|``.

    For equal, independent errors on the two frequencies (2.588 for L1/L5).

    Parameters
    ----------
    f1_hz, f2_hz : float
        Carrier frequencies, Hz (different, > 0).

    Returns
    -------
    float
    """
    if not (f1_hz > 0 and f2_hz > 0) or f1_hz == f2_hz:
        raise InputError(f"need two different positive frequencies, got {f1_hz}, {f2_hz}")
    return math.sqrt((f1_hz**4 + f2_hz**4) / (f1_hz**2 - f2_hz**2) ** 2)


def sigma_air_m(
    elevation_deg: ArrayLike,
    *,
    dual_frequency: bool = True,
    f1_hz: float = F_L1_HZ,
    f2_hz: float = F_L5_HZ,
    multipath_variance_factor: ArrayLike = 1.0,
    noise_variance_factor: ArrayLike = 1.0,
) -> NDArray[np.float64]:
    """Airborne code error sigma ``F sqrt(A_MP sigma_MP^2 + A_noise sigma_noise^2)``, metres.

    Seed 000 eq. (3) (eq. (1) with unit factors; ``F`` the iono-free factor,
    1 for single frequency). Use :func:`smoothing_variance_factor` for
    ``A_MP(k)`` and ``A_noise(k)`` (seed 000 eq. 21).

    Parameters
    ----------
    elevation_deg : array_like
        Elevation, degrees.
    dual_frequency : bool, default True
        Apply the iono-free factor of ``f1_hz, f2_hz``.
    f1_hz, f2_hz : float
        Frequencies of the combination, Hz (default L1, L5).
    multipath_variance_factor, noise_variance_factor : array_like, default 1
        Variance inflation ``A_MP``, ``A_noise`` (dimensionless).

    Returns
    -------
    ndarray
    """
    f = iono_free_factor(f1_hz, f2_hz) if dual_frequency else 1.0
    amp = np.asarray(multipath_variance_factor, dtype=float)
    anoise = np.asarray(noise_variance_factor, dtype=float)
    if (amp < 0).any() or (anoise < 0).any():
        raise InputError("variance factors must be >= 0")
    mp = sigma_multipath_airborne_m(elevation_deg)
    nz = sigma_noise_airborne_m(elevation_deg)
    return f * np.sqrt(amp * mp**2 + anoise * nz**2)
