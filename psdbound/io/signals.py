"""Carrier frequencies and wavelengths of GNSS signals, by RINEX code.

Frequencies in hertz from the systems' interface-control documents.
GLONASS FDMA carriers depend on the satellite's frequency channel ``k``
(RINEX 3 observation header ``GLONASS SLOT / FRQ #``, or the GLONASS records
of a navigation file: :attr:`psdbound.io.Navigation.glonass_channels`, merged
by :meth:`psdbound.io.Observations.with_glonass_channels`).
"""

from __future__ import annotations

from collections.abc import Mapping

from psdbound.constants import F_L1_HZ, F_L2_HZ, F_L5_HZ, SPEED_OF_LIGHT_M_S
from psdbound.errors import InputError

__all__ = [
    "carrier_frequency_hz",
    "wavelength_m",
    "RINEX2_TO_RINEX3",
]

_L1, _L2, _L5 = F_L1_HZ, F_L2_HZ, F_L5_HZ

_F = {
    "G": {"1": _L1, "2": _L2, "5": _L5},
    "E": {"1": _L1, "5": _L5, "7": 1207.14e6, "8": 1191.795e6, "6": 1278.75e6},
    "C": {
        "1": _L1,
        "2": 1561.098e6,
        "5": _L5,
        "7": 1207.14e6,
        "8": 1191.795e6,
        "6": 1268.52e6,
    },
    "J": {"1": _L1, "2": _L2, "5": _L5, "6": 1278.75e6},
    "S": {"1": _L1, "5": _L5},
    "I": {"5": _L5, "9": 2492.028e6, "1": _L1},
    "R": {"4": 1600.995e6, "6": 1248.06e6, "3": 1202.025e6},
}
_GLO_FDMA = {"1": (1602.0e6, 0.5625e6), "2": (1246.0e6, 0.4375e6)}

#: Conventional RINEX 3 code for each RINEX 2 observation code (GPS).
#: RINEX 2 "L2"/"P2" of geodetic receivers is the semi-codeless P(Y) signal (W).
RINEX2_TO_RINEX3 = {
    "L1": "L1C",
    "L2": "L2W",
    "L5": "L5X",
    "C1": "C1C",
    "P1": "C1W",
    "P2": "C2W",
    "C2": "C2L",
    "C5": "C5X",
    "D1": "D1C",
    "D2": "D2W",
    "S1": "S1C",
    "S2": "S2W",
    "S5": "S5X",
}


def carrier_frequency_hz(
    sat: str, code: str, glonass_channels: Mapping[str, int] | None = None
) -> float:
    """Return the carrier frequency of a signal in hertz.

    Parameters
    ----------
    sat : str
        Satellite identifier such as ``"G05"`` or ``"R12"``.
    code : str
        RINEX observation code (``"L1C"``, ``"C2W"``; RINEX 2 ``"L1"``); only
        the band digit (second character) matters.
    glonass_channels : mapping of str to int, optional
        GLONASS frequency channel per satellite (``{"R01": 1, ...}``),
        required for GLONASS FDMA bands 1 and 2.

    Returns
    -------
    float
        Carrier frequency in Hz.

    Raises
    ------
    InputError
        If the system/band is unknown or a GLONASS channel is missing.
    """
    system, band = sat[0], code[1:2]
    if system == "R" and band in _GLO_FDMA:
        if not glonass_channels or sat not in glonass_channels:
            raise InputError(
                f"no GLONASS frequency channel known for {sat} (signal {code}); it comes from "
                "the observation header (GLONASS SLOT / FRQ #) or the GLONASS records of a "
                "navigation file (Observations.with_glonass_channels)"
            )
        f0, df = _GLO_FDMA[band]
        return f0 + glonass_channels[sat] * df
    try:
        return _F[system][band]
    except KeyError:
        raise InputError(f"unknown carrier for system {system!r} band {band!r} ({code})") from None


def wavelength_m(sat: str, code: str, glonass_channels: Mapping[str, int] | None = None) -> float:
    """Return the carrier wavelength in metres (see :func:`carrier_frequency_hz`)."""
    return SPEED_OF_LIGHT_M_S / carrier_frequency_hz(sat, code, glonass_channels)
