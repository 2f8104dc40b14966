"""The physical limit of carrier-phase multipath in an isolated series.

A single specular reflection with amplitude ratio ``alpha < 1`` shifts the
carrier phase by ``atan(alpha sin psi / (1 + alpha cos psi))``, whose largest
value ``asin(alpha)`` approaches 90 degrees as ``alpha -> 1``: carrier
multipath cannot exceed a quarter of the wavelength (Braasch, 1996; Georgiadou
and Kleusberg, 1988). An isolated series combines several such terms, so its
absolute value is bounded by the scaled sum of their limits:

* dual-frequency ``(L_a - L_b) / sqrt(2)``: ``(lambda_a + lambda_b) / (4 sqrt 2)``
  (GPS L1/L2: 7.70 cm);
* dual-antenna double difference ``/ 2`` (four terms of one signal):
  ``4 (lambda / 4) / 2 = lambda / 2`` (GPS L1: 9.51 cm).

A sample beyond the limit is not multipath: residual ionosphere, an undetected
cycle slip or a bad observation.

References
----------
Georgiadou, Y., Kleusberg, A. (1988). On carrier signal multipath effects in
relative GPS positioning. Manuscripta Geodaetica 13, 172-179.

Braasch, M. S. (1996). Multipath effects. In Parkinson, B. W., Spilker, J. J.
(eds.), Global Positioning System: Theory and Applications, vol. I, AIAA,
547-568.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from psdbound.errors import InputError

__all__ = ["multipath_limit_m"]


def multipath_limit_m(wavelengths_m: Sequence[float], scaling: float) -> float:
    """Largest possible absolute value of carrier multipath in a combination, metres.

    Parameters
    ----------
    wavelengths_m : sequence of float
        Wavelength of every phase term in the combination, metres (two for
        a DF difference, four equal ones for a double difference).
    scaling : float
        Factor applied to the combination (``1/sqrt(2)`` DF, ``1/2`` DA).

    Returns
    -------
    float
        ``scaling * sum(lambda_i / 4)``, metres.
    """
    lam = np.asarray(wavelengths_m, dtype=float)
    if lam.size == 0 or not np.all(np.isfinite(lam)) or np.any(lam <= 0):
        raise InputError(f"wavelengths must be positive numbers, got {list(wavelengths_m)}")
    if not (np.isfinite(scaling) and scaling > 0):
        raise InputError(f"scaling must be a positive number, got {scaling}")
    return float(scaling * np.sum(lam / 4.0))
