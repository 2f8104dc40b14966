"""Multipath isolation: dual-frequency (DF) and dual-antenna (DA) pipelines.

Public surface:

* :func:`isolate_dual_frequency` (arcs -> :class:`MultipathSeries`)
* :func:`isolate_dual_antenna` (two observation files -> :class:`MultipathSeries`)
* :func:`isolate_code_multipath` (observations -> code multipath by carrier
  levelling, one code or ionosphere-free pair, as a :class:`MultipathSeries`),
  :func:`rms_by_satellite`, :func:`level_shifts` (steps that split a levelling arc)
* :func:`estimate_baseline_correction`, :func:`baseline_note` (the dual-antenna
  baseline from the double differences)
* :class:`HighPass` (zero-phase high-pass designs and edge handling)
* :func:`filter_safety_check` (Lomb-Scargle power removed below/above f_c)

The method: docs/method/isolation.rst.
"""

from __future__ import annotations

from psdbound.isolation.baseline import (
    BaselineEstimate,
    baseline_note,
    estimate_baseline_correction,
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
    "estimate_baseline_correction",
    "filter_safety_check",
    "isolate_code_multipath",
    "level_shifts",
    "isolate_dual_antenna",
    "isolate_dual_frequency",
    "rms_by_satellite",
]
