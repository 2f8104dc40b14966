"""Observation simulator with ground truth, and the embedded demo data set.

Public surface:

* :class:`Scenario`, :class:`MultipathModel`, :class:`Reflection`,
  :class:`IonoDisturbance`, :func:`preset`; text forms
  :meth:`Scenario.from_toml` / :meth:`Scenario.to_toml` and
  :meth:`MultipathModel.from_spec` (``"sigma_gm_m=0.004,tau_s=120,mapping=1,12,10"``)
* :func:`simulate` -> :class:`SimulationResult` (RINEX 3 obs + nav + truth files)
* :func:`truth_model` (the PSD a bound on the mapped DF series must cover) and
  :func:`compare_to_truth` -> :class:`TruthComparison`
* :func:`demo_data` -> :class:`DemoData` (the cached demo, generated on first use)
* :func:`gauss_markov` (exact stationary GMRP sequences)
"""

from __future__ import annotations

from psdbound.simulate.demo import DemoData, cache_dir, demo_data
from psdbound.simulate.scenario import (
    MAX_MULTIPATH_M,
    MULTIPATH_SPEC_EXAMPLE,
    PRESETS,
    IonoDisturbance,
    MultipathModel,
    Reflection,
    Scenario,
    preset,
)
from psdbound.simulate.simulator import SimulationResult, gauss_markov, simulate
from psdbound.simulate.truth import TruthComparison, compare_to_truth, truth_model

__all__ = [
    "MAX_MULTIPATH_M",
    "MULTIPATH_SPEC_EXAMPLE",
    "PRESETS",
    "DemoData",
    "IonoDisturbance",
    "MultipathModel",
    "Reflection",
    "Scenario",
    "SimulationResult",
    "TruthComparison",
    "cache_dir",
    "compare_to_truth",
    "demo_data",
    "gauss_markov",
    "preset",
    "simulate",
    "truth_model",
]
