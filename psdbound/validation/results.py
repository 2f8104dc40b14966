"""Result containers of the cutoff validation, with text and JSON forms."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.validation.geometry import CONVENTION_LABELS, Reflection
from psdbound.validation.jacobi_anger import Harmonics
from psdbound.validation.modes import RateSource

__all__ = ["DirectCheck", "ExpansionCheck", "ValidationReport"]


def _num(x: float | None) -> float | None:
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _verdict(passed: bool) -> str:
    return "pass" if passed else "FAIL"


@dataclass(frozen=True)
class ExpansionCheck:
    """Fraction of multipath power below the cutoff from a Jacobi-Anger expansion.

    Attributes
    ----------
    model : {"rotating", "oscillation"}
        Thesis model (geometry angle turning at the rate) or an attitude
        oscillation ``theta0 + A sin(2 pi f t)``.
    geometry : Reflection
        The reflection.
    convention : {"physical", "thesis"}
        Phase convention (:data:`~psdbound.validation.geometry.CONVENTION_LABELS`).
    z : float
        Bessel argument of the geometry, rad.
    wavelength_m : float
        Carrier wavelength, m.
    rate : RateSource
        Geometry rate ``f_geom`` and its origin.
    cutoff_hz : float
        High-pass cutoff ``f_c``, Hz.
    alpha : float
        Reflection amplitude ratio.
    threshold : float
        Largest acceptable fraction of power below ``f_c``.
    first, second : Harmonics
        First- and second-order (in alpha) line spectra.
    fraction_first_order, fraction_second_order : float
        Power below ``f_c`` over the total (constant term excluded).
    fraction_range : tuple of float or None
        Min and max of the fraction (both orders) over the distance sweep
        ``D +- distance_tolerance_m``, when one was requested.
    distance_tolerance_m : float
        Half-width of the distance sweep, m (0: none).
    theta0_deg, amplitude_deg : float or None
        Mean angle and oscillation amplitude (oscillation model), degrees.
    notes : tuple of str
        Remarks (pairing of mode and geometry, etc.).
    """

    model: str
    geometry: Reflection
    convention: str
    z: float
    wavelength_m: float
    rate: RateSource
    cutoff_hz: float
    alpha: float
    threshold: float
    first: Harmonics
    second: Harmonics
    fraction_first_order: float
    fraction_second_order: float
    fraction_range: tuple[float, float] | None = None
    distance_tolerance_m: float = 0.0
    theta0_deg: float | None = None
    amplitude_deg: float | None = None
    notes: tuple[str, ...] = ()

    @property
    def fraction_below_cutoff(self) -> float:
        """Fraction used for the verdict: the largest of both orders (and the sweep)."""
        f = max(self.fraction_first_order, self.fraction_second_order)
        if self.fraction_range is not None:
            f = max(f, self.fraction_range[1])
        return float(f)

    @property
    def passed(self) -> bool:
        """True when :attr:`fraction_below_cutoff` is at most :attr:`threshold`."""
        return self.fraction_below_cutoff <= self.threshold

    @property
    def z_oscillation(self) -> float | None:
        """Equivalent thesis-form argument ``z |g'(theta0)| A`` of an oscillation, rad."""
        if self.model != "oscillation" or self.theta0_deg is None or self.amplitude_deg is None:
            return None
        th0 = math.radians(self.theta0_deg)
        slope = math.cos(th0) if self.geometry.kind == "ground" else math.sin(th0)
        return abs(self.z * slope) * math.radians(self.amplitude_deg)

    def frequencies_hz(self, harmonics: Harmonics | None = None) -> NDArray[np.float64]:
        """Frequencies of the harmonics (default: second order), Hz."""
        h = self.second if harmonics is None else harmonics
        return h.orders * self.rate.frequency_hz

    def summary(self) -> str:
        """One line: geometry, convention, z, fractions and verdict."""
        osc = ""
        if self.model == "oscillation":
            osc = f" theta0={self.theta0_deg:g}deg A={self.amplitude_deg:g}deg"
        rng = ""
        if self.fraction_range is not None:
            lo, hi = self.fraction_range
            rng = f" [{100 * lo:.2f}-{100 * hi:.2f} % over +-{self.distance_tolerance_m:g} m]"
        return (
            f"{self.model:11s} {self.geometry.label:14s} {self.convention:8s} "
            f"z={self.z:9.3f} rate={self.rate.name}{osc}: below f_c "
            f"{100 * self.fraction_first_order:6.2f} % (1st) "
            f"{100 * self.fraction_second_order:6.2f} % (2nd){rng} -> "
            f"{_verdict(self.passed)} (threshold {100 * self.threshold:g} %)"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable form (no arrays)."""
        return {
            "kind": "expansion",
            "model": self.model,
            "geometry": self.geometry.label,
            "reflection": self.geometry.kind,
            "distance_m": self.geometry.distance_m,
            "convention": self.convention,
            "z_definition": CONVENTION_LABELS[self.convention],
            "z_rad": _num(self.z),
            "wavelength_m": self.wavelength_m,
            "rate": self.rate.name,
            "rate_hz": self.rate.frequency_hz,
            "rate_description": self.rate.description,
            "cutoff_hz": self.cutoff_hz,
            "alpha": self.alpha,
            "theta0_deg": _num(self.theta0_deg),
            "amplitude_deg": _num(self.amplitude_deg),
            "z_oscillation_rad": _num(self.z_oscillation),
            "n_harmonics": int(self.second.orders.size),
            "largest_bessel_order": int(self.second.n_terms),
            "truncation_bound_rad": _num(self.second.truncation_bound_rad),
            "fraction_below_cutoff_first_order": _num(self.fraction_first_order),
            "fraction_below_cutoff_second_order": _num(self.fraction_second_order),
            "fraction_range": None
            if self.fraction_range is None
            else [_num(self.fraction_range[0]), _num(self.fraction_range[1])],
            "distance_tolerance_m": self.distance_tolerance_m,
            "fraction_below_cutoff": _num(self.fraction_below_cutoff),
            "threshold": self.threshold,
            "passed": bool(self.passed),
            "verdict": _verdict(self.passed).lower(),
            "notes": list(self.notes),
        }


@dataclass(frozen=True)
class DirectCheck:
    """Fraction of power below the cutoff from a direct time-domain simulation.

    Attributes
    ----------
    source : {"satellite", "oscillation"}
        Elevation track of a real satellite pass, or an attitude oscillation.
    label : str
        What was simulated, e.g. ``'G05 pass 06:12-12:40'``.
    geometry : Reflection
        The reflection.
    convention : {"physical", "thesis"}
        Phase convention.
    alpha : float
        Reflection amplitude ratio.
    cutoff_hz, threshold : float
        As in :class:`ExpansionCheck`.
    duration_s, dt_s : float
        Record length and sampling interval, s.
    fraction_below_cutoff : float
        Periodogram power at ``0 < f < f_c`` over the power at ``f > 0``.
    frequencies_hz, psd_rad2_hz : ndarray
        The tapered periodogram (one-sided, rad^2/Hz), for figures.
    expansion_fraction : float or None
        The matching expansion's fraction, when there is one.
    elevation_range_deg : tuple of float or None
        Min and max angle of arrival over the record, degrees.
    """

    source: str
    label: str
    geometry: Reflection
    convention: str
    alpha: float
    cutoff_hz: float
    threshold: float
    duration_s: float
    dt_s: float
    fraction_below_cutoff: float
    frequencies_hz: NDArray[np.float64] = field(repr=False)
    psd_rad2_hz: NDArray[np.float64] = field(repr=False)
    expansion_fraction: float | None = None
    elevation_range_deg: tuple[float, float] | None = None

    @property
    def passed(self) -> bool:
        """True when the fraction is at most the threshold."""
        return self.fraction_below_cutoff <= self.threshold

    def summary(self) -> str:
        """One line: what was simulated, the fraction and the verdict."""
        cmp = ""
        if self.expansion_fraction is not None:
            diff = 100 * (self.fraction_below_cutoff - self.expansion_fraction)
            cmp = f" (expansion {100 * self.expansion_fraction:.2f} %, diff {diff:+.2f} pp)"
        return (
            f"direct      {self.geometry.label:14s} {self.convention:8s} {self.label}: "
            f"below f_c {100 * self.fraction_below_cutoff:6.2f} %{cmp} -> "
            f"{_verdict(self.passed)}"
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable form (no arrays)."""
        return {
            "kind": "direct",
            "source": self.source,
            "label": self.label,
            "geometry": self.geometry.label,
            "convention": self.convention,
            "z_definition": CONVENTION_LABELS[self.convention],
            "alpha": self.alpha,
            "cutoff_hz": self.cutoff_hz,
            "duration_s": self.duration_s,
            "dt_s": self.dt_s,
            "elevation_range_deg": None
            if self.elevation_range_deg is None
            else [float(v) for v in self.elevation_range_deg],
            "fraction_below_cutoff": _num(self.fraction_below_cutoff),
            "expansion_fraction": _num(self.expansion_fraction),
            "threshold": self.threshold,
            "passed": bool(self.passed),
            "verdict": _verdict(self.passed).lower(),
        }


@dataclass(frozen=True)
class ValidationReport:
    """All checks of one cutoff.

    The overall verdict uses the physical convention only; rows in the
    thesis convention are there to compare with the thesis. Satellite-track
    simulations enter the verdict through their worst pass.

    Attributes
    ----------
    cutoff_hz, threshold, alpha, wavelength_m : float
        Common settings.
    expansion : tuple of ExpansionCheck
    direct : tuple of DirectCheck
    notes : tuple of str
    """

    cutoff_hz: float
    threshold: float
    alpha: float
    wavelength_m: float
    expansion: tuple[ExpansionCheck, ...] = ()
    direct: tuple[DirectCheck, ...] = ()
    notes: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        """True when every physical-convention check passes."""
        checks = [c for c in (*self.expansion, *self.direct) if c.convention == "physical"]
        return all(c.passed for c in checks)

    def summary(self) -> str:
        """Multi-line text report."""
        lines = [
            f"cutoff validation: f_c = {self.cutoff_hz:.4g} Hz, alpha = {self.alpha:g}, "
            f"threshold = {100 * self.threshold:g} % of multipath power below f_c, "
            f"lambda = {self.wavelength_m:.6f} m",
        ]
        for name, text in CONVENTION_LABELS.items():
            lines.append(f"  {name:8s}: {text}")
        lines += [c.summary() for c in self.expansion]
        lines += [c.summary() for c in self.direct if c.source != "satellite"]
        groups: dict[tuple[str, str], list[DirectCheck]] = {}
        for c in self.direct:
            if c.source == "satellite":
                groups.setdefault((c.geometry.label, c.convention), []).append(c)
        for (label, conv), checks in groups.items():
            fr = np.array([c.fraction_below_cutoff for c in checks])
            worst = checks[int(np.argmax(fr))]
            lines.append(
                f"direct      {label:14s} {conv:8s} satellite passes (n={len(checks)}): "
                f"below f_c median {100 * np.median(fr):6.2f} %, max {100 * fr.max():6.2f} % "
                f"({worst.label}), {sum(not c.passed for c in checks)} failing -> "
                f"{_verdict(all(c.passed for c in checks))}"
            )
        lines += [f"note: {n}" for n in self.notes]
        lines.append(
            f"verdict (physical convention): {'pass' if self.passed else 'FAIL'}"
            + ("" if self.passed else " - the cutoff removes too much multipath")
        )
        return "\n".join(lines)

    def rows(self) -> list[dict[str, Any]]:
        """One flat dict per check (the CSV table)."""
        return [c.to_dict() for c in (*self.expansion, *self.direct)]

    def to_dict(self) -> dict[str, Any]:
        """JSON-serialisable form, for the ``validation`` section of result.json."""
        return {
            "cutoff_hz": self.cutoff_hz,
            "threshold": self.threshold,
            "alpha": self.alpha,
            "wavelength_m": self.wavelength_m,
            "conventions": dict(CONVENTION_LABELS),
            "verdict_basis": "physical convention; fraction = max over orders, "
            "distance sweep and satellite passes",
            "passed": bool(self.passed),
            "verdict": "pass" if self.passed else "fail",
            "expansion": [c.to_dict() for c in self.expansion],
            "direct": [c.to_dict() for c in self.direct],
            "notes": list(self.notes),
        }
