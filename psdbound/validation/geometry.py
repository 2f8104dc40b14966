"""Specular reflection geometries and the two phase conventions.

Two limit cases of the thesis (section 2.7, equations 2.7-2.8; see
docs/method/validation.rst), for a direct and a reflected ray arriving parallel, at angle
``theta`` above the horizontal reference of the reflector:

``ground``
    horizontal reflector at height ``h`` below the antenna:
    ``Delta = 2 h sin(theta)``;
``wall``
    vertical reflector at horizontal distance ``d`` from the antenna, the
    satellite in the plane normal to the wall: ``Delta = 2 d cos(theta)``.

Both are written ``Delta = 2 D g(theta)`` with ``D`` the characteristic
distance (m) and ``g = sin`` (ground) or ``cos`` (wall). The multipath phase
is ``psi = s Delta / lambda`` with the scale ``s`` fixed by the convention:

``"physical"``
    ``s = 2 pi``: ``psi`` is the carrier phase difference in radians, and
    the Bessel argument is ``z = 4 pi D / lambda`` (radians);
``"thesis"``
    ``s = 1``: the thesis defines ``psi = Delta / lambda`` (a path difference
    in cycles) but then uses it as a phase in ``sin``, giving
    ``z = 2 D / lambda`` (thesis eq. 2.10). This is reproduced for
    comparison; it understates the phase rate by ``2 pi``.

The azimuth of the satellite relative to the wall is not modelled (the
thesis's two-dimensional picture); a real wall sees ``Delta = 2 d cos(theta)
cos(az - az_normal)``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import F_L1_HZ, SPEED_OF_LIGHT_M_S
from psdbound.errors import InputError

__all__ = [
    "CONVENTIONS",
    "CONVENTION_LABELS",
    "GEOMETRY_KINDS",
    "GPS_L1_WAVELENGTH_M",
    "Reflection",
    "parse_geometry",
    "phase_scale",
]

#: GPS L1 carrier wavelength, m (c / 1575.42 MHz).
GPS_L1_WAVELENGTH_M = SPEED_OF_LIGHT_M_S / F_L1_HZ

#: Phase conventions, see the module docstring.
CONVENTIONS = ("thesis", "physical")

#: One-line description of each convention, for reports.
CONVENTION_LABELS = {
    "thesis": "z = 2 D / lambda (thesis eq. 2.10: path difference in cycles used as a phase)",
    "physical": "z = 4 pi D / lambda (phase difference psi = 2 pi Delta / lambda, radians)",
}

#: Reflection kinds and the name of their distance parameter.
GEOMETRY_KINDS = {"ground": "h", "wall": "d"}

# the aircraft axis whose attitude oscillation changes each geometry's angle
_AXIS = {"ground": "longitudinal", "wall": "lateral"}

_SYNTAX = re.compile(r"^\s*([A-Za-z]+)\s*:\s*([A-Za-z]+)\s*=\s*(\S+)\s*$")


def phase_scale(convention: str) -> float:
    """Return ``s`` in ``psi = s Delta / lambda`` for a phase convention.

    Parameters
    ----------
    convention : {"physical", "thesis"}
        See the module docstring.

    Returns
    -------
    float
        ``2 pi`` for ``"physical"``, ``1`` for ``"thesis"``.

    Raises
    ------
    InputError
        Unknown convention.
    """
    if convention == "physical":
        return 2.0 * math.pi
    if convention == "thesis":
        return 1.0
    raise InputError(f"unknown phase convention {convention!r}; expected one of {CONVENTIONS}")


@dataclass(frozen=True)
class Reflection:
    """One specular reflection geometry.

    Parameters
    ----------
    kind : {"ground", "wall"}
        Horizontal (``Delta = 2 h sin theta``) or vertical
        (``Delta = 2 d cos theta``) reflector.
    distance_m : float
        ``h`` (ground: antenna height above the reflector) or ``d`` (wall:
        horizontal distance to the reflector), m, finite and > 0.

    Raises
    ------
    InputError
        Unknown kind, or a distance that is not finite and positive.
    """

    kind: str
    distance_m: float

    def __post_init__(self) -> None:
        if self.kind not in GEOMETRY_KINDS:
            raise InputError(
                f"unknown reflection geometry {self.kind!r}; expected 'ground' or 'wall'"
            )
        d = float(self.distance_m)
        if not math.isfinite(d) or d <= 0.0:
            name = GEOMETRY_KINDS[self.kind]
            raise InputError(
                f"{self.kind} geometry: {name} must be a finite distance > 0 m, "
                f"got {self.distance_m}"
            )
        object.__setattr__(self, "distance_m", d)

    @property
    def label(self) -> str:
        """Text form accepted by :func:`parse_geometry`, e.g. ``'wall:d=25'``."""
        return f"{self.kind}:{GEOMETRY_KINDS[self.kind]}={self.distance_m:g}"

    @property
    def axis(self) -> str:
        """Aircraft axis whose attitude modes change this geometry's angle.

        ``'longitudinal'`` (pitch: phugoid, short period) for ground-type,
        ``'lateral'`` (bank: spiral, Dutch roll) for wall-type reflections
        (thesis section 5.3).
        """
        return _AXIS[self.kind]

    def path_delay_m(self, theta_rad: ArrayLike) -> NDArray[np.float64]:
        """Extra path length of the reflected ray.

        Parameters
        ----------
        theta_rad : array_like of float
            Angle of arrival above the horizontal reference, rad.

        Returns
        -------
        ndarray of float64
            ``Delta``, m: ``2 h sin(theta)`` or ``2 d cos(theta)``.
        """
        th = np.asarray(theta_rad, dtype=np.float64)
        g = np.sin(th) if self.kind == "ground" else np.cos(th)
        return 2.0 * self.distance_m * g

    def phase_rad(
        self,
        theta_rad: ArrayLike,
        *,
        wavelength_m: float = GPS_L1_WAVELENGTH_M,
        convention: str = "physical",
    ) -> NDArray[np.float64]:
        """Multipath phase ``psi = s Delta / lambda`` (see :func:`phase_scale`).

        Parameters
        ----------
        theta_rad : array_like of float
            Angle of arrival, rad.
        wavelength_m : float, default GPS L1
            Carrier wavelength, m.
        convention : {"physical", "thesis"}, default "physical"
            Phase convention.

        Returns
        -------
        ndarray of float64
            ``psi``, rad (in the thesis convention: the cycle count used as
            radians).
        """
        return phase_scale(convention) * self.path_delay_m(theta_rad) / float(wavelength_m)

    def z(
        self, *, wavelength_m: float = GPS_L1_WAVELENGTH_M, convention: str = "physical"
    ) -> float:
        """Bessel argument ``z`` of the Jacobi-Anger expansion.

        Parameters
        ----------
        wavelength_m : float, default GPS L1
            Carrier wavelength, m.
        convention : {"physical", "thesis"}, default "physical"
            ``4 pi D / lambda`` or the thesis's ``2 D / lambda``.

        Returns
        -------
        float
            ``z``, rad, such that ``psi = z sin(theta)`` (ground) or
            ``z cos(theta)`` (wall).
        """
        wl = float(wavelength_m)
        if not math.isfinite(wl) or wl <= 0.0:
            raise InputError(f"wavelength must be a finite value > 0 m, got {wavelength_m}")
        return phase_scale(convention) * 2.0 * self.distance_m / wl


def parse_geometry(text: str) -> Reflection:
    """Parse a geometry such as ``'wall:d=25'`` or ``'ground:h=1.5'``.

    Parameters
    ----------
    text : str
        ``KIND:NAME=METRES`` with KIND ``ground`` (NAME ``h``) or ``wall``
        (NAME ``d``); case-insensitive, spaces allowed around separators.

    Returns
    -------
    Reflection

    Raises
    ------
    InputError
        Malformed text, an unknown kind, a parameter name that does not
        belong to the kind, or a distance that is not a positive number.
    """
    m = _SYNTAX.match(text)
    if m is None:
        raise InputError(
            f"cannot parse geometry {text!r}; expected e.g. 'wall:d=25' or 'ground:h=1.5' "
            "(distances in metres)"
        )
    kind, name, value = m.group(1).lower(), m.group(2).lower(), m.group(3)
    if kind not in GEOMETRY_KINDS:
        raise InputError(
            f"unknown reflection geometry {kind!r} in {text!r}; expected 'ground' or 'wall'"
        )
    want = GEOMETRY_KINDS[kind]
    if name != want:
        raise InputError(
            f"{kind} geometry takes {want}=<metres>, got {name!r} in {text!r} "
            f"(e.g. '{kind}:{want}={'1.5' if kind == 'ground' else '25'}')"
        )
    try:
        distance = float(value)
    except ValueError:
        raise InputError(f"geometry {text!r}: {want} must be a number of metres") from None
    return Reflection(kind, distance)
