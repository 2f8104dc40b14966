"""One call that runs every check of a cutoff: expansions and direct simulations."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from numpy.typing import ArrayLike

from psdbound.errors import InputError
from psdbound.validation.cutoff import DEFAULT_THRESHOLD, check_oscillation, check_rotating
from psdbound.validation.direct import (
    direct_check,
    oscillation_track,
    pass_track,
    sampling_interval_s,
    satellite_passes,
)
from psdbound.validation.geometry import (
    CONVENTIONS,
    GPS_L1_WAVELENGTH_M,
    Reflection,
    parse_geometry,
    phase_scale,
)
from psdbound.validation.modes import DynamicMode, RateSource, resolve_rate
from psdbound.validation.results import DirectCheck, ExpansionCheck, ValidationReport

__all__ = ["DEFAULT_THETA0_DEG", "validate_cutoff"]

#: Default mean angle of arrival relative to the reflector for aircraft modes, degrees.
DEFAULT_THETA0_DEG = 30.0


def validate_cutoff(
    geometries: Sequence[Reflection | str],
    *,
    cutoff_hz: float,
    rate: str | float | RateSource = "orbit",
    alpha: float = 0.1,
    threshold: float = DEFAULT_THRESHOLD,
    conventions: Sequence[str] = CONVENTIONS,
    wavelength_m: float = GPS_L1_WAVELENGTH_M,
    modes: Mapping[str, DynamicMode] | None = None,
    theta0_deg: float = DEFAULT_THETA0_DEG,
    amplitude_deg: float | None = None,
    n_periods: int = 128,
    orbit: Any = None,
    receiver_xyz_m: ArrayLike | None = None,
    sats: list[str] | None = None,
    system: str = "G",
    elevation_mask_deg: float = 5.0,
    min_pass_s: float = 3600.0,
    distance_tolerance_m: float = 0.0,
) -> ValidationReport:
    """Validate a high-pass cutoff against geometric multipath.

    For every geometry and convention:

    * the thesis's rotating-angle expansion at ``rate``;
    * when ``rate`` is an aircraft mode, the oscillation expansion for
      ``theta0 +- A`` and the direct simulation of the same oscillation;
    * when ``orbit`` is given, the direct simulation along every satellite
      pass over the receiver.

    Parameters
    ----------
    geometries : sequence of Reflection or str
        E.g. ``["wall:d=25", "ground:h=1.5"]``.
    cutoff_hz : float
        Cutoff ``f_c``, Hz (> 0).
    rate : str, float or RateSource, default "orbit"
        Geometry rate (:func:`~psdbound.validation.modes.resolve_rate`).
    alpha : float, default 0.1
        Reflection amplitude ratio, in (0, 1).
    threshold : float, default 0.10
        Largest acceptable fraction of multipath power below ``f_c``.
    conventions : sequence of str, default ("thesis", "physical")
        Phase conventions to run.
    wavelength_m : float, default GPS L1
        Carrier wavelength, m.
    modes : mapping, optional
        Aircraft mode table (default: the built-in one).
    theta0_deg : float, default 30
        Mean angle of arrival relative to the reflector for aircraft modes,
        degrees (an assumption; the thesis gives none).
    amplitude_deg : float, optional
        Attitude oscillation amplitude, degrees (default: the mode's).
    n_periods : int, default 128
        Oscillation periods in the direct simulation.
    orbit : Navigation or PreciseOrbit, optional
        For satellite passes (with ``receiver_xyz_m``).
    receiver_xyz_m : array_like, optional
        Receiver ECEF position, m.
    sats : list of str, optional
        Satellites for the passes (default: all of ``system``).
    system : str, default "G"
        Satellite system of the passes.
    elevation_mask_deg : float, default 5
        Elevation mask of the passes, degrees.
    min_pass_s : float, default 3600
        Shortest pass simulated, s.
    distance_tolerance_m : float, default 0
        Distance sweep of the rotating expansion
        (:func:`~psdbound.validation.cutoff.check_rotating`).

    Returns
    -------
    ValidationReport
    """
    geoms, src = _checked_inputs(geometries, conventions, rate, modes, orbit, receiver_xyz_m)
    st = _Settings(cutoff_hz, alpha, threshold, wavelength_m)
    expansion = _rotating_checks(geoms, conventions, src, st, distance_tolerance_m)
    direct: list[DirectCheck] = []
    notes: list[str] = []
    if src.frequency_hz >= cutoff_hz:
        notes.append(
            f"the geometry rate {src.frequency_hz:.4g} Hz is at or above f_c: in the rotating "
            "model every harmonic lies above f_c, so its fraction is 0 by construction"
        )
    if src.mode is not None:
        amp = src.mode.amplitude_deg if amplitude_deg is None else float(amplitude_deg)
        notes.append(
            f"{src.mode.name} oscillation: theta = {theta0_deg:g} + {amp:g} sin(2 pi "
            f"{src.frequency_hz:.4g} Hz t) deg (mean angle and amplitude are assumptions)"
        )
        for g in geoms:
            for conv in conventions:
                chk, d = _oscillation_check(g, conv, src, st, theta0_deg, amp, n_periods)
                expansion.append(chk)
                direct.append(d)
    if orbit is not None:
        passes = satellite_passes(
            orbit,
            receiver_xyz_m,  # type: ignore[arg-type]
            system=system,
            sats=sats,
            elevation_mask_deg=elevation_mask_deg,
            min_duration_s=min_pass_s,
        )
        notes.append(
            f"satellite tracks: {len(passes)} passes of {min_pass_s / 60:g} min or more above "
            f"{elevation_mask_deg:g} deg; the satellite is taken in the plane normal to the "
            "reflector (azimuth ignored, as in the thesis)"
        )
        for p in passes:
            direct.extend(_pass_checks(p, geoms, conventions, st))
    return ValidationReport(
        float(cutoff_hz),
        float(threshold),
        float(alpha),
        float(wavelength_m),
        tuple(expansion),
        tuple(direct),
        tuple(_merged_notes(notes, expansion)),
    )


def _checked_inputs(
    geometries: Sequence[Reflection | str],
    conventions: Sequence[str],
    rate: str | float | RateSource,
    modes: Mapping[str, DynamicMode] | None,
    orbit: Any,
    receiver_xyz_m: ArrayLike | None,
) -> tuple[list[Reflection], RateSource]:
    """Parse the geometries and the rate; check the conventions and the receiver position."""
    geoms = [g if isinstance(g, Reflection) else parse_geometry(g) for g in geometries]
    if not geoms:
        raise InputError("give at least one reflection geometry, e.g. 'wall:d=25'")
    for c in conventions:
        phase_scale(c)  # validates
    src = rate if isinstance(rate, RateSource) else resolve_rate(rate, modes=modes)
    if orbit is not None and receiver_xyz_m is None:
        raise InputError("a satellite track needs the receiver ECEF position")
    return geoms, src


def _merged_notes(notes: list[str], expansion: list[ExpansionCheck]) -> list[str]:
    """Append the expansions' notes not yet in ``notes``; return ``notes``."""
    for chk in expansion:
        for n in chk.notes:
            if n not in notes:
                notes.append(n)
    return notes


@dataclass(frozen=True)
class _Settings:
    """The settings every check shares: cutoff (Hz), amplitude ratio, threshold, wavelength (m)."""

    cutoff_hz: float
    alpha: float
    threshold: float
    wavelength_m: float


def _rotating_checks(
    geoms: list[Reflection],
    conventions: Sequence[str],
    src: RateSource,
    st: _Settings,
    distance_tolerance_m: float,
) -> list[ExpansionCheck]:
    """Run the rotating-angle expansion of every geometry and convention."""
    expansion: list[ExpansionCheck] = []
    for g in geoms:
        for conv in conventions:
            expansion.append(
                check_rotating(
                    g,
                    cutoff_hz=st.cutoff_hz,
                    rate=src,
                    alpha=st.alpha,
                    convention=conv,
                    threshold=st.threshold,
                    wavelength_m=st.wavelength_m,
                    distance_tolerance_m=distance_tolerance_m,
                )
            )
    return expansion


def _oscillation_check(
    g: Reflection,
    conv: str,
    src: RateSource,
    st: _Settings,
    theta0_deg: float,
    amp: float,
    n_periods: int,
) -> tuple[ExpansionCheck, DirectCheck]:
    """Check one geometry and convention under an aircraft oscillation: expansion and direct."""
    assert src.mode is not None
    chk = check_oscillation(
        g,
        cutoff_hz=st.cutoff_hz,
        rate=src,
        theta0_deg=theta0_deg,
        amplitude_deg=amp,
        alpha=st.alpha,
        convention=conv,
        threshold=st.threshold,
        wavelength_m=st.wavelength_m,
    )
    max_rate = math.radians(amp) * 2.0 * math.pi * src.frequency_hz
    dt = sampling_interval_s(
        g, max_rate_rad_s=max_rate, convention=conv, wavelength_m=st.wavelength_m
    )
    _, theta, step = oscillation_track(
        src.frequency_hz,
        theta0_deg=theta0_deg,
        amplitude_deg=amp,
        dt_s=dt,
        n_periods=n_periods,
    )
    d = direct_check(
        g,
        theta,
        step,
        cutoff_hz=st.cutoff_hz,
        alpha=st.alpha,
        convention=conv,
        threshold=st.threshold,
        wavelength_m=st.wavelength_m,
        source="oscillation",
        label=f"{src.mode.name} {n_periods} periods",
    )
    return chk, _with_expansion(d, chk.fraction_second_order)


def _pass_checks(
    p: Any, geoms: list[Reflection], conventions: Sequence[str], st: _Settings
) -> list[DirectCheck]:
    """Simulate every geometry and convention along one satellite pass."""
    direct: list[DirectCheck] = []
    for g in geoms:
        for conv in conventions:
            dt, el = pass_track(p, g, convention=conv, wavelength_m=st.wavelength_m)
            direct.append(
                direct_check(
                    g,
                    el,
                    dt,
                    cutoff_hz=st.cutoff_hz,
                    alpha=st.alpha,
                    convention=conv,
                    threshold=st.threshold,
                    wavelength_m=st.wavelength_m,
                    source="satellite",
                    label=p.label,
                )
            )
    return direct


def _with_expansion(d: DirectCheck, fraction: float) -> DirectCheck:
    from dataclasses import replace

    return replace(d, expansion_fraction=float(fraction))
