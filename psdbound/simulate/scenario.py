"""Simulation scenarios: every parameter of a simulated data set, and presets."""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass, field, replace
from typing import Any

from psdbound.errors import InputError

__all__ = ["IonoDisturbance", "Reflection", "MultipathModel", "Scenario", "PRESETS", "preset"]


@dataclass(frozen=True)
class Reflection:
    """A deterministic specular reflector (method.md section 3).

    Parameters
    ----------
    kind : {"ground", "wall"}
        Ground: extra path ``2 h sin(el)``; wall: ``2 d cos(el)``.
    distance_m : float
        Antenna height ``h`` above the ground, or distance ``d`` to the wall, m.
    alpha : float
        Reflected-to-direct amplitude ratio (< 1).
    """

    kind: str
    distance_m: float
    alpha: float

    def __post_init__(self) -> None:
        if self.kind not in ("ground", "wall"):
            raise InputError(f"reflection kind must be 'ground' or 'wall', got {self.kind!r}")
        if not self.distance_m > 0 or not 0 <= self.alpha < 1:
            raise InputError(
                f"reflection needs distance > 0 m and 0 <= alpha < 1; got {self.distance_m}, "
                f"{self.alpha}"
            )


@dataclass(frozen=True)
class IonoDisturbance:
    """A span of fast ionospheric phase fluctuations (ground truth for the screening).

    Inside the span the slant TEC of the chosen satellites gets a random walk
    whose 30-s increments have the standard deviation ``0.5 roti_tecu_min``
    TECU, so that ROT (TECU/min, 30 s) has the standard deviation
    ``roti_tecu_min``: the span's ROTI (Pi et al. 1997). Outside the span
    the walk is frozen, so the TEC stays continuous.

    Parameters
    ----------
    start_s : float
        Start, seconds after the scenario's start.
    duration_s : float
        Length of the span, s.
    roti_tecu_min : float
        ROTI of the fluctuations, TECU/min.
    sats : tuple of str
        Affected satellites (e.g. ``("G05", "G12")``); empty: every satellite.
    """

    start_s: float
    duration_s: float
    roti_tecu_min: float
    sats: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if not (self.start_s >= 0 and self.duration_s > 0 and self.roti_tecu_min > 0):
            raise InputError(
                "an ionospheric disturbance needs start_s >= 0 s, duration_s > 0 s and "
                f"roti_tecu_min > 0; got {self.start_s}, {self.duration_s}, {self.roti_tecu_min}"
            )


@dataclass(frozen=True)
class MultipathModel:
    """Per-signal carrier-phase error: mapped Gauss-Markov + white noise (+ reflections).

    The error of one signal is ``m(el) * (GM + WN) + sum of reflections``
    with ``m(el) = a + b exp(-el^2 / (2 c^2))`` (thesis mapping), GM a
    first-order Gauss-Markov process (``sigma_gm_m``, ``tau_s``) and WN white
    noise (``sigma_wn_m`` per sample), independent per signal and satellite.

    Parameters
    ----------
    sigma_gm_m, tau_s, sigma_wn_m : float
        Gauss-Markov standard deviation (m), time constant (s), white-noise
        standard deviation (m), at zenith scale.
    a, b, c_deg : float
        Elevation mapping parameters (c in degrees).
    reflections : tuple of Reflection
        Deterministic reflectors, exact formula ``atan2(alpha sin psi,
        1 + alpha cos psi)``.
    """

    sigma_gm_m: float = 0.003
    tau_s: float = 30.0
    sigma_wn_m: float = 0.001
    a: float = 1.0
    b: float = 9.0
    c_deg: float = 15.0
    reflections: tuple[Reflection, ...] = ()


