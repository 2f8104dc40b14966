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

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.screening.options import ScreeningOptions
    from psdbound.screening.plausibility import multipath_limit_m
    from psdbound.screening.rot import (
        ROT_INTERVAL_S,
        ROTI_BLOCK_S,
        RotiBlocks,
        geometry_free_m_per_tecu,
        rate_of_tec,
        roti_blocks,
    )
    from psdbound.screening.screen import ExcludedSpan, Screening, screen_series
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

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "multipath_limit_m": ("psdbound.screening.plausibility", "multipath_limit_m"),
    "ROT_INTERVAL_S": ("psdbound.screening.rot", "ROT_INTERVAL_S"),
    "ROTI_BLOCK_S": ("psdbound.screening.rot", "ROTI_BLOCK_S"),
    "RotiBlocks": ("psdbound.screening.rot", "RotiBlocks"),
    "geometry_free_m_per_tecu": ("psdbound.screening.rot", "geometry_free_m_per_tecu"),
    "rate_of_tec": ("psdbound.screening.rot", "rate_of_tec"),
    "roti_blocks": ("psdbound.screening.rot", "roti_blocks"),
    "ExcludedSpan": ("psdbound.screening.spans", "ExcludedSpan"),
    "Screening": ("psdbound.screening.screen", "Screening"),
    "ScreeningOptions": ("psdbound.screening.options", "ScreeningOptions"),
    "screen_series": ("psdbound.screening.screen", "screen_series"),
    "RatioNull": ("psdbound.screening.threefreq", "RatioNull"),
    "triple_combination": ("psdbound.screening.threefreq", "triple_combination"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
