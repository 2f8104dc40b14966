"""Direct simulation of the exact multipath phase error, independent of Bessel functions.

Given the angle of arrival ``theta(t)`` on an even time grid, the simulation
computes ``psi = s Delta(theta) / lambda`` and the exact phase error
``dphi = atan2(alpha sin psi, 1 + alpha cos psi)`` (thesis eq. 2.9), then
its one-sided periodogram with a Hann taper after removing the
taper-weighted mean (:func:`psdbound.periodogram.tapered_periodogram`), and
the fraction of power in the bins ``0 < f < f_c`` among all bins ``f > 0``
(:func:`~psdbound.validation.cutoff.power_fraction_below`).

Two sources of ``theta(t)``:

* :func:`satellite_passes`: the elevation of a real satellite over a static
  antenna, from a navigation or SP3 file, computed every 30 s and
  interpolated by a cubic spline to the simulation step. This is the real
  motion the thesis's rotating model idealises: the elevation rises and
  sets over a pass instead of turning uniformly, and it is slow near
  culmination and (for low passes) everywhere.
* :func:`oscillation_track`: an aircraft attitude oscillation
  ``theta(t) = theta0 + A sin(2 pi f t)`` over a whole number of periods,
  the same signal as :func:`~psdbound.validation.jacobi_anger.oscillation_harmonics`
  describes, so the two fractions can be compared.

The sampling step is chosen so that the phase ``psi`` advances at most
``pi / 4`` per sample: harmonics up to ``sin(3 psi)`` (``alpha^3 / 3``) are
then below the Nyquist frequency; :func:`direct_check` refuses coarser
grids.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from psdbound.errors import InputError, NoDataError
from psdbound.periodogram import tapered_periodogram
from psdbound.validation.cutoff import DEFAULT_THRESHOLD, power_fraction_below
from psdbound.validation.geometry import GPS_L1_WAVELENGTH_M, Reflection
from psdbound.validation.results import DirectCheck

__all__ = [
    "SatellitePass",
    "direct_check",
    "oscillation_track",
    "pass_track",
    "phase_error_rad",
    "sampling_interval_s",
    "satellite_passes",
]

_MAX_PHASE_STEP_RAD = math.pi / 4.0
_MIN_SAMPLES = 64
_MAX_HALVINGS = 6  # a pass's step is halved at most this often (64 times finer)


def phase_error_rad(
    psi_rad: ArrayLike, alpha: float, *, order: int | None = None
) -> NDArray[np.float64]:
    """Carrier-phase error of one reflection.

    Parameters
    ----------
    psi_rad : array_like of float
        Multipath phase ``psi``, rad.
    alpha : float
        Reflected-to-direct amplitude ratio, in (0, 1).
    order : int, optional
        None (default): the exact ``atan2(alpha sin psi, 1 + alpha cos psi)``;
        ``M``: the series ``sum_{m <= M} (-1)^(m+1) alpha^m sin(m psi) / m``
        (1: thesis eq. 2.10, 2: eq. 2.15).

    Returns
    -------
    ndarray of float64
        ``dphi``, rad.
    """
    psi = np.asarray(psi_rad, dtype=np.float64)
    a = float(alpha)
    if not (math.isfinite(a) and 0.0 < a < 1.0):
        raise InputError(f"reflection amplitude ratio alpha must be in (0, 1), got {alpha}")
    if order is None:
        return np.arctan2(a * np.sin(psi), 1.0 + a * np.cos(psi))
    if int(order) != order or order < 1:
        raise InputError(f"series order must be an integer >= 1, got {order}")
    out = np.zeros_like(psi)
    for m in range(1, int(order) + 1):
        out += (-1.0) ** (m + 1) * a**m / m * np.sin(m * psi)
    return out


def sampling_interval_s(
    geometry: Reflection,
    *,
    max_rate_rad_s: float,
    convention: str = "physical",
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
    max_dt_s: float = 30.0,
) -> float:
    """Largest step keeping the phase advance per sample at most ``pi / 4``.

    Parameters
    ----------
    geometry : Reflection
        The reflection.
    max_rate_rad_s : float
        Largest ``|d theta / dt|`` over the record, rad/s.
    convention : {"physical", "thesis"}, default "physical"
        Phase convention.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.
    max_dt_s : float, default 30
        Upper limit of the step, s.

    Returns
    -------
    float
        Step, s (``|d psi / dt| <= z |d theta / dt|``).
    """
    z = geometry.z(wavelength_m=wavelength_m, convention=convention)
    rate = z * abs(float(max_rate_rad_s))
    if rate == 0.0:
        return float(max_dt_s)
    return float(min(max_dt_s, _MAX_PHASE_STEP_RAD / rate))


def direct_check(
    geometry: Reflection,
    theta_rad: ArrayLike,
    dt_s: float,
    *,
    cutoff_hz: float,
    alpha: float = 0.1,
    convention: str = "physical",
    threshold: float = DEFAULT_THRESHOLD,
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
    source: str = "oscillation",
    label: str = "",
) -> DirectCheck:
    """Fraction of the exact phase error's power below ``f_c`` along a track.

    Parameters
    ----------
    geometry : Reflection
        The reflection.
    theta_rad : array_like of float
        Angle of arrival on an even grid, rad.
    dt_s : float
        Sampling interval, s.
    cutoff_hz : float
        Cutoff ``f_c``, Hz (> 0).
    alpha : float, default 0.1
        Reflection amplitude ratio, in (0, 1).
    convention : {"physical", "thesis"}, default "physical"
        Phase convention of ``psi``.
    threshold : float, default 0.10
        Largest acceptable fraction below ``f_c``.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.
    source : {"oscillation", "satellite"}, default "oscillation"
        Kind of track, for the report.
    label : str, default ""
        What was simulated, for the report.

    Returns
    -------
    DirectCheck

    Raises
    ------
    InputError
        Bad parameters, a track shorter than 64 samples, non-finite angles,
        or a step so coarse that ``psi`` advances more than ``pi / 4`` per
        sample.
    """
    th = np.asarray(theta_rad, dtype=np.float64)
    if th.ndim != 1 or th.size < _MIN_SAMPLES or not np.all(np.isfinite(th)):
        raise InputError(f"track must be >= {_MIN_SAMPLES} finite angles, got {th.size}")
    if not (math.isfinite(dt_s) and dt_s > 0.0):
        raise InputError(f"sampling interval must be > 0 s, got {dt_s}")
    if not (math.isfinite(cutoff_hz) and cutoff_hz > 0.0):
        raise InputError(f"cutoff frequency must be > 0 Hz, got {cutoff_hz}")
    psi = geometry.phase_rad(th, wavelength_m=wavelength_m, convention=convention)
    step = float(np.max(np.abs(np.diff(psi)))) if psi.size > 1 else 0.0
    if step > _MAX_PHASE_STEP_RAD:
        raise InputError(
            f"sampling step {dt_s:g} s too coarse for {geometry.label} ({convention}): psi "
            f"advances {step:.3f} rad per sample, at most pi/4 allowed; use dt <= "
            f"{dt_s * _MAX_PHASE_STEP_RAD / step:.3g} s"
        )
    dphi = phase_error_rad(psi, alpha)
    f, psd = tapered_periodogram(dphi, dt_s)
    frac = power_fraction_below(f, psd, cutoff_hz)
    el = (math.degrees(float(th.min())), math.degrees(float(th.max())))
    return DirectCheck(
        source,
        label,
        geometry,
        convention,
        float(alpha),
        float(cutoff_hz),
        float(threshold),
        float(th.size * dt_s),
        float(dt_s),
        frac,
        f,
        psd,
        elevation_range_deg=el,
    )


def oscillation_track(
    frequency_hz: float,
    *,
    theta0_deg: float,
    amplitude_deg: float,
    dt_s: float,
    n_periods: int = 128,
) -> tuple[NDArray[np.float64], NDArray[np.float64], float]:
    """Attitude oscillation ``theta0 + A sin(2 pi f t)`` over whole periods.

    Parameters
    ----------
    frequency_hz : float
        Oscillation frequency ``f``, Hz (> 0).
    theta0_deg, amplitude_deg : float
        Mean angle and amplitude, degrees.
    dt_s : float
        Largest acceptable step, s; the step used divides the period.
    n_periods : int, default 128
        Number of periods (the periodogram resolution is ``f / n_periods``).

    Returns
    -------
    t_s : ndarray of float64
        Times, s, from 0.
    theta_rad : ndarray of float64
        Angle, rad.
    dt_s : float
        The step used, s.
    """
    if not (math.isfinite(frequency_hz) and frequency_hz > 0.0):
        raise InputError(f"oscillation frequency must be > 0 Hz, got {frequency_hz}")
    if int(n_periods) != n_periods or n_periods < 1:
        raise InputError(f"number of periods must be an integer >= 1, got {n_periods}")
    per_period = max(8, math.ceil(1.0 / (frequency_hz * dt_s)))
    step = 1.0 / (frequency_hz * per_period)
    k = np.arange(per_period * int(n_periods))
    t = k * step
    theta = math.radians(theta0_deg) + math.radians(amplitude_deg) * np.sin(
        2.0 * np.pi * k / per_period
    )
    return t, theta, step


@dataclass(frozen=True)
class SatellitePass:
    """Elevation of one satellite above a mask, sampled coarsely.

    Attributes
    ----------
    sat : str
        Satellite id, e.g. ``'G05'``.
    t_gps_s : ndarray of float64
        Times, GPS seconds (even coarse step).
    elevation_rad : ndarray of float64
        Elevation, rad.
    """

    sat: str
    t_gps_s: NDArray[np.float64]
    elevation_rad: NDArray[np.float64]

    @property
    def duration_s(self) -> float:
        """Pass length, s."""
        return float(self.t_gps_s[-1] - self.t_gps_s[0])

    @cached_property
    def max_rate_rad_s(self) -> float:
        """Largest ``|d el / dt|``, rad/s."""
        return float(np.max(np.abs(np.gradient(self.elevation_rad, self.t_gps_s))))

    @cached_property
    def _spline(self) -> CubicSpline:
        """The elevation's cubic spline (built once: every reflector resamples the pass)."""
        return CubicSpline(self.t_gps_s, self.elevation_rad)

    @property
    def label(self) -> str:
        """E.g. ``'G05 06:12-12:40 GPST'`` (time of GPS day)."""

        def hm(t: float) -> str:
            s = int(round(t)) % 86400
            return f"{s // 3600:02d}:{(s % 3600) // 60:02d}"

        return f"{self.sat} {hm(self.t_gps_s[0])}-{hm(self.t_gps_s[-1])} GPST"

    def resample(self, dt_s: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Elevation on an even grid of step ``dt_s`` (cubic spline).

        Returns
        -------
        t_gps_s, elevation_rad : ndarray of float64
        """
        t = np.arange(self.t_gps_s[0], self.t_gps_s[-1], float(dt_s))
        return t, self._spline(t)


def pass_track(
    p: SatellitePass,
    geometry: Reflection,
    *,
    convention: str = "physical",
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
) -> tuple[float, NDArray[np.float64]]:
    """Sample a pass finely enough for a reflection's phase: the step and the elevations.

    The step is :func:`sampling_interval_s` at the pass's largest rate, read
    from its coarse track; the spline between coarse samples can turn faster
    (an orbit with a gap, the ends of a pass), so the step is halved while
    ``psi`` still advances more than ``pi / 4`` per sample (at most
    :data:`_MAX_HALVINGS` times; beyond, :func:`direct_check` says so).

    Parameters
    ----------
    p : SatellitePass
        The pass.
    geometry : Reflection
        The reflection.
    convention : {"physical", "thesis"}, default "physical"
        Phase convention.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.

    Returns
    -------
    dt_s : float
        Step, s.
    elevation_rad : ndarray of float64
        The pass's elevation on that step, rad.
    """
    dt = sampling_interval_s(
        geometry, max_rate_rad_s=p.max_rate_rad_s, convention=convention, wavelength_m=wavelength_m
    )
    _, el = p.resample(dt)
    for _ in range(_MAX_HALVINGS):
        psi = geometry.phase_rad(el, wavelength_m=wavelength_m, convention=convention)
        if psi.size < 2 or float(np.max(np.abs(np.diff(psi)))) <= _MAX_PHASE_STEP_RAD:
            break
        dt /= 2.0
        _, el = p.resample(dt)
    return dt, el


def _orbit_span(orbit: object) -> tuple[float, float]:
    eph = getattr(orbit, "ephemerides", None)
    if isinstance(eph, dict) and eph:
        toe = np.concatenate([e.toe_gps_s for e in eph.values()])
        return float(toe.min()) - 7200.0, float(toe.max()) + 7200.0
    t = getattr(orbit, "t_gps_s", None)
    if t is not None and np.size(t):
        return float(np.min(t)), float(np.max(t))
    raise InputError("cannot tell the time span of the orbit; give span_gps_s")


def _check_satellites(
    names: Sequence[str], held: Sequence[str], asked: Sequence[str] | None, system: str
) -> None:
    """Refuse satellites the orbit does not hold, naming them (not 'no pass')."""
    have = "".join(sorted({s[0] for s in held})) or "no satellite"
    if asked is not None:
        unknown = [s for s in asked if s not in held]
        if unknown:
            raise InputError(
                f"satellite(s) {', '.join(unknown)} not in the orbit file (it holds {have}: "
                f"{', '.join(held[:4])}{', ...' if len(held) > 4 else ''})"
            )
    elif not names:
        raise InputError(
            f"the orbit file has no satellite of system {system} (it holds {have}); choose "
            "that system or give an orbit file with it"
        )


def satellite_passes(
    orbit: object,
    receiver_xyz_m: ArrayLike,
    *,
    system: str = "G",
    sats: list[str] | None = None,
    elevation_mask_deg: float = 5.0,
    min_duration_s: float = 3600.0,
    step_s: float = 30.0,
    span_gps_s: tuple[float, float] | None = None,
) -> list[SatellitePass]:
    """Continuous passes above an elevation mask from an orbit file.

    Parameters
    ----------
    orbit : Navigation or PreciseOrbit
        From :func:`psdbound.io.read_orbit`.
    receiver_xyz_m : array_like of float, shape (3,)
        Receiver ECEF position, m.
    system : str, default "G"
        Satellite system letter (ignored when ``sats`` is given).
    sats : list of str, optional
        Satellites to use (default: every satellite of ``system``).
    elevation_mask_deg : float, default 5
        Elevation mask, degrees.
    min_duration_s : float, default 3600
        Shortest pass kept, s.
    step_s : float, default 30
        Step of the elevation computation, s.
    span_gps_s : (float, float), optional
        Time span, GPS seconds (default: the orbit's).

    Returns
    -------
    list of SatellitePass
        In satellite then time order.

    Raises
    ------
    NoDataError
        No pass meets the mask and minimum duration.
    """
    from psdbound.io.geometry import satellite_azel

    rx = np.asarray(receiver_xyz_m, dtype=np.float64)
    if rx.shape != (3,) or not np.all(np.isfinite(rx)) or np.linalg.norm(rx) < 6.0e6:
        raise InputError(f"receiver position must be 3 finite ECEF metres near the Earth, got {rx}")
    t0, t1 = _orbit_span(orbit) if span_gps_s is None else span_gps_s
    t = np.arange(t0, t1 + step_s / 2, step_s)
    held = list(orbit.satellites)  # type: ignore[attr-defined]
    names = list(sats) if sats is not None else [s for s in held if s.startswith(system)]
    _check_satellites(names, held, sats, system)
    mask = math.radians(elevation_mask_deg)
    out: list[SatellitePass] = []
    for sat in names:
        _, el_deg = satellite_azel(orbit, sat, t, rx)  # type: ignore[arg-type]
        el = np.radians(el_deg)
        up = np.isfinite(el) & (el > mask)
        edges = np.flatnonzero(np.diff(np.concatenate([[0], up.astype(np.int8), [0]])))
        for a, b in edges.reshape(-1, 2):
            if (b - a - 1) * step_s >= min_duration_s:
                out.append(SatellitePass(sat, t[a:b], el[a:b]))
    if not out:
        raise NoDataError(
            f"no satellite pass of {min_duration_s / 60:g} min or more above "
            f"{elevation_mask_deg:g} deg elevation"
        )
    return out
