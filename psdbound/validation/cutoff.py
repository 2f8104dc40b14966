"""Fraction of multipath power a cutoff removes, from the Jacobi-Anger expansion.

Harmonic ``q`` of the expansion lies at ``q f_geom`` (:mod:`.modes`). The
fraction removed by a high-pass filter at ``f_c`` is taken as

    sum_{0 < q f_geom < f_c} P_q / sum_{q > 0} P_q,

with ``P_q`` the mean-square power of harmonic ``q`` (the squared
amplitude over two). The constant term (``q = 0``, only in the oscillation
model) is excluded from both sums: psdbound removes each arc's mean with the
ambiguity before any filtering, whatever the cutoff. An ideal brick-wall
filter is assumed; a real filter also damps content just above ``f_c`` and
leaks some just below.

The verdict uses the larger of the first- and second-order fractions, and,
when a distance tolerance is given, the largest over the sweep of the
reflector distance: the fraction oscillates with ``z`` (the low harmonics
all share the factor ``sin^2(z - pi/4)``), so a verdict can flip with a
centimetre of distance and the worst case is what bounds the error.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from psdbound.errors import InputError
from psdbound.validation.geometry import GPS_L1_WAVELENGTH_M, Reflection, phase_scale
from psdbound.validation.jacobi_anger import Harmonics, oscillation_harmonics, rotating_harmonics
from psdbound.validation.modes import RateSource
from psdbound.validation.results import ExpansionCheck

__all__ = [
    "DEFAULT_THRESHOLD",
    "check_oscillation",
    "check_rotating",
    "power_fraction_below",
]

#: Default largest acceptable fraction of multipath power below f_c.
DEFAULT_THRESHOLD = 0.10

_SWEEP_STEPS_PER_PERIOD = 16
_SWEEP_MAX_POINTS = 2001


def power_fraction_below(frequencies_hz: ArrayLike, power: ArrayLike, cutoff_hz: float) -> float:
    """Fraction of the power at ``0 < f < f_c`` among all power at ``f > 0``.

    Parameters
    ----------
    frequencies_hz : array_like of float
        Frequencies of the lines or bins, Hz.
    power : array_like of float
        Power of each line or bin (any unit; bins must be of equal width).
    cutoff_hz : float
        Cutoff ``f_c``, Hz.

    Returns
    -------
    float
        The fraction in [0, 1]; 0 when there is no power at ``f > 0``.
    """
    f = np.asarray(frequencies_hz, dtype=np.float64)
    p = np.asarray(power, dtype=np.float64)
    ac = f > 0.0
    total = float(p[ac].sum())
    if total <= 0.0:
        return 0.0
    return float(p[ac & (f < cutoff_hz)].sum() / total)


def _check_common(cutoff_hz: float, alpha: float, threshold: float) -> None:
    if not (math.isfinite(cutoff_hz) and cutoff_hz > 0.0):
        raise InputError(f"cutoff frequency must be > 0 Hz, got {cutoff_hz}")
    if not (math.isfinite(alpha) and 0.0 < alpha < 1.0):
        raise InputError(f"reflection amplitude ratio alpha must be in (0, 1), got {alpha}")
    if not (math.isfinite(threshold) and 0.0 <= threshold <= 1.0):
        raise InputError(f"threshold must be a fraction in [0, 1], got {threshold}")


def _fraction(h: Harmonics, rate_hz: float, cutoff_hz: float) -> float:
    return power_fraction_below(h.orders * rate_hz, h.power_rad2, cutoff_hz)


def check_rotating(
    geometry: Reflection,
    *,
    cutoff_hz: float,
    rate: RateSource,
    alpha: float = 0.1,
    convention: str = "physical",
    threshold: float = DEFAULT_THRESHOLD,
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
    distance_tolerance_m: float = 0.0,
    tol: float = 1e-12,
) -> ExpansionCheck:
    """Check a cutoff with the thesis model: the geometry angle turns at ``rate``.

    Parameters
    ----------
    geometry : Reflection
        Ground or wall reflection.
    cutoff_hz : float
        High-pass cutoff ``f_c``, Hz (> 0).
    rate : RateSource
        Geometry rate (:func:`~psdbound.validation.modes.resolve_rate`).
    alpha : float, default 0.1
        Reflection amplitude ratio, in (0, 1).
    convention : {"physical", "thesis"}, default "physical"
        Phase convention for ``z``.
    threshold : float, default 0.10
        Largest acceptable fraction below ``f_c``.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.
    distance_tolerance_m : float, default 0
        If > 0, also sweep the distance over ``D +- tolerance`` (16 points
        per period of the fraction's oscillation in ``z``, at most 2001) and
        judge on the largest fraction.
    tol : float, default 1e-12
        Truncation tolerance of the expansion, rad.

    Returns
    -------
    ExpansionCheck
    """
    _check_common(cutoff_hz, alpha, threshold)
    z = geometry.z(wavelength_m=wavelength_m, convention=convention)
    first = rotating_harmonics(z, kind=geometry.kind, alpha=alpha, order=1, tol=tol)
    second = rotating_harmonics(z, kind=geometry.kind, alpha=alpha, order=2, tol=tol)
    f1 = _fraction(first, rate.frequency_hz, cutoff_hz)
    f2 = _fraction(second, rate.frequency_hz, cutoff_hz)
    rng = None
    tol_m = float(distance_tolerance_m)
    if not (math.isfinite(tol_m) and tol_m >= 0.0):
        raise InputError(f"distance tolerance must be >= 0 m, got {distance_tolerance_m}")
    if tol_m > 0.0:
        rng = _sweep(geometry, tol_m, rate, cutoff_hz, alpha, convention, wavelength_m, tol)
    notes = []
    if rate.mode is not None and rate.mode.geometry_kind != geometry.kind:
        notes.append(_pairing_note(rate, geometry))
    return ExpansionCheck(
        "rotating",
        geometry,
        convention,
        z,
        float(wavelength_m),
        rate,
        float(cutoff_hz),
        float(alpha),
        float(threshold),
        first,
        second,
        f1,
        f2,
        rng,
        tol_m,
        notes=tuple(notes),
    )


def _pairing_note(rate: RateSource, geometry: Reflection) -> str:
    assert rate.mode is not None
    return (
        f"{rate.mode.name} is a {rate.mode.axis} mode, which pairs with {rate.mode.geometry_kind}-"
        f"type reflections; {geometry.label} is {geometry.kind}-type"
    )


def _sweep(
    geometry: Reflection,
    tol_m: float,
    rate: RateSource,
    cutoff_hz: float,
    alpha: float,
    convention: str,
    wavelength_m: float,
    tol: float,
) -> tuple[float, float]:
    # the fraction has period pi in z: dD = pi lambda / (2 s)
    period_m = math.pi * wavelength_m / (2.0 * phase_scale(convention))
    n = int(
        min(_SWEEP_MAX_POINTS, max(3, math.ceil(2 * tol_m / period_m * _SWEEP_STEPS_PER_PERIOD)))
    )
    lo = max(geometry.distance_m - tol_m, 1e-9)
    values = []
    for d in np.linspace(lo, geometry.distance_m + tol_m, n | 1):
        g = Reflection(geometry.kind, float(d))
        z = g.z(wavelength_m=wavelength_m, convention=convention)
        for order in (1, 2):
            h = rotating_harmonics(z, kind=g.kind, alpha=alpha, order=order, tol=tol)
            values.append(_fraction(h, rate.frequency_hz, cutoff_hz))
    return float(min(values)), float(max(values))


def check_oscillation(
    geometry: Reflection,
    *,
    cutoff_hz: float,
    rate: RateSource,
    theta0_deg: float,
    amplitude_deg: float | None = None,
    alpha: float = 0.1,
    convention: str = "physical",
    threshold: float = DEFAULT_THRESHOLD,
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
    tol: float = 1e-12,
) -> ExpansionCheck:
    """Check a cutoff for an attitude oscillation ``theta0 + A sin(2 pi f t)``.

    Parameters
    ----------
    geometry : Reflection
        Ground or wall reflection.
    cutoff_hz : float
        High-pass cutoff ``f_c``, Hz (> 0).
    rate : RateSource
        Oscillation frequency (an aircraft mode, or any rate).
    theta0_deg : float
        Mean angle of arrival relative to the reflector, degrees in [0, 90].
    amplitude_deg : float, optional
        Oscillation amplitude, degrees (default: the mode's, else an error).
    alpha : float, default 0.1
        Reflection amplitude ratio, in (0, 1).
    convention : {"physical", "thesis"}, default "physical"
        Phase convention for ``z``.
    threshold : float, default 0.10
        Largest acceptable fraction below ``f_c``.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.
    tol : float, default 1e-12
        Truncation tolerance of the expansion, rad.

    Returns
    -------
    ExpansionCheck
    """
    _check_common(cutoff_hz, alpha, threshold)
    if amplitude_deg is None:
        if rate.mode is None:
            raise InputError(
                f"rate {rate.name!r} is not an aircraft mode: give the oscillation amplitude"
            )
        amplitude_deg = rate.mode.amplitude_deg
    amp = float(amplitude_deg)
    th0 = float(theta0_deg)
    if not (math.isfinite(th0) and 0.0 <= th0 <= 90.0):
        raise InputError(f"mean angle theta0 must be in [0, 90] degrees, got {theta0_deg}")
    if not (math.isfinite(amp) and 0.0 < amp < 90.0):
        raise InputError(f"oscillation amplitude must be in (0, 90) degrees, got {amplitude_deg}")
    z = geometry.z(wavelength_m=wavelength_m, convention=convention)
    kw = dict(
        kind=geometry.kind,
        theta0_rad=math.radians(th0),
        amplitude_rad=math.radians(amp),
        alpha=alpha,
        tol=tol,
    )
    first = oscillation_harmonics(z, order=1, **kw)  # type: ignore[arg-type]
    second = oscillation_harmonics(z, order=2, **kw)  # type: ignore[arg-type]
    notes = []
    if rate.mode is not None and rate.mode.geometry_kind != geometry.kind:
        notes.append(_pairing_note(rate, geometry))
    return ExpansionCheck(
        "oscillation",
        geometry,
        convention,
        z,
        float(wavelength_m),
        rate,
        float(cutoff_hz),
        float(alpha),
        float(threshold),
        first,
        second,
        _fraction(first, rate.frequency_hz, cutoff_hz),
        _fraction(second, rate.frequency_hz, cutoff_hz),
        theta0_deg=th0,
        amplitude_deg=amp,
        notes=tuple(notes),
    )
