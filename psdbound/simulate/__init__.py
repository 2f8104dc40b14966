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

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
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

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "DemoData": ("psdbound.simulate.demo", "DemoData"),
    "cache_dir": ("psdbound.simulate.demo", "cache_dir"),
    "demo_data": ("psdbound.simulate.demo", "demo_data"),
    "MAX_MULTIPATH_M": ("psdbound.simulate.scenario", "MAX_MULTIPATH_M"),
    "MULTIPATH_SPEC_EXAMPLE": ("psdbound.simulate.scenario", "MULTIPATH_SPEC_EXAMPLE"),
    "PRESETS": ("psdbound.simulate.scenario", "PRESETS"),
    "IonoDisturbance": ("psdbound.simulate.scenario", "IonoDisturbance"),
    "MultipathModel": ("psdbound.simulate.scenario", "MultipathModel"),
    "Reflection": ("psdbound.simulate.scenario", "Reflection"),
    "Scenario": ("psdbound.simulate.scenario", "Scenario"),
    "preset": ("psdbound.simulate.scenario", "preset"),
    "SimulationResult": ("psdbound.simulate.simulator", "SimulationResult"),
    "gauss_markov": ("psdbound.simulate.simulator", "gauss_markov"),
    "simulate": ("psdbound.simulate.simulator", "simulate"),
    "TruthComparison": ("psdbound.simulate.truth", "TruthComparison"),
    "compare_to_truth": ("psdbound.simulate.truth", "compare_to_truth"),
    "truth_model": ("psdbound.simulate.truth", "truth_model"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
