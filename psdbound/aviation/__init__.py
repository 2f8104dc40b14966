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
  ``result.json`` and Q-Q figure;
* :mod:`~psdbound.aviation.code_samples` -- code multipath by carrier
  levelling straight from RINEX files (:func:`code_multipath_from_files`)
  and its description for a result (:func:`describe_code_series`), its
  overbound with sparse elevation bins named (:func:`overbound_code_series`);
* :mod:`~psdbound.aviation.options` -- :class:`CodeMultipathOptions`, the
  ``[code_multipath]`` section of a fit.

The airborne sigma curves, smoothing ratios and the Q-Q overbound of seeds
000, 001 and 004 live in :mod:`psdbound.kalman.aviation` and are used here.
"""

from __future__ import annotations

from psdbound.aviation.bias import (
    BiasResponse,
    bias_response,
    fault_threshold,
    kalman_gains,
    prob_horizontal_exceeds,
)
from psdbound.aviation.budget import (
    GAD_PARAMETERS,
    K_FFMD,
    K_MD,
    PROCESSES,
    BudgetTerms,
    budget_report,
    error_budget,
    ground_sigma_pr_m,
    iono_free_multiplier,
    los_from_az_el,
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

__all__ = [
    "DEFAULT_MIN_ABS_Z",
    "GAD_PARAMETERS",
    "K_FFMD",
    "K_MD",
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
    "bias_response",
    "budget_report",
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
