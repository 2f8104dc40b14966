"""The pooled bound with everything it states: limits, model set and the low frequencies.

One chain, used by :meth:`psdbound.spectra.BoundModel.fit`,
:func:`psdbound.bound_series` and the campaign's pooled days:

1. :func:`~psdbound.spectra.pooled.fit_pooled_bound`: band averages, pooled
   limits and the tightest bound above them from ``f_min`` to Nyquist;
2. :func:`~psdbound.spectra.intervals.model_set`: the Gauss-Markov + white
   models the data admit;
3. :func:`~psdbound.spectra.lowfreq.bound_below`: the bound raised, where
   needed, above every admitted model below ``f_min``, down to 0 Hz;
4. :func:`~psdbound.spectra.unresolved.cover_unresolved`: where a shape group's
   windows are all too short to resolve ``f_min``, the bound raised, where needed, above
   the group's admitted models carried down to ``f_min``;
5. :func:`~psdbound.spectra.lowest.cover_lowest` (unfiltered data, when the
   windows' lowest Fourier ordinates are given): the bound raised, where
   needed, so that its expected estimate there lies above each shape group's
   upper limit, whatever the truth's shape;
6. :func:`~psdbound.spectra.cells.cover_cells`: the bound raised above any
   cell of the estimator's resolution whose group mean refutes it (a peak
   narrower than its band).

The model set is identified on more of the spectrum than the statement
covers: from each window's lowest Fourier frequency ``1/T`` when the data
went through no filter (:func:`identification_bands`). Below ``f_min = W +
1/T`` a multitaper estimate is no average of the PSD near its frequency (it
smooths over ``f +- W`` and the mean removal empties 0 Hz), so no limit is
stated there; but its exact expectation under each model is known
(:mod:`psdbound.spectra.expectation`), and these lowest ordinates are the
ones that see a Gauss-Markov plateau. Without them a time constant longer
than ``1 / (2 pi f_min)`` is not identified and the low-frequency rule must
cover every admitted one up to the prior (``benchmarks/bound_coverage.py``:
on homogeneous truths the bound's median variance 3.6 times the truth's at
30 s and 2.6 at 1 s with the statement's bands alone).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError
from psdbound.spectra.bands import BandSpectra, band_spectra, resolved_from_hz
from psdbound.spectra.bound import BoundFit, join_floors
from psdbound.spectra.cells import CellCheck, cover_cells
from psdbound.spectra.estimators import PSDEstimate
from psdbound.spectra.intervals import ModelSet, model_set
from psdbound.spectra.lowest import LowestFrequencies, cover_lowest
from psdbound.spectra.lowfreq import TAU_MAX_S, LowFrequency, bound_below
from psdbound.spectra.ordinates import LowestOrdinates
from psdbound.spectra.pooled import MIN_GROUP_DOF, PooledLimits, fit_pooled_bound, smoothing_hz
from psdbound.spectra.unresolved import UnresolvedGroups, cover_unresolved

__all__ = ["StatedBound", "fit_stated_bound", "identification_bands", "statement"]


class StatedBound(NamedTuple):
    """A pooled bound and what it states.

    Attributes
    ----------
    fit : BoundFit
        The bound.
    bands : BandSpectra
        The windows' band averages.
    limits : PooledLimits
        The pooled limits it lies above.
    model_set : ModelSet or None
        The admitted models, widened to contain the bound.
    model_set_note : str
        Why there is no model set.
    low_frequency : LowFrequency
        What the bound covers below its lowest band.
    lowest : LowestFrequencies or None
        The check at the lowest Fourier frequencies (None: not made).
    cells : CellCheck or None
        The check on resolution cells (None: not a multitaper estimate).
    unresolved : UnresolvedGroups or None
        The groups whose windows do not resolve ``f_min``, carried down to it.
    """

    fit: BoundFit
    bands: BandSpectra
    limits: PooledLimits
    model_set: ModelSet | None
    model_set_note: str
    low_frequency: LowFrequency
    lowest: LowestFrequencies | None = None
    cells: CellCheck | None = None
    unresolved: UnresolvedGroups | None = None


def fit_stated_bound(
    psds: Sequence[PSDEstimate],
    dt_s: float,
    *,
    f_min_hz: float,
    confidence_level: float = 0.95,
    tau_max_s: float = TAU_MAX_S,
    objective: str = "variance",
    n_grid: int = 64,
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None = None,
    filtered: bool | None = None,
    lowest: LowestOrdinates | None = None,
    **pool_options: Any,
) -> StatedBound:
    """Fit the pooled bound, its model set and its low-frequency statement.

    Parameters
    ----------
    psds : sequence of PSDEstimate
        One estimate per (disjoint) window.
    dt_s : float
        Sampling interval, seconds.
    f_min_hz : float
        Lowest band edge, Hz.
    confidence_level : float, default 0.95
        Level of the statement and of the model set.
    tau_max_s : float, default 900
        Prior upper limit of the time constant below the lowest band, seconds
        (:mod:`psdbound.spectra.lowfreq`).
    objective : {"variance", "area"}, default "variance"
        Tightness objective.
    n_grid : int, default 64
        ``tau`` grid size.
    power_response : callable, optional
        ``|H(f)|^2`` of a high-pass the data went through.
    filtered : bool, optional
        Whether a filter shaped the spectra below ``f_min`` (then the model
        set is identified on the statement's bands only,
        :func:`identification_bands`); default: whether ``power_response``
        is given. Pass True for spectra whose filter response was divided
        out already (a campaign's days).
    lowest : LowestOrdinates, optional
        The windows' estimates at their lowest Fourier frequencies
        (:func:`psdbound.spectra.ordinates.lowest_ordinates`; unfiltered data
        only): the bound's expectation there is held above each group's
        upper limit (:func:`psdbound.spectra.lowest.cover_lowest`).
    **pool_options
        ``coverage``, ``shape_alpha``, ``bands_per_decade``, ``clusters``,
        ``cluster_correlation``, ``deviation_model``
        (:func:`~psdbound.spectra.pooled.fit_pooled_bound`).

    Returns
    -------
    StatedBound

    Raises
    ------
    InputError
        ``tau_max_s`` below ``dt_s / 2``, where the model set's time
        constants start: no model would lie under the prior, and white
        noise would read as data admitting only longer time constants.
    """
    if tau_max_s < dt_s / 2:
        raise InputError(
            f"tau_max_s {tau_max_s:g} s is below the shortest time constant the bound searches, "
            f"dt_s / 2 = {dt_s / 2:g} s: give at least that (a shorter one is white noise at "
            "this sampling)"
        )
    fit, bands, limits = fit_pooled_bound(
        psds,
        dt_s,
        f_min_hz=f_min_hz,
        confidence_level=confidence_level,
        power_response=power_response,
        objective=objective,
        n_grid=n_grid,
        lowest=lowest,
        **pool_options,
    )
    id_bands = identification_bands(
        psds,
        bands,
        filtered=power_response is not None if filtered is None else filtered,
        bands_per_decade=pool_options.get("bands_per_decade", 10),
    )
    ms, why = model_set(
        id_bands,
        limits,
        dt_s,
        confidence_level=confidence_level,
        smoothing_hz=smoothing_hz(psds),
        tau_max_s=tau_max_s,
    )
    fit, low = bound_below(
        fit,
        bands,
        limits,
        ms,
        dt_s,
        tau_max_s=tau_max_s,
        objective=objective,
        n_grid=n_grid,
        reason=why,
    )
    fit, unresolved, checked, cells = _data_checks(
        fit,
        psds,
        bands,
        id_bands,
        limits,
        low,
        dt_s,
        lowest=lowest,
        power_response=power_response,
        objective=objective,
        n_grid=n_grid,
    )
    if ms is not None:  # the reported set contains the bound it accompanies
        ms = ms.with_model("bound", fit.sigma_gm_m, fit.tau_s, fit.sigma_wn_m)
    return StatedBound(fit, bands, limits, ms, why, low, checked, cells, unresolved)


def _data_checks(
    fit: BoundFit,
    psds: Sequence[PSDEstimate],
    bands: BandSpectra,
    id_bands: BandSpectra,
    limits: PooledLimits,
    low: LowFrequency,
    dt_s: float,
    *,
    lowest: LowestOrdinates | None,
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None,
    objective: str,
    n_grid: int,
) -> tuple[BoundFit, UnresolvedGroups, LowestFrequencies | None, CellCheck | None]:
    """Run steps 4-6 of :func:`fit_stated_bound`: each raises the bound where data refute it.

    Every step keeps the points of the steps before it (their floors and rows).
    """
    fit, unresolved = cover_unresolved(
        fit,
        [resolved_from_hz(p) for p in psds],
        bands,
        limits,
        dt_s,
        id_bands=id_bands,
        smoothing_hz=smoothing_hz(psds),
        floor=low.floor(),
        objective=objective,
        n_grid=n_grid,
    )
    floor = join_floors(low.floor(), unresolved.floor())
    checked = None
    if lowest is not None and lowest.j.size:
        fit, checked = cover_lowest(
            fit, lowest, limits, bands, floor, objective=objective, n_grid=n_grid
        )
    fit, cells = cover_cells(
        fit,
        psds,
        limits,
        bands,
        dt_s,
        power_response=power_response,
        floor=floor,
        extra=None if checked is None else checked.rows,
        objective=objective,
        n_grid=n_grid,
    )
    return fit, unresolved, checked, cells


def identification_bands(
    psds: Sequence[PSDEstimate],
    bands: BandSpectra,
    *,
    filtered: bool = False,
    bands_per_decade: int = 10,
) -> BandSpectra:
    """Return the bands the model set is identified on.

    Parameters
    ----------
    psds : sequence of PSDEstimate
        One estimate per window.
    bands : BandSpectra
        The statement's bands (from ``f_min``).
    filtered : bool, default False
        Whether a filter (a high-pass) shaped the spectra below ``f_min``:
        then the statement's bands are returned (there the filter's
        response, not the data, set the estimate).
    bands_per_decade : int, default 10
        Bands per decade.

    Returns
    -------
    BandSpectra
        Multitaper estimates without a filter: bands from the lowest Fourier
        frequency ``1 / T`` of the longest window, every ordinate used;
        otherwise ``bands``.
    """
    if filtered or smoothing_hz(psds) <= 0 or bands.duration_s is None:
        return bands
    f_low = 1.0 / float(np.max(bands.duration_s))
    if f_low >= bands.edges_hz[0]:
        return bands
    return band_spectra(
        psds, f_min_hz=f_low * (1.0 - 1e-9), bands_per_decade=bands_per_decade, below_resolved=True
    )


def _merged_groups(limits: PooledLimits, bands: BandSpectra) -> list[int]:
    """Return the groups whose limits hold on merged bands (wider than the common ones)."""
    if limits.band_span_hz is None:
        return []
    lo = limits.band_span_hz[:, :, 0]
    have = np.isfinite(lo)
    common = np.broadcast_to(bands.edges_hz[:-1], lo.shape)
    return [
        g for g in range(lo.shape[0]) if np.any(have[g] & ~np.isclose(lo[g], common[g], rtol=1e-9))
    ]


def statement(
    limits: PooledLimits,
    bands: BandSpectra,
    low: LowFrequency | None = None,
    lowest: LowestFrequencies | None = None,
    cells: CellCheck | None = None,
    unresolved: UnresolvedGroups | None = None,
) -> str:
    """Return what a bound above ``limits`` covers, in words (result.json ``bound.covers``).

    Parameters
    ----------
    limits : PooledLimits
        The pooled limits.
    bands : BandSpectra
        Their bands.
    low : LowFrequency, optional
        What the bound covers below the lowest band (its sentence is added).
    lowest : LowestFrequencies, optional
        The check at the lowest Fourier frequencies (its sentence is added).
    cells : CellCheck, optional
        The check on resolution cells (its sentence is added).
    unresolved : UnresolvedGroups, optional
        The groups carried down to ``f_min`` (its sentence is added when there are any).

    Returns
    -------
    str
    """
    n_w = int(limits.groups.size)
    allowed = int(np.floor((1.0 - limits.coverage) * n_w + 1e-9))
    merged = _merged_groups(limits, bands)
    text = (
        f"with {100 * limits.confidence_level:g} % confidence the bound lies above the true "
        f"PSD of at least {100 * limits.coverage:g} % of the {n_w} windows (all but {allowed}) "
        f"in every band from {bands.edges_hz[0]:.3g} Hz to Nyquist (band means; within a band "
        f"the bound is held sqrt(f_hi/f_lo) above the limit at the lower edge): exact "
        f"chi-square limits of {limits.n_groups} group(s) of one spectral shape, raised by "
        f"every covered window's own upper deviation from its group (a level, and a tilt in "
        f"log frequency where significant); no distribution of the windows is assumed"
    )
    if merged:
        text += (
            f"; group(s) {', '.join(map(str, merged))} on merged bands of at least "
            f"{MIN_GROUP_DOF:g} pooled degrees of freedom"
        )
    parts = [text] + [p.sentence() for p in (low, lowest, cells, unresolved) if p is not None]
    return "; ".join(p for p in parts if p)