@dataclass(frozen=True)
class Scenario:
    """Everything that defines a simulated data set (with the seed).

    Parameters
    ----------
    name : str
        File-name stem.
    lat_deg, lon_deg, height_m : float
        Antenna A position (WGS84).
    start_gps : str
        Start epoch, ISO calendar label in GPS time (``"2020-11-24T14:00:00"``).
    duration_s, interval_s : float
        Span and sampling interval, seconds.
    systems : str
        ``"G"`` (GPS L1C/L2W) or ``"GE"`` (plus Galileo L1C/L5Q).
    nav_path : str or None
        Navigation file for the geometry; None uses the nominal constellation.
    elevation_mask_deg : float
        Satellites are tracked above this elevation.
    multipath : MultipathModel
        The injected error model.
    receiver_noise_m : float
        Extra white phase noise per signal, metres (part of the truth error).
    code_noise_m : float
        Code noise at zenith, metres (scaled by the mapping).
    vtec_day_tecu, vtec_night_tecu : float
        Smooth diurnal vertical TEC (peak at 14 h local time), TECU.
    tid_amplitude_tecu, tid_period_s : float
        A travelling-disturbance term (per-satellite phase), TECU and seconds.
    disturbances : tuple of IonoDisturbance
        Spans of fast ionospheric fluctuations with a chosen ROTI (written to
        the truth JSON; drawn from their own random stream, so adding them
        changes nothing else).
    zenith_tropo_m : float
        Zenith tropospheric delay, metres (1/sin(el) mapping).
    slip_rate_per_h : float
        Cycle slips per satellite per hour (one carrier, 1-3 cycles).
    slip_lli_fraction : float
        Fraction of slips the receiver flags with the LLI bit.
    gap_rate_per_h, gap_max_s : float
        Tracking gaps per satellite per hour and their maximum length.
    dual_antenna : bool
        Also write antenna B.
    baseline_enu_m : tuple of float
        Antenna B minus antenna A, east/north/up metres.
    common_fraction : float
        Fraction of the multipath variance common to both antennas (it
        cancels in the dual-antenna difference).
    receiver_clock_s : tuple of float
        Receiver clock offsets of antennas A and B at the start, seconds.
    seed : int
        Seed of every random draw.
    """

    name: str = "sim"
    lat_deg: float = 41.84
    lon_deg: float = -87.63
    height_m: float = 180.0
    start_gps: str = "2020-11-24T14:00:00"
    duration_s: float = 4 * 3600.0
    interval_s: float = 1.0
    systems: str = "G"
    nav_path: str | None = None
    elevation_mask_deg: float = 5.0
    multipath: MultipathModel = field(default_factory=MultipathModel)
    receiver_noise_m: float = 0.0005
    code_noise_m: float = 0.3
    vtec_day_tecu: float = 25.0
    vtec_night_tecu: float = 5.0
    tid_amplitude_tecu: float = 0.3
    tid_period_s: float = 3600.0
    disturbances: tuple[IonoDisturbance, ...] = ()
    zenith_tropo_m: float = 2.4
    slip_rate_per_h: float = 0.2
    slip_lli_fraction: float = 0.5
    gap_rate_per_h: float = 0.2
    gap_max_s: float = 120.0
    dual_antenna: bool = True
    baseline_enu_m: tuple[float, float, float] = (5.0, 0.0, 0.0)
    common_fraction: float = 0.3
    receiver_clock_s: tuple[float, float] = (2.5e-4, -4.0e-4)
    seed: int = 1

    def __post_init__(self) -> None:
        if not -90.0 <= self.lat_deg <= 90.0:
            raise InputError(f"latitude must be within [-90, 90] deg, got {self.lat_deg}")
        if not self.duration_s > 0 or not self.interval_s > 0:
            raise InputError("duration and interval must be > 0 s")
        if self.duration_s / self.interval_s > 2_000_000:
            raise InputError("more than 2e6 epochs requested; shorten or decimate")
        if set(self.systems) - {"G", "E"}:
            raise InputError(f"systems must be G and/or E, got {self.systems!r}")
        if not 0.0 <= self.common_fraction <= 1.0:
            raise InputError(f"common_fraction must be in [0, 1], got {self.common_fraction}")

    def to_dict(self) -> dict[str, Any]:
        """All parameters as JSON-compatible data."""
        return json.loads(json.dumps(asdict(self)))

    def digest(self) -> str:
        """SHA-256 of the parameters (identifies a data set)."""
        blob = json.dumps(self.to_dict(), sort_keys=True).encode()
        return hashlib.sha256(blob).hexdigest()

    def replace(self, **changes: Any) -> Scenario:
        """Return a copy with some parameters changed."""
        return replace(self, **changes)


#: Named scenarios. ``demo``: 4 h at 1 Hz, GPS, two antennas 5 m apart on a
#: Chicago rooftop on the thesis's collection day, nominal constellation.
PRESETS: dict[str, Scenario] = {
    "demo": Scenario(name="psdbound-demo", seed=2020),
    "short": Scenario(name="psdbound-short", duration_s=2 * 3600.0, seed=7),
}


def preset(name: str) -> Scenario:
    """Return a named scenario (see :data:`PRESETS`)."""
    try:
        return PRESETS[name]
    except KeyError:
        raise InputError(f"unknown preset {name!r}; available: {', '.join(PRESETS)}") from None
