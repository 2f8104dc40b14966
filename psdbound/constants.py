"""Physical constants used across the stages: one definition each.

Every stage that needs the Earth's rotation or the sidereal day imports it
from here, at the bottom of the import graph (this module imports nothing).

``OMEGA_E_RAD_S``
    The Earth's rotation rate of WGS-84 and of the GPS, Galileo and QZSS
    interface documents, rad/s (IS-GPS-200; BeiDou's 7.292115e-5 is kept
    per system in :mod:`psdbound.io.ephemeris`).
``SIDEREAL_DAY_S``
    The Earth's rotation period relative to the stars at that rate,
    ``2 pi / OMEGA_E_RAD_S`` = 86164.0989 s. The mean sidereal day counted
    from the equinox is 86164.0905 s, 8 ms shorter (precession); the stages
    use this period for the repeat of satellite geometry, where the
    difference is immaterial. (Two values were in use before, 86164.0905 s
    in the cutoff validation and 86164.0989 s elsewhere.)
"""

from __future__ import annotations

import math

__all__ = ["OMEGA_E_RAD_S", "SIDEREAL_DAY_S"]

#: Earth rotation rate (WGS-84, GPS/Galileo/QZSS), rad/s.
OMEGA_E_RAD_S = 7.2921151467e-5
#: Earth rotation period relative to the stars, 2 pi / OMEGA_E_RAD_S, s.
SIDEREAL_DAY_S = 2.0 * math.pi / OMEGA_E_RAD_S
