"""Physical constants used across the stages: one definition each.

``tests/test_structure.py`` checks that no other module writes these numbers.

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

__all__ = [
    "F_L1_HZ",
    "F_L2_HZ",
    "F_L5_HZ",
    "GLONASS_A_E_M",
    "GLONASS_GM_M3_S2",
    "GLONASS_J2",
    "GLONASS_OMEGA_E_RAD_S",
    "GM_BEIDOU_GALILEO_M3_S2",
    "GM_GPS_M3_S2",
    "OMEGA_E_BEIDOU_RAD_S",
    "OMEGA_E_RAD_S",
    "SIDEREAL_DAY_S",
    "SPEED_OF_LIGHT_M_S",
    "WGS84_A_M",
    "WGS84_F",
]

#: Earth rotation rate (WGS-84, GPS/Galileo/QZSS), rad/s.
OMEGA_E_RAD_S = 7.2921151467e-5
#: Earth rotation period relative to the stars, 2 pi / OMEGA_E_RAD_S, s.
SIDEREAL_DAY_S = 2.0 * math.pi / OMEGA_E_RAD_S

#: Earth rotation rate of BeiDou's interface document (BDS-SIS-ICD-B1I), rad/s.
OMEGA_E_BEIDOU_RAD_S = 7.292115e-5

#: Earth's gravitational constant GM of the GPS and QZSS interface documents
#: (IS-GPS-200, IS-QZSS), m^3/s^2.
GM_GPS_M3_S2 = 3.986005e14
#: GM of the Galileo (OS SIS ICD) and BeiDou interface documents, m^3/s^2.
GM_BEIDOU_GALILEO_M3_S2 = 3.986004418e14

#: Speed of light in vacuum, m/s (exact, SI).
SPEED_OF_LIGHT_M_S = 299792458.0

#: TAI - GPS time, s: constant by the definition of GPS time (IS-GPS-200).
TAI_MINUS_GPS_S = 19.0

#: WGS-84 semi-major axis, m (NIMA TR8350.2).
WGS84_A_M = 6378137.0
#: WGS-84 flattening (NIMA TR8350.2).
WGS84_F = 1.0 / 298.257223563

#: GPS L1 (also Galileo E1, BeiDou B1C, QZSS, SBAS L1) carrier frequency, Hz (IS-GPS-200).
F_L1_HZ = 1575.42e6
#: GPS L2 carrier frequency, Hz (IS-GPS-200).
F_L2_HZ = 1227.60e6
#: GPS L5 (also Galileo E5a, BeiDou B2a) carrier frequency, Hz (IS-GPS-705).
F_L5_HZ = 1176.45e6

#: GLONASS (PZ-90.11) gravitational constant times Earth mass, m^3/s^2 (GLONASS ICD).
GLONASS_GM_M3_S2 = 398600.4418e9
#: GLONASS second zonal harmonic J2 = -C20 (PZ-90.11, unnormalised), dimensionless.
GLONASS_J2 = 1082.62575e-6
#: GLONASS (PZ-90.11) Earth equatorial radius, m.
GLONASS_A_E_M = 6378136.0
#: Earth rotation rate used for GLONASS orbit integration, rad/s (the WGS-84
#: value, as before this module held it; the GLONASS ICD's PZ-90 value
#: 7.292115e-5 differs by 2e-14 rad/s, under a millimetre over an integration).
GLONASS_OMEGA_E_RAD_S = 7.2921151467e-5
