"""Cutoff validation: how much multipath does the ionosphere high-pass remove?

A cutoff that removes multipath along with the ionosphere makes the PSD
bound optimistic. This package predicts the fraction of multipath power
below the cutoff ``f_c`` for specular ground and wall reflections (thesis section 2.7;
docs/method/validation.rst) and gives a pass/fail verdict against a
threshold (default 10 %):

* :func:`validate_cutoff` -> :class:`ValidationReport` runs everything;
* :func:`check_rotating` (the thesis's Jacobi-Anger model, the geometry
  angle turning at the orbit or mode rate) and :func:`check_oscillation`
  (an aircraft attitude oscillation) -> :class:`ExpansionCheck`;
* :func:`direct_check` -> :class:`DirectCheck`: the exact phase error
  simulated along a real satellite pass (:func:`satellite_passes`) or an
  oscillation (:func:`oscillation_track`), its tapered periodogram
  (:func:`tapered_periodogram`, from :mod:`psdbound.periodogram`) and
  fraction, independent of the expansion;
* :func:`rotating_harmonics`, :func:`oscillation_harmonics` ->
  :class:`Harmonics` with rigorous truncation bounds
  (:func:`terms_for_tolerance`, :func:`truncation_bound`);
* geometries (:class:`Reflection`, :func:`parse_geometry`) in two phase
  conventions, labelled everywhere: ``"physical"`` (``z = 4 pi D /
  lambda``) and ``"thesis"`` (``z = 2 D / lambda``);
* aircraft modes (:data:`AIRCRAFT_MODES`, :func:`mode_table`,
  :func:`load_modes`) and orbit rates (:func:`resolve_rate`);
* whole runs and files: :func:`run_validation` (what ``psdbound validate``
  does), :func:`write_validation_outputs`, :func:`validation_csv`; figures
  in :mod:`psdbound.validation.figures` (matplotlib, imported on demand);
* the reflection measured instead of assumed (GNSS-IR, from SNR):
  :func:`reflector_heights` -> :class:`ReflectorHeights`, the ground
  reflector height and amplitude ratio ``alpha`` of every rising and
  setting arc of a station (:mod:`psdbound.validation.reflectors`), and
  for one arc :func:`arc_height` -> :class:`ArcHeight` and
  :func:`amplitude_ratio` (:mod:`psdbound.validation.snr_arc`, which
  describes the method).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.periodogram import tapered_periodogram
    from psdbound.validation.cutoff import (
        DEFAULT_THRESHOLD,
        check_oscillation,
        check_rotating,
        power_fraction_below,
    )
    from psdbound.validation.direct import (
        SatellitePass,
        direct_check,
        oscillation_track,
        phase_error_rad,
        sampling_interval_s,
        satellite_passes,
    )
    from psdbound.validation.geometry import (
        CONVENTION_LABELS,
        CONVENTIONS,
        GPS_L1_WAVELENGTH_M,
        Reflection,
        parse_geometry,
        phase_scale,
    )
    from psdbound.validation.jacobi_anger import (
        Harmonics,
        bessel_tail_bound,
        closed_form_power_rad2,
        oscillation_harmonics,
        rotating_harmonics,
        series_coefficients,
        terms_for_tolerance,
        truncation_bound,
    )
    from psdbound.validation.modes import (
        AIRCRAFT_MODES,
        ORBIT_RATES_HZ,
        DynamicMode,
        RateSource,
        load_modes,
        mode_table,
        resolve_rate,
    )
    from psdbound.validation.options import ValidationOptions
    from psdbound.validation.outputs import validation_csv, write_validation_outputs
    from psdbound.validation.reflectors import ReflectorHeights, reflector_heights
    from psdbound.validation.results import DirectCheck, ExpansionCheck, ValidationReport
    from psdbound.validation.snr_arc import ArcHeight, amplitude_ratio, arc_height
    from psdbound.validation.validate import DEFAULT_THETA0_DEG, validate_cutoff
    from psdbound.validation.workflow import run_validation

__all__ = [
    "ValidationOptions",
    "AIRCRAFT_MODES",
    "CONVENTIONS",
    "CONVENTION_LABELS",
    "DEFAULT_THETA0_DEG",
    "DEFAULT_THRESHOLD",
    "GPS_L1_WAVELENGTH_M",
    "ORBIT_RATES_HZ",
    "ArcHeight",
    "DirectCheck",
    "DynamicMode",
    "ExpansionCheck",
    "Harmonics",
    "RateSource",
    "Reflection",
    "ReflectorHeights",
    "SatellitePass",
    "ValidationReport",
    "amplitude_ratio",
    "arc_height",
    "bessel_tail_bound",
    "check_oscillation",
    "check_rotating",
    "closed_form_power_rad2",
    "direct_check",
    "load_modes",
    "mode_table",
    "oscillation_harmonics",
    "oscillation_track",
    "parse_geometry",
    "phase_error_rad",
    "phase_scale",
    "power_fraction_below",
    "reflector_heights",
    "resolve_rate",
    "rotating_harmonics",
    "run_validation",
    "sampling_interval_s",
    "satellite_passes",
    "series_coefficients",
    "tapered_periodogram",
    "terms_for_tolerance",
    "truncation_bound",
    "validate_cutoff",
    "validation_csv",
    "write_validation_outputs",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "tapered_periodogram": ("psdbound.periodogram", "tapered_periodogram"),
    "DEFAULT_THRESHOLD": ("psdbound.validation.cutoff", "DEFAULT_THRESHOLD"),
    "check_oscillation": ("psdbound.validation.cutoff", "check_oscillation"),
    "check_rotating": ("psdbound.validation.cutoff", "check_rotating"),
    "power_fraction_below": ("psdbound.validation.cutoff", "power_fraction_below"),
    "SatellitePass": ("psdbound.validation.direct", "SatellitePass"),
    "direct_check": ("psdbound.validation.direct", "direct_check"),
    "oscillation_track": ("psdbound.validation.direct", "oscillation_track"),
    "phase_error_rad": ("psdbound.validation.direct", "phase_error_rad"),
    "sampling_interval_s": ("psdbound.validation.direct", "sampling_interval_s"),
    "satellite_passes": ("psdbound.validation.direct", "satellite_passes"),
    "CONVENTION_LABELS": ("psdbound.validation.geometry", "CONVENTION_LABELS"),
    "CONVENTIONS": ("psdbound.validation.geometry", "CONVENTIONS"),
    "GPS_L1_WAVELENGTH_M": ("psdbound.validation.geometry", "GPS_L1_WAVELENGTH_M"),
    "Reflection": ("psdbound.validation.geometry", "Reflection"),
    "parse_geometry": ("psdbound.validation.geometry", "parse_geometry"),
    "phase_scale": ("psdbound.validation.geometry", "phase_scale"),
    "Harmonics": ("psdbound.validation.jacobi_anger", "Harmonics"),
    "bessel_tail_bound": ("psdbound.validation.jacobi_anger", "bessel_tail_bound"),
    "closed_form_power_rad2": ("psdbound.validation.jacobi_anger", "closed_form_power_rad2"),
    "oscillation_harmonics": ("psdbound.validation.jacobi_anger", "oscillation_harmonics"),
    "rotating_harmonics": ("psdbound.validation.jacobi_anger", "rotating_harmonics"),
    "series_coefficients": ("psdbound.validation.jacobi_anger", "series_coefficients"),
    "terms_for_tolerance": ("psdbound.validation.jacobi_anger", "terms_for_tolerance"),
    "truncation_bound": ("psdbound.validation.jacobi_anger", "truncation_bound"),
    "AIRCRAFT_MODES": ("psdbound.validation.modes", "AIRCRAFT_MODES"),
    "ORBIT_RATES_HZ": ("psdbound.validation.modes", "ORBIT_RATES_HZ"),
    "DynamicMode": ("psdbound.validation.modes", "DynamicMode"),
    "RateSource": ("psdbound.validation.modes", "RateSource"),
    "load_modes": ("psdbound.validation.modes", "load_modes"),
    "mode_table": ("psdbound.validation.modes", "mode_table"),
    "resolve_rate": ("psdbound.validation.modes", "resolve_rate"),
    "ValidationOptions": ("psdbound.validation.options", "ValidationOptions"),
    "validation_csv": ("psdbound.validation.outputs", "validation_csv"),
    "write_validation_outputs": ("psdbound.validation.outputs", "write_validation_outputs"),
    "ReflectorHeights": ("psdbound.validation.reflectors", "ReflectorHeights"),
    "reflector_heights": ("psdbound.validation.reflectors", "reflector_heights"),
    "DirectCheck": ("psdbound.validation.results", "DirectCheck"),
    "ExpansionCheck": ("psdbound.validation.results", "ExpansionCheck"),
    "ValidationReport": ("psdbound.validation.results", "ValidationReport"),
    "ArcHeight": ("psdbound.validation.snr_arc", "ArcHeight"),
    "amplitude_ratio": ("psdbound.validation.snr_arc", "amplitude_ratio"),
    "arc_height": ("psdbound.validation.snr_arc", "arc_height"),
    "DEFAULT_THETA0_DEG": ("psdbound.validation.validate", "DEFAULT_THETA0_DEG"),
    "validate_cutoff": ("psdbound.validation.validate", "validate_cutoff"),
    "run_validation": ("psdbound.validation.workflow", "run_validation"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
