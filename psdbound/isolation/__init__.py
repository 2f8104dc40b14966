"""Multipath isolation: dual-frequency (DF) and dual-antenna (DA) pipelines.

Public surface:

* :func:`isolate_dual_frequency` (arcs -> :class:`MultipathSeries`)
* :func:`isolate_dual_antenna` (two observation files -> :class:`MultipathSeries`)
* :func:`isolate_code_multipath` (observations -> code multipath by carrier
  levelling, one code or ionosphere-free pair, as a :class:`MultipathSeries`),
  :func:`rms_by_satellite`, :func:`level_shifts` (steps that split a levelling arc)
* :func:`estimate_baseline_correction`, :func:`baseline_note` (the dual-antenna
  baseline from the double differences), :func:`long_baseline_note` (what a
  long one leaves in them)
* :class:`HighPass` (zero-phase high-pass designs and edge handling)
* :func:`filter_safety_check` (Lomb-Scargle power removed below/above f_c)

The method: docs/method/isolation.rst.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.isolation.baseline import (
        BaselineEstimate,
        baseline_note,
        estimate_baseline_correction,
        long_baseline_note,
    )
    from psdbound.isolation.code import isolate_code_multipath, level_shifts, rms_by_satellite
    from psdbound.isolation.dual_antenna import DA_SCALING, isolate_dual_antenna
    from psdbound.isolation.dual_frequency import DF_SCALING, isolate_dual_frequency
    from psdbound.isolation.filters import FILTER_KINDS, HighPass
    from psdbound.isolation.safety import SafetyCheck, filter_safety_check
    from psdbound.isolation.series import ArcView, MultipathSeries

__all__ = [
    "ArcView",
    "BaselineEstimate",
    "DA_SCALING",
    "DF_SCALING",
    "FILTER_KINDS",
    "HighPass",
    "MultipathSeries",
    "SafetyCheck",
    "baseline_note",
    "long_baseline_note",
    "estimate_baseline_correction",
    "filter_safety_check",
    "isolate_code_multipath",
    "level_shifts",
    "isolate_dual_antenna",
    "isolate_dual_frequency",
    "rms_by_satellite",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "BaselineEstimate": ("psdbound.isolation.baseline", "BaselineEstimate"),
    "baseline_note": ("psdbound.isolation.baseline", "baseline_note"),
    "long_baseline_note": ("psdbound.isolation.baseline", "long_baseline_note"),
    "estimate_baseline_correction": ("psdbound.isolation.baseline", "estimate_baseline_correction"),
    "isolate_code_multipath": ("psdbound.isolation.code", "isolate_code_multipath"),
    "level_shifts": ("psdbound.isolation.code", "level_shifts"),
    "rms_by_satellite": ("psdbound.isolation.code", "rms_by_satellite"),
    "DA_SCALING": ("psdbound.isolation.dual_antenna", "DA_SCALING"),
    "isolate_dual_antenna": ("psdbound.isolation.dual_antenna", "isolate_dual_antenna"),
    "DF_SCALING": ("psdbound.isolation.dual_frequency", "DF_SCALING"),
    "isolate_dual_frequency": ("psdbound.isolation.dual_frequency", "isolate_dual_frequency"),
    "FILTER_KINDS": ("psdbound.isolation.filters", "FILTER_KINDS"),
    "HighPass": ("psdbound.isolation.filters", "HighPass"),
    "SafetyCheck": ("psdbound.isolation.safety", "SafetyCheck"),
    "filter_safety_check": ("psdbound.isolation.safety", "filter_safety_check"),
    "ArcView": ("psdbound.isolation.series", "ArcView"),
    "MultipathSeries": ("psdbound.isolation.series", "MultipathSeries"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
