"""Screening of the isolated multipath: residual ionosphere and physical plausibility.

Stage between isolation and windowing (data flow: observations -> arcs ->
multipath series -> **screening** -> windows -> PSDs -> bound).

Public surface:

* :func:`screen_series` -> :class:`Screening` (kept series, excluded spans),
  :class:`ScreeningOptions`, :class:`ExcludedSpan`
* ROT/ROTI: :func:`rate_of_tec`, :func:`roti_blocks`,
  :func:`geometry_free_m_per_tecu`
* the carrier-multipath limit: :func:`multipath_limit_m`
* three carriers: :func:`triple_combination`, :class:`RatioNull`
  (:mod:`psdbound.screening.threefreq`)
"""

from __future__ import annotations

from psdbound.screening.plausibility import multipath_limit_m
from psdbound.screening.rot import (
    ROT_INTERVAL_S,
    ROTI_BLOCK_S,
    RotiBlocks,
    geometry_free_m_per_tecu,
    rate_of_tec,
    roti_blocks,
)
from psdbound.screening.screen import ExcludedSpan, Screening, ScreeningOptions, screen_series
from psdbound.screening.threefreq import RatioNull, triple_combination

__all__ = [
    "ROTI_BLOCK_S",
    "ROT_INTERVAL_S",
    "ExcludedSpan",
    "RatioNull",
    "RotiBlocks",
    "Screening",
    "ScreeningOptions",
    "geometry_free_m_per_tecu",
    "multipath_limit_m",
    "rate_of_tec",
    "roti_blocks",
    "screen_series",
    "triple_combination",
]
