"""Rates at which a reflection geometry changes: orbits and aircraft modes.

Harmonic ``k`` of the Jacobi-Anger expansion lies at ``k f_geom``, where
``f_geom`` is the rate of the geometry angle (thesis section 2.7.4):

* a static antenna: the satellite orbit, once per half sidereal day for GPS
  (the ground track repeats after two revolutions per sidereal day);
* an aircraft in flight: its attitude oscillations, the slowest of which are
  the phugoid (longitudinal: pitch) and the spiral (lateral: bank) modes.
  Longitudinal modes change the angle to horizontal surfaces (ground-type
  geometry), lateral modes the angle to vertical ones (wall-type geometry).

The built-in aircraft table holds the two Boeing 747-200 modes the thesis
uses (section 5.3, its reference [24]); amplitudes are an assumption of
psdbound (2 degrees of attitude), not from the thesis. The spiral mode of a
conventional aircraft is aperiodic (a slow divergence or convergence); as in
the thesis it is treated here as an oscillation at the quoted frequency.

The table is extended from a TOML file (:func:`load_modes`)::

    [modes.dutch_roll]
    frequency_hz = 0.15
    axis = "lateral"          # or "longitudinal"
    amplitude_deg = 1.0       # optional, default 2
    aircraft = "my aircraft"  # optional
    source = "flight manual"  # optional
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError

__all__ = [
    "AIRCRAFT_MODES",
    "DynamicMode",
    "ORBIT_RATES_HZ",
    "RateSource",
    "load_modes",
    "mode_table",
    "resolve_rate",
]


#: Geometry rates of a static antenna: one over the orbital period, Hz.
#: GPS: 2 revolutions per sidereal day; Galileo 17 in 10; GLONASS 17 in 8;
#: BeiDou MEO 13 in 7 sidereal days.
ORBIT_RATES_HZ = {
    "orbit": 2.0 / SIDEREAL_DAY_S,
    "orbit-gps": 2.0 / SIDEREAL_DAY_S,
    "orbit-galileo": 17.0 / (10.0 * SIDEREAL_DAY_S),
    "orbit-glonass": 17.0 / (8.0 * SIDEREAL_DAY_S),
    "orbit-beidou": 13.0 / (7.0 * SIDEREAL_DAY_S),
}

_AXES = {"longitudinal": "ground", "lateral": "wall"}


@dataclass(frozen=True)
class DynamicMode:
    """An aircraft attitude mode treated as a sinusoidal oscillation.

    Parameters
    ----------
    name : str
        Key in the mode table, e.g. ``'phugoid'``.
    frequency_hz : float
        Oscillation frequency, Hz (> 0).
    axis : {"longitudinal", "lateral"}
        Pitch-plane or roll/yaw-plane mode.
    amplitude_deg : float, default 2.0
        Attitude oscillation amplitude used by default, degrees (> 0). An
        assumption, not a property of the aircraft.
    aircraft : str, default ""
        Aircraft type.
    source : str, default ""
        Where the frequency comes from.

    Raises
    ------
    InputError
        Non-positive frequency or amplitude, unknown axis.
    """

    name: str
    frequency_hz: float
    axis: str
    amplitude_deg: float = 2.0
    aircraft: str = ""
    source: str = ""

    def __post_init__(self) -> None:
        f = float(self.frequency_hz)
        if not (math.isfinite(f) and f > 0.0):
            raise InputError(
                f"mode {self.name!r}: frequency_hz must be > 0, got {self.frequency_hz}"
            )
        if self.axis not in _AXES:
            raise InputError(
                f"mode {self.name!r}: axis must be 'longitudinal' or 'lateral', got {self.axis!r}"
            )
        a = float(self.amplitude_deg)
        if not (math.isfinite(a) and 0.0 < a < 90.0):
            raise InputError(
                f"mode {self.name!r}: amplitude_deg must be in (0, 90), got {self.amplitude_deg}"
            )
        object.__setattr__(self, "frequency_hz", f)
        object.__setattr__(self, "amplitude_deg", a)

    @property
    def geometry_kind(self) -> str:
        """Reflection geometry this mode pairs with: ``'ground'`` or ``'wall'``."""
        return _AXES[self.axis]

    @property
    def period_s(self) -> float:
        """Oscillation period, s."""
        return 1.0 / self.frequency_hz


_B747 = "Boeing 747-200"
_REF = "thesis section 5.3, ref. [24]"

#: Built-in aircraft modes (the thesis's Boeing 747-200 values).
AIRCRAFT_MODES: dict[str, DynamicMode] = {
    "phugoid": DynamicMode("phugoid", 5.5e-3, "longitudinal", 2.0, _B747, _REF),
    "spiral": DynamicMode("spiral", 3.1e-3, "lateral", 2.0, _B747, _REF),
}


@dataclass(frozen=True)
class RateSource:
    """The rate of the geometry angle and where it comes from.

    Attributes
    ----------
    name : str
        ``'orbit'``, a mode name, or the number as given.
    frequency_hz : float
        ``f_geom``, Hz.
    mode : DynamicMode or None
        The aircraft mode, when the rate is one.
    """

    name: str
    frequency_hz: float
    mode: DynamicMode | None = None

    @property
    def description(self) -> str:
        """Human-readable origin of the rate."""
        if self.mode is not None:
            m = self.mode
            who = f"{m.aircraft} " if m.aircraft else ""
            return f"{who}{m.name} mode ({m.axis}), {m.frequency_hz:.4g} Hz"
        if self.name in ORBIT_RATES_HZ:
            return f"{self.name}: period {1.0 / self.frequency_hz / 3600.0:.4f} h"
        return f"user rate {self.frequency_hz:.4g} Hz"


def load_modes(path: str | os.PathLike[str]) -> dict[str, DynamicMode]:
    """Read aircraft modes from a TOML file (format in the module docstring).

    Parameters
    ----------
    path : str or path-like
        TOML file with a ``[modes.<name>]`` table per mode.

    Returns
    -------
    dict of str to DynamicMode

    Raises
    ------
    InputError
        Unreadable file, invalid TOML, a missing or invalid field.
    """
    try:
        with open(path, "rb") as fh:
            data = tomllib.load(fh)
    except OSError as exc:
        raise InputError(f"cannot read mode table: {exc.strerror}", path=path) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"invalid TOML: {exc}", path=path) from None
    modes = data.get("modes")
    if not isinstance(modes, dict) or not modes:
        raise InputError("expected at least one [modes.<name>] table", path=path)
    try:
        return _modes_from_mapping(modes)
    except InputError as exc:
        raise InputError(exc.reason, path=path) from None


def _modes_from_mapping(modes: Mapping[str, Any]) -> dict[str, DynamicMode]:
    out: dict[str, DynamicMode] = {}
    allowed = {"frequency_hz", "axis", "amplitude_deg", "aircraft", "source"}
    for name, spec in modes.items():
        key = str(name).lower()
        if isinstance(spec, DynamicMode):
            out[key] = spec
            continue
        if not isinstance(spec, Mapping):
            raise InputError(f"mode {name!r}: expected a table of fields")
        unknown = set(spec) - allowed
        if unknown:
            raise InputError(f"mode {name!r}: unknown field(s) {sorted(unknown)}")
        for need in ("frequency_hz", "axis"):
            if need not in spec:
                raise InputError(f"mode {name!r}: missing {need}")
        try:
            freq = float(spec["frequency_hz"])
            amp = float(spec.get("amplitude_deg", 2.0))
        except (TypeError, ValueError):
            raise InputError(
                f"mode {name!r}: frequency_hz and amplitude_deg must be numbers"
            ) from None
        out[key] = DynamicMode(
            key,
            freq,
            str(spec["axis"]),
            amp,
            str(spec.get("aircraft", "")),
            str(spec.get("source", "")),
        )
    return out


def mode_table(
    extra: Mapping[str, Any] | str | os.PathLike[str] | None = None,
) -> dict[str, DynamicMode]:
    """Built-in aircraft modes, extended or overridden by ``extra``.

    Parameters
    ----------
    extra : mapping, path or None
        A TOML file path, or a mapping of name to :class:`DynamicMode` or to
        a dict of its fields (``frequency_hz``, ``axis``, ...).

    Returns
    -------
    dict of str to DynamicMode
        Keys in lower case.
    """
    table = dict(AIRCRAFT_MODES)
    if extra is None:
        return table
    if isinstance(extra, Mapping):
        table.update(_modes_from_mapping(extra))
    else:
        table.update(load_modes(extra))
    return table


def resolve_rate(
    spec: str | float, *, modes: Mapping[str, DynamicMode] | None = None
) -> RateSource:
    """Turn ``'orbit'``, a mode name or a number of hertz into a rate.

    Parameters
    ----------
    spec : str or float
        A key of :data:`ORBIT_RATES_HZ`, a mode name (case-insensitive), or
        a positive frequency in Hz.
    modes : mapping of str to DynamicMode, optional
        Mode table (default :data:`AIRCRAFT_MODES`).

    Returns
    -------
    RateSource

    Raises
    ------
    InputError
        Unknown name or a non-positive number.
    """
    table = AIRCRAFT_MODES if modes is None else modes
    if isinstance(spec, int | float):
        text = repr(float(spec))
    else:
        text = str(spec).strip()
    key = text.lower()
    if key in ORBIT_RATES_HZ:
        return RateSource(key, ORBIT_RATES_HZ[key])
    if key in table:
        mode = table[key]
        return RateSource(key, mode.frequency_hz, mode)
    try:
        f = float(text)
    except ValueError:
        known = ", ".join([*ORBIT_RATES_HZ, *sorted(table)])
        raise InputError(
            f"unknown rate {text!r}; expected one of {known}, or a frequency in Hz"
        ) from None
    if not (math.isfinite(f) and f > 0.0):
        raise InputError(f"rate must be a frequency > 0 Hz, got {text}")
    return RateSource(text, f)
