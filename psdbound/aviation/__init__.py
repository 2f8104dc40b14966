"""Aviation integrity tools around a multipath bound (issue 21).

* :mod:`~psdbound.aviation.overbound` -- Gaussian overbounds (two-step and
  CDF/paired) of sample error distributions per elevation bin,
  :func:`overbound_by_elevation` -> :class:`OverboundResult`;
* :mod:`~psdbound.aviation.budget` -- the LADGNSS/GBAS error budget of
  seed 004 (ground, airborne, ionosphere, troposphere sigmas vs elevation
  and smoothing time) and the vertical protection level;
* :mod:`~psdbound.aviation.geometry` -- that VPL over time for a satellite
  geometry from a navigation/SP3 file or the nominal GPS / Galileo
  constellations: :func:`sky_over` -> :class:`Sky`, :func:`vpl_series` ->
  :class:`VplSeries` (``vpl.json``, ``vpl.png``: :func:`write_vpl_series`),
  :func:`nominal_orbit`;
* :mod:`~psdbound.aviation.bias` -- a constant range bias propagated
  through a linear Kalman filter to the position error, and the probability
  that the horizontal error exceeds an alert limit (seed 003);
* :mod:`~psdbound.aviation.files` -- sample input and the overbound's
  ``overbound.json`` and Q-Q figure;
* :mod:`~psdbound.aviation.code_samples` -- code multipath by carrier
  levelling straight from RINEX files (:func:`code_multipath_from_files`)
  and its description for a result (:func:`describe_code_series`), its
  overbound with sparse elevation bins named (:func:`overbound_code_series`);
* :mod:`~psdbound.aviation.options` -- :class:`CodeMultipathOptions`, the
  ``[code_multipath]`` section of a fit.

* :mod:`~psdbound.aviation.airborne` -- airborne (AAD-A) sigma curves and the
  iono-free factor (seeds 000, 001);
* :mod:`~psdbound.aviation.smoothing` -- carrier-smoothing inflation, the
  Hatch filter variance and the smoothing-time ratio ``xi(tau)`` (seeds 000,
  001, 004);
* :mod:`~psdbound.aviation.qq` -- the Q-Q criterion of seed 001;
* :mod:`~psdbound.aviation.paired` -- the paired overbound (bias and sigma);
  :mod:`~psdbound.aviation.sample_size` -- effective sample size of a
  correlated series and tail probabilities with confidence;
* :mod:`~psdbound.aviation.standards` -- the constants of the standards and
  seeds, each with its source.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.aviation.airborne import (
        iono_free_factor,
        sigma_air_m,
        sigma_multipath_airborne_m,
        sigma_noise_airborne_m,
    )
    from psdbound.aviation.bias import (
        BiasResponse,
        bias_bound_response,
        bias_response,
        fault_threshold,
        kalman_gains,
        prob_horizontal_exceeds,
    )
    from psdbound.aviation.budget import (
        PROCESSES,
        BudgetTerms,
        budget_document,
        budget_report,
        error_budget,
        ground_sigma_pr_m,
        iono_free_multiplier,
        los_from_az_el,
        multipliers,
        obliquity_factor,
        projection_matrix,
        vpl,
    )
    from psdbound.aviation.code_samples import (
        code_multipath_from_files,
        describe_code_series,
        overbound_code_series,
    )
    from psdbound.aviation.files import read_samples, write_overbound
    from psdbound.aviation.geometry import (
        SEED004_START_GPS_S,
        Sky,
        VplSeries,
        nominal_orbit,
        sky_over,
        vpl_series,
        write_vpl_series,
    )
    from psdbound.aviation.options import CodeMultipathOptions
    from psdbound.aviation.overbound import (
        DEFAULT_MIN_ABS_Z,
        METHODS,
        BinOverbound,
        OverboundResult,
        cdf_overbound_sigma,
        overbound_by_elevation,
        samples_in_full_bins,
        two_step_overbound,
    )
    from psdbound.aviation.paired import paired_bounding_functions, paired_overbound
    from psdbound.aviation.qq import gaussian_overbound_sigma, qq_ratio
    from psdbound.aviation.sample_size import effective_sample_size
    from psdbound.aviation.smoothing import (
        SMOOTHING_RATIO_FORMULAS,
        alpha_for_inflation,
        alpha_from_tau,
        hatch_filter_variance,
        running_mean_variance,
        smoothing_sigma_factor,
        smoothing_time_ratio,
        smoothing_variance_factor,
    )
    from psdbound.aviation.standards import GAD_PARAMETERS, K_FFMD, K_MD, Sourced, sources

__all__ = [
    "effective_sample_size",
    "paired_bounding_functions",
    "paired_overbound",
    "iono_free_factor",
    "sigma_air_m",
    "sigma_multipath_airborne_m",
    "sigma_noise_airborne_m",
    "gaussian_overbound_sigma",
    "qq_ratio",
    "SMOOTHING_RATIO_FORMULAS",
    "alpha_for_inflation",
    "alpha_from_tau",
    "hatch_filter_variance",
    "running_mean_variance",
    "smoothing_sigma_factor",
    "smoothing_time_ratio",
    "smoothing_variance_factor",
    "GAD_PARAMETERS",
    "K_FFMD",
    "K_MD",
    "Sourced",
    "sources",
    "DEFAULT_MIN_ABS_Z",
    "METHODS",
    "PROCESSES",
    "SEED004_START_GPS_S",
    "BiasResponse",
    "BinOverbound",
    "BudgetTerms",
    "CodeMultipathOptions",
    "OverboundResult",
    "Sky",
    "VplSeries",
    "bias_bound_response",
    "bias_response",
    "budget_document",
    "budget_report",
    "multipliers",
    "cdf_overbound_sigma",
    "code_multipath_from_files",
    "describe_code_series",
    "overbound_code_series",
    "error_budget",
    "fault_threshold",
    "ground_sigma_pr_m",
    "iono_free_multiplier",
    "kalman_gains",
    "los_from_az_el",
    "nominal_orbit",
    "obliquity_factor",
    "overbound_by_elevation",
    "prob_horizontal_exceeds",
    "read_samples",
    "samples_in_full_bins",
    "projection_matrix",
    "sky_over",
    "two_step_overbound",
    "vpl",
    "vpl_series",
    "write_vpl_series",
    "write_overbound",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "effective_sample_size": ("psdbound.aviation.sample_size", "effective_sample_size"),
    "paired_bounding_functions": ("psdbound.aviation.paired", "paired_bounding_functions"),
    "paired_overbound": ("psdbound.aviation.paired", "paired_overbound"),
    "iono_free_factor": ("psdbound.aviation.airborne", "iono_free_factor"),
    "sigma_air_m": ("psdbound.aviation.airborne", "sigma_air_m"),
    "sigma_multipath_airborne_m": ("psdbound.aviation.airborne", "sigma_multipath_airborne_m"),
    "sigma_noise_airborne_m": ("psdbound.aviation.airborne", "sigma_noise_airborne_m"),
    "gaussian_overbound_sigma": ("psdbound.aviation.qq", "gaussian_overbound_sigma"),
    "qq_ratio": ("psdbound.aviation.qq", "qq_ratio"),
    "SMOOTHING_RATIO_FORMULAS": ("psdbound.aviation.smoothing", "SMOOTHING_RATIO_FORMULAS"),
    "alpha_for_inflation": ("psdbound.aviation.smoothing", "alpha_for_inflation"),
    "alpha_from_tau": ("psdbound.aviation.smoothing", "alpha_from_tau"),
    "hatch_filter_variance": ("psdbound.aviation.smoothing", "hatch_filter_variance"),
    "running_mean_variance": ("psdbound.aviation.smoothing", "running_mean_variance"),
    "smoothing_sigma_factor": ("psdbound.aviation.smoothing", "smoothing_sigma_factor"),
    "smoothing_time_ratio": ("psdbound.aviation.smoothing", "smoothing_time_ratio"),
    "smoothing_variance_factor": ("psdbound.aviation.smoothing", "smoothing_variance_factor"),
    "GAD_PARAMETERS": ("psdbound.aviation.standards", "GAD_PARAMETERS"),
    "K_FFMD": ("psdbound.aviation.standards", "K_FFMD"),
    "K_MD": ("psdbound.aviation.standards", "K_MD"),
    "Sourced": ("psdbound.aviation.standards", "Sourced"),
    "sources": ("psdbound.aviation.standards", "sources"),
    "BiasResponse": ("psdbound.aviation.bias", "BiasResponse"),
    "bias_bound_response": ("psdbound.aviation.bias", "bias_bound_response"),
    "bias_response": ("psdbound.aviation.bias", "bias_response"),
    "fault_threshold": ("psdbound.aviation.bias", "fault_threshold"),
    "kalman_gains": ("psdbound.aviation.bias", "kalman_gains"),
    "prob_horizontal_exceeds": ("psdbound.aviation.bias", "prob_horizontal_exceeds"),
    "PROCESSES": ("psdbound.aviation.budget", "PROCESSES"),
    "BudgetTerms": ("psdbound.aviation.budget", "BudgetTerms"),
    "budget_document": ("psdbound.aviation.budget", "budget_document"),
    "budget_report": ("psdbound.aviation.budget", "budget_report"),
    "multipliers": ("psdbound.aviation.budget", "multipliers"),
    "error_budget": ("psdbound.aviation.budget", "error_budget"),
    "ground_sigma_pr_m": ("psdbound.aviation.budget", "ground_sigma_pr_m"),
    "iono_free_multiplier": ("psdbound.aviation.budget", "iono_free_multiplier"),
    "los_from_az_el": ("psdbound.aviation.budget", "los_from_az_el"),
    "obliquity_factor": ("psdbound.aviation.budget", "obliquity_factor"),
    "projection_matrix": ("psdbound.aviation.budget", "projection_matrix"),
    "vpl": ("psdbound.aviation.budget", "vpl"),
    "code_multipath_from_files": ("psdbound.aviation.code_samples", "code_multipath_from_files"),
    "describe_code_series": ("psdbound.aviation.code_samples", "describe_code_series"),
    "overbound_code_series": ("psdbound.aviation.code_samples", "overbound_code_series"),
    "read_samples": ("psdbound.aviation.files", "read_samples"),
    "write_overbound": ("psdbound.aviation.files", "write_overbound"),
    "SEED004_START_GPS_S": ("psdbound.aviation.geometry", "SEED004_START_GPS_S"),
    "Sky": ("psdbound.aviation.geometry", "Sky"),
    "VplSeries": ("psdbound.aviation.geometry", "VplSeries"),
    "nominal_orbit": ("psdbound.aviation.geometry", "nominal_orbit"),
    "sky_over": ("psdbound.aviation.geometry", "sky_over"),
    "vpl_series": ("psdbound.aviation.geometry", "vpl_series"),
    "write_vpl_series": ("psdbound.aviation.geometry", "write_vpl_series"),
    "CodeMultipathOptions": ("psdbound.aviation.options", "CodeMultipathOptions"),
    "DEFAULT_MIN_ABS_Z": ("psdbound.aviation.overbound", "DEFAULT_MIN_ABS_Z"),
    "METHODS": ("psdbound.aviation.overbound", "METHODS"),
    "BinOverbound": ("psdbound.aviation.overbound", "BinOverbound"),
    "OverboundResult": ("psdbound.aviation.overbound", "OverboundResult"),
    "cdf_overbound_sigma": ("psdbound.aviation.overbound", "cdf_overbound_sigma"),
    "overbound_by_elevation": ("psdbound.aviation.overbound", "overbound_by_elevation"),
    "samples_in_full_bins": ("psdbound.aviation.overbound", "samples_in_full_bins"),
    "two_step_overbound": ("psdbound.aviation.overbound", "two_step_overbound"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
