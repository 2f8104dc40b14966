"""Tracking arcs: the stretches of one satellite's carrier phase with constant ambiguities.

The stage between the observations (:mod:`psdbound.io`) and the isolated
multipath (:mod:`psdbound.isolation`). Public surface:

* :func:`find_arcs` -> :class:`ArcSet` of :class:`Arc` (gaps, receiver flags,
  cycle slips from the geometry-free phase, the elevation mask), with
  :class:`ArcOptions`; :func:`require_arcs` turns an empty set into one clear
  error; :data:`DEFAULT_SIGNALS` is each system's dual-frequency pair, and
  :func:`default_pair` the pair a file holds (:data:`SIGNAL_CANDIDATES`, per
  carrier in order of preference)
* :func:`add_third_carrier` reads a third carrier's phase alongside the pair
  (:data:`THIRD_SIGNALS`), for the screening's three-frequency test
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.arcs.find import (
        DEFAULT_SIGNALS,
        SIGNAL_CANDIDATES,
        Arc,
        ArcSet,
        default_pair,
        find_arcs,
        require_arcs,
    )
    from psdbound.arcs.options import ArcOptions
    from psdbound.arcs.third import THIRD_SIGNALS, add_third_carrier

__all__ = [
    "DEFAULT_SIGNALS",
    "SIGNAL_CANDIDATES",
    "THIRD_SIGNALS",
    "Arc",
    "ArcOptions",
    "ArcSet",
    "add_third_carrier",
    "default_pair",
    "find_arcs",
    "require_arcs",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "DEFAULT_SIGNALS": ("psdbound.arcs.find", "DEFAULT_SIGNALS"),
    "SIGNAL_CANDIDATES": ("psdbound.arcs.find", "SIGNAL_CANDIDATES"),
    "default_pair": ("psdbound.arcs.find", "default_pair"),
    "Arc": ("psdbound.arcs.find", "Arc"),
    "ArcSet": ("psdbound.arcs.find", "ArcSet"),
    "find_arcs": ("psdbound.arcs.find", "find_arcs"),
    "require_arcs": ("psdbound.arcs.find", "require_arcs"),
    "ArcOptions": ("psdbound.arcs.options", "ArcOptions"),
    "THIRD_SIGNALS": ("psdbound.arcs.third", "THIRD_SIGNALS"),
    "add_third_carrier": ("psdbound.arcs.third", "add_third_carrier"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
