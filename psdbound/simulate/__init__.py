"""Observation simulator with ground truth, and the embedded demo data set.

Public surface:

* :class:`Scenario`, :class:`MultipathModel`, :class:`Reflection`,
  :class:`IonoDisturbance`, :func:`preset`
* :func:`simulate` -> :class:`SimulationResult` (RINEX 3 obs + nav + truth files)
* :func:`demo_data` -> :class:`DemoData` (the cached demo, generated on first use)
* :func:`gauss_markov` (exact stationary GMRP sequences)
"""

from __future__ import annotations

from psdbound.simulate.demo import DemoData, cache_dir, demo_data
from psdbound.simulate.scenario import (
    PRESETS,
    IonoDisturbance,
    MultipathModel,
    Reflection,
    Scenario,
    preset,
)
from psdbound.simulate.simulator import SimulationResult, gauss_markov, simulate

__all__ = [
    "PRESETS",
    "DemoData",
    "IonoDisturbance",
    "MultipathModel",
    "Reflection",
    "Scenario",
    "SimulationResult",
    "cache_dir",
    "demo_data",
    "gauss_markov",
    "preset",
    "simulate",
]
