"""Kalman-filter tools for KF-ARAIM: the bound as a filter model, and its verification.

Public surface:

* :class:`GaussMarkovBound` -- the bound (from parameters, a
  :class:`~psdbound.spectra.BoundFit` or a ``result.json``), its PSDs,
  autocovariance and :meth:`~GaussMarkovBound.to_state_space` ``(Phi, Qd, R)``
* :func:`augment_gm_states` -> :class:`AugmentedModel` -- one Gauss-Markov
  multipath state per measurement appended to a filter's ``(F, Q, H, R)``
* :func:`analyze_covariance` -> :class:`CovarianceAnalysis` -- true vs
  filter error covariance, step by step and in steady state, for a true
  multipath given as an :class:`ErrorProcess`, a :class:`SampledPSD` or
  :class:`ErrorSequences`

Modules: :mod:`~psdbound.kalman.bound` (the bound and its state-space
export), :mod:`~psdbound.kalman.augment`, :mod:`~psdbound.kalman.covariance`
(the analysis front), :mod:`~psdbound.kalman.process` and
:mod:`~psdbound.kalman.truth` (true errors), :mod:`~psdbound.kalman.analysis`
(the result). The aviation models of the seeds (airborne sigma curves,
carrier-smoothing inflation, ``xi(tau)``, the Q-Q criterion) live in
:mod:`psdbound.aviation`.

* :class:`GaussMarkovSet` -> :meth:`~GaussMarkovSet.design` ->
  :class:`UncertainGMBound` -- a design model safe for every Gauss-Markov
  process with ``tau`` and ``sigma`` in intervals (non-stationary start,
  [Langel2021]_, [GarciaCrespillo2023]_), its export ``(phi, q, r, p0)`` and
  :func:`verify_design` (covariance analysis over a grid of true processes)
  (:mod:`psdbound.kalman.uncertain`)
* KF-ARAIM building blocks (:mod:`psdbound.kalman.kf_araim`): a
  position-velocity-clock filter with one multipath state per satellite,
  its design position covariance (:func:`predict_position_covariance`) and
  a Monte Carlo run on given multipath series
  (:func:`monte_carlo_position_covariance`)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.kalman.analysis import CovarianceAnalysis
    from psdbound.kalman.augment import AugmentedModel, augment_gm_states
    from psdbound.kalman.bound import WHITE_NOISE_MODES, GaussMarkovBound, GMStateSpace
    from psdbound.kalman.covariance import analyze_covariance
    from psdbound.kalman.error_model import Component, ErrorModel, ErrorStateSpace
    from psdbound.kalman.kf_araim import (
        PositionCovariance,
        monte_carlo_position_covariance,
        predict_position_covariance,
        pvt_model,
    )
    from psdbound.kalman.process import ErrorProcess
    from psdbound.kalman.truth import ErrorSequences, SampledPSD
    from psdbound.kalman.uncertain import (
        DesignCheck,
        GaussMarkovSet,
        UncertainGMBound,
        UncertainGMStateSpace,
        minimum_initial_variance_m2,
        verify_design,
    )

__all__ = [
    "WHITE_NOISE_MODES",
    "AugmentedModel",
    "Component",
    "CovarianceAnalysis",
    "DesignCheck",
    "ErrorModel",
    "ErrorProcess",
    "ErrorSequences",
    "ErrorStateSpace",
    "GMStateSpace",
    "GaussMarkovBound",
    "GaussMarkovSet",
    "PositionCovariance",
    "SampledPSD",
    "UncertainGMBound",
    "UncertainGMStateSpace",
    "analyze_covariance",
    "augment_gm_states",
    "minimum_initial_variance_m2",
    "monte_carlo_position_covariance",
    "predict_position_covariance",
    "pvt_model",
    "verify_design",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "CovarianceAnalysis": ("psdbound.kalman.analysis", "CovarianceAnalysis"),
    "AugmentedModel": ("psdbound.kalman.augment", "AugmentedModel"),
    "augment_gm_states": ("psdbound.kalman.augment", "augment_gm_states"),
    "WHITE_NOISE_MODES": ("psdbound.kalman.bound", "WHITE_NOISE_MODES"),
    "GaussMarkovBound": ("psdbound.kalman.bound", "GaussMarkovBound"),
    "GMStateSpace": ("psdbound.kalman.bound", "GMStateSpace"),
    "analyze_covariance": ("psdbound.kalman.covariance", "analyze_covariance"),
    "Component": ("psdbound.kalman.error_model", "Component"),
    "ErrorModel": ("psdbound.kalman.error_model", "ErrorModel"),
    "ErrorStateSpace": ("psdbound.kalman.error_model", "ErrorStateSpace"),
    "PositionCovariance": ("psdbound.kalman.kf_araim", "PositionCovariance"),
    "monte_carlo_position_covariance": (
        "psdbound.kalman.kf_araim",
        "monte_carlo_position_covariance",
    ),
    "predict_position_covariance": ("psdbound.kalman.kf_araim", "predict_position_covariance"),
    "pvt_model": ("psdbound.kalman.kf_araim", "pvt_model"),
    "ErrorProcess": ("psdbound.kalman.process", "ErrorProcess"),
    "ErrorSequences": ("psdbound.kalman.truth", "ErrorSequences"),
    "SampledPSD": ("psdbound.kalman.truth", "SampledPSD"),
    "DesignCheck": ("psdbound.kalman.uncertain", "DesignCheck"),
    "GaussMarkovSet": ("psdbound.kalman.uncertain", "GaussMarkovSet"),
    "UncertainGMBound": ("psdbound.kalman.uncertain", "UncertainGMBound"),
    "UncertainGMStateSpace": ("psdbound.kalman.uncertain", "UncertainGMStateSpace"),
    "minimum_initial_variance_m2": ("psdbound.kalman.uncertain", "minimum_initial_variance_m2"),
    "verify_design": ("psdbound.kalman.uncertain", "verify_design"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
