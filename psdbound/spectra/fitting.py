"""From stationary windows to a fitted bound: a model/results pair.

:class:`BoundModel` holds the stationary windows and the PSD estimator
choice; :meth:`BoundModel.fit` estimates one PSD per window and returns a
:class:`BoundResults` (in the style of statsmodels' model/results split)
with the tightest GMRP + white-noise bound, the per-window margins and a
``summary()``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError, NoDataError
from psdbound.spectra.bands import BandSpectra, over_data_db, resolved_from_hz
from psdbound.spectra.bound import RULES, BoundFit, fit_bound
from psdbound.spectra.cells import CellCheck
from psdbound.spectra.dependence import overlap_correlation, reference_clusters
from psdbound.spectra.estimators import PSDEstimate, estimate_psd
from psdbound.spectra.intervals import ModelSet
from psdbound.spectra.lowest import LowestFrequencies
from psdbound.spectra.lowfreq import TAU_MAX_S, LowFrequency
from psdbound.spectra.ordinates import lowest_ordinates
from psdbound.spectra.pooled import PooledLimits
from psdbound.spectra.stated import fit_stated_bound, statement
from psdbound.spectra.unresolved import UnresolvedGroups
from psdbound.stationarity.windowing import WindowSet

__all__ = ["BoundModel", "BoundResults"]


@dataclass(frozen=True)
class BoundResults:
    """Result of :meth:`BoundModel.fit`.

    Attributes
    ----------
    bound : BoundFit
        The fitted bound (parameters with units, margins, tau search).
    windows : WindowSet
        The stationary windows bounded.
    psds : tuple of PSDEstimate
        One PSD estimate per window (mapped multipath, one-sided, m^2/Hz).
    estimator : str
        PSD estimator used.
    estimator_options : dict
        Its options.
    rule : {"pooled", "envelope"}
        How the bounded data were formed.
    bands, pooled : BandSpectra, PooledLimits or None
        The pooled rule's band spectra and limits (None for the envelope).
    dependence : dict
        Clusters of dependent windows used by the pooled rule
        (:meth:`BoundModel.dependence`).
    model_set : ModelSet or None
        The GM + white-noise models consistent with the pooled spectrum
        (:func:`psdbound.spectra.intervals.model_set`; None for the envelope
        rule or with too few bands, ``model_set_note`` says why).
    low_frequency : LowFrequency or None
        What the bound covers below its lowest band
        (:mod:`psdbound.spectra.lowfreq`; None for the envelope rule).
    cells : CellCheck or None
        The groups' mean spectra on resolution cells against the bound
        (:mod:`psdbound.spectra.cells`; None for the envelope rule or another
        estimator than the multitaper).
    lowest_frequencies : LowestFrequencies or None
        The bound's expected estimate at the windows' lowest Fourier
        frequencies (:mod:`psdbound.spectra.lowest`): data that went through
        no filter (dual antenna); None otherwise.
    unresolved : UnresolvedGroups or None
        The shape groups none of whose windows resolves the lowest stated
        frequency, carried down to it (:mod:`psdbound.spectra.unresolved`).
    """

    bound: BoundFit
    windows: WindowSet
    psds: tuple[PSDEstimate, ...]
    estimator: str
    estimator_options: dict[str, Any] = field(default_factory=dict)
    rule: str = "envelope"
    bands: BandSpectra | None = None
    pooled: PooledLimits | None = None
    model_set: ModelSet | None = None
    model_set_note: str = ""
    dependence: dict[str, Any] = field(default_factory=dict)
    low_frequency: LowFrequency | None = None
    cells: CellCheck | None = None
    lowest_frequencies: LowestFrequencies | None = None
    unresolved: UnresolvedGroups | None = None

    @property
    def margins(self) -> NDArray[np.float64]:
        """Per window, the minimum over frequency of bound / point estimate.

        Under the envelope rule with ``target="point"`` every margin is
        ``>= 1``; under the pooled rule single windows' estimates scatter
        around the pooled spectrum, so margins below 1 are expected (the
        bound covers the windows' true PSDs, not each noisy estimate).
        """
        if self.rule == "envelope":
            return self.bound.margins
        f_min = self.bound.f_min_hz
        out = []
        for p in self.psds:
            use = (p.f_hz >= f_min) & (p.psd_m2_hz > 0)
            r = self.bound.psd(p.f_hz[use]) / p.psd_m2_hz[use]
            out.append(float(r.min()) if r.size else np.inf)
        return np.asarray(out)

    def confidence_statement(self) -> str:
        """Return what the bound covers, in words."""
        b = self.bound
        if self.rule == "envelope":
            what = (
                "every window's PSD estimate"
                if b.target == "point"
                else f"every window's {100 * (b.level or 0):g} % upper confidence limit"
            )
            return (
                f"the envelope rule (thesis): the bound lies above {what} from "
                f"{b.f_min_hz:.3g} Hz to Nyquist; no confidence level is stated for the "
                "true PSD of the data"
            )
        assert self.pooled is not None and self.bands is not None
        return statement(
            self.pooled,
            self.bands,
            self.low_frequency,
            self.lowest_frequencies,
            self.cells,
            self.unresolved,
        )

    def params(self) -> dict[str, float]:
        """Bound parameters with units in their names."""
        return self.bound.params()

    def over_data_db(self) -> dict[str, float] | None:
        """How far the bound lies above the pooled data per band, dB (None: no bands).

        See :func:`psdbound.spectra.bands.over_data_db` (``median_db``, ``max_db``,
        ``f_max_hz``, ``n_bands``).
        """
        return None if self.bands is None else over_data_db(self.bound.psd, self.bands)

    def summary(self) -> str:
        """Return a text summary: bound table, windows, estimator, mapping."""
        ws = self.windows
        mp = ws.mapping
        dof = [float(np.median(np.atleast_1d(p.dof))) for p in self.psds]
        extra = [
            f"{'PSD estimator':<28}{self.estimator:>12s}  (median dof {np.median(dof):.1f})",
            f"{'elevation mapping':<28}{mp.source:>12s}  a={mp.a:.3g} b={mp.b:.3g} "
            f"c={mp.c_deg:.3g} deg",
            f"{'windows':<28}{len(ws):>12d}  ({ws.total_duration_s / 3600:.2f} h, "
            f"never stationary {ws.uncovered_s / 60:.1f} min)",
        ]
        return self.bound.summary() + "\n" + "\n".join(extra)


class BoundModel:
    """PSD bounding of stationary multipath windows.

    Parameters
    ----------
    windows : WindowSet
        Output of :func:`psdbound.stationarity.find_stationary_windows`.
    estimator : {"multitaper", "welch", "blackman-tukey"}, default "multitaper"
        PSD estimator (see :mod:`psdbound.spectra.estimators`). Multitaper is
        the default: the thesis's Blackman-Tukey with an 80 %/20 % lag
        taper leaks, which inflated its DF bound.
    **estimator_options
        Passed to :func:`psdbound.spectra.estimate_psd`.

    See Also
    --------
    psdbound.spectra.pooled.fit_pooled_bound : The pooled rule.
    psdbound.fit : The whole pipeline, of which this is the bound stage.

    References
    ----------
    .. [1] Percival, D. B., & Walden, A. T. (1993). *Spectral Analysis for
       Physical Applications*. Cambridge University Press (the multitaper
       estimate and its degrees of freedom).
    .. [2] Bartlett, M. S., & Kendall, D. G. (1946). The statistical analysis of
       variance-heterogeneity and the logarithmic transformation. *Supplement to
       the Journal of the Royal Statistical Society*, 8(1), 128-138 (the
       variance of a log band value).
    .. [3] Cochran, W. G. (1954). The combination of estimates from different
       experiments. *Biometrics*, 10(1), 101-129 (the homogeneity p-values
       reported in ``bound.pooled``).
    .. [4] docs/method/bound.rst (the pooled rule, its statement and what was
       measured).

    Examples
    --------
    >>> from psdbound.arcs import find_arcs
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.isolation import isolate_dual_frequency
    >>> from psdbound.stationarity import find_stationary_windows
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()
    >>> arcs = find_arcs(read_obs(d.obs_paths[0], systems="G"), ("L1C", "L2W"),
    ...                  orbit=read_orbit(d.nav_path))
    >>> results = BoundModel(find_stationary_windows(isolate_dual_frequency(arcs, 1.5e-3))).fit()
    >>> results.rule, results.bound.level
    ('pooled', 0.95)
    """

    def __init__(
        self, windows: WindowSet, *, estimator: str = "multitaper", **estimator_options: Any
    ) -> None:
        if len(windows) == 0:
            raise NoDataError(
                "no stationary window to bound "
                f"({windows.n_tests} stationarity tests; never-stationary time "
                f"{windows.uncovered_s / 60:.1f} min)"
            )
        self.windows = windows
        self.estimator = estimator
        self.estimator_options = estimator_options
        self._psds: tuple[PSDEstimate, ...] | None = None

    def psds(self) -> tuple[PSDEstimate, ...]:
        """Estimate (once) and return the PSD of every window."""
        if self._psds is None:
            self._psds = tuple(
                estimate_psd(
                    self.windows.data(k),
                    self.windows.interval_s,
                    method=self.estimator,
                    **self.estimator_options,
                )
                for k in range(len(self.windows))
            )
        return self._psds

    def fit(
        self,
        *,
        rule: str = "pooled",
        objective: str = "variance",
        f_min_hz: float | None = None,
        confidence_level: float = 0.95,
        coverage: float = 0.99,
        shape_alpha: float = 0.05,
        bands_per_decade: int = 10,
        power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None = None,
        target: str = "point",
        level: float = 0.95,
        n_grid: int = 64,
        tau_max_s: float = TAU_MAX_S,
    ) -> BoundResults:
        """Fit the tightest bound over the windows' PSDs.

        Parameters
        ----------
        rule : {"pooled", "envelope"}, default "pooled"
            Pooled upper confidence limits (:func:`psdbound.spectra.pooled.fit_pooled_bound`;
            the windows must be disjoint) or the thesis's envelope of every
            window's PSD (:func:`psdbound.spectra.fit_bound`).
        objective : {"variance", "area"}, default "variance"
            Tightness objective.
        f_min_hz : float, optional
            Pooled rule: lowest frequency bounded, Hz (e.g. where the
            high-pass filter stops attenuating); default the lowest
            frequency any window's estimate resolves
            (:func:`~psdbound.spectra.bands.resolved_from_hz`).
        confidence_level, coverage, shape_alpha : float
            Pooled rule (see :func:`psdbound.spectra.pooled.pool_bands`).
        bands_per_decade : int, default 10
            Pooled rule: frequency bands per decade.
        power_response : callable, optional
            Pooled rule: ``|H(f)|^2`` of the high-pass the data went through,
            undone in the band averages.
        target : {"point", "upper"}, default "point"
            Envelope rule: bound the PSD estimates or their upper confidence limits.
        level : float, default 0.95
            Envelope rule: confidence level for ``target="upper"``.
        n_grid : int, default 64
            Size of the log-spaced ``tau`` grid.
        tau_max_s : float, default 900
            Pooled rule: prior upper limit of the time constant, seconds,
            used below the lowest band only where the data do not bound it
            (:mod:`psdbound.spectra.lowfreq`).

        Returns
        -------
        BoundResults
            Bound, windows, PSDs and estimator provenance.

        Raises
        ------
        InputError
            An unknown rule, or overlapping windows with the pooled rule.
        """
        if rule not in RULES:
            raise InputError(f"unknown bound rule {rule!r}; choose from {', '.join(RULES)}")
        psds = self.psds()
        dt = self.windows.interval_s
        common = dict(
            psds=psds,
            windows=self.windows,
            estimator=self.estimator,
            estimator_options=dict(self.estimator_options),
        )
        if rule == "envelope":
            bound = fit_bound(
                psds, dt, objective=objective, target=target, level=level, n_grid=n_grid
            )
            return BoundResults(bound, rule="envelope", **common)
        if self.windows.params.get("overlap", False):
            raise InputError(
                "the pooled bound needs disjoint windows (their spectra must be independent); "
                "window with overlap=False (stationarity windows = 'disjoint') or use the "
                "envelope rule"
            )
        if f_min_hz is None:
            f_min_hz = min(resolved_from_hz(p) for p in psds)
        dependence = self.dependence()
        lowest = None
        if power_response is None:  # no filter shaped the lowest frequencies (dual antenna)
            data = [self.windows.data(k) for k in range(len(self.windows))]
            lowest = lowest_ordinates(data, dt, f_min_hz)
        sb = fit_stated_bound(
            psds,
            dt,
            f_min_hz=f_min_hz,
            confidence_level=confidence_level,
            coverage=coverage,
            shape_alpha=shape_alpha,
            bands_per_decade=bands_per_decade,
            power_response=power_response,
            objective=objective,
            n_grid=n_grid,
            clusters=dependence["labels"],
            cluster_correlation=dependence["correlation"],
            tau_max_s=tau_max_s,
            lowest=lowest,
        )
        return BoundResults(
            sb.fit,
            rule="pooled",
            bands=sb.bands,
            pooled=sb.limits,
            model_set=sb.model_set,
            model_set_note=sb.model_set_note,
            dependence=dependence,
            low_frequency=sb.low_frequency,
            cells=sb.cells,
            lowest_frequencies=sb.lowest,
            unresolved=sb.unresolved,
            **common,
        )

    def dependence(self) -> dict[str, Any]:
        """Clusters of windows that share an error source, and their correlation.

        Double-difference windows that share a reference satellite in time
        (:func:`psdbound.spectra.dependence.reference_clusters`), with the
        median correlation of their overlapping samples
        (:func:`~psdbound.spectra.dependence.overlap_correlation`, an upper
        bound on the correlation of their spectra). Single-difference or
        dual-frequency windows: independent.

        Returns
        -------
        dict
            ``labels`` (ndarray or None), ``correlation``, ``n_clusters``,
            ``n_pairs`` (overlapping pairs measured), ``method``.
        """
        ws = self.windows.windows
        t0 = np.array([w.t_start_gps_s for w in ws])
        labels = reference_clusters(
            [w.sats for w in ws], t0, np.array([w.t_stop_gps_s for w in ws])
        )
        if labels is None:
            return {
                "labels": None,
                "correlation": 0.0,
                "n_clusters": len(ws),
                "n_pairs": 0,
                "method": "windows of different satellites: independent",
            }
        series = [self.windows.data(k) for k in range(len(ws))]
        rho, n_pairs = overlap_correlation(series, t0, self.windows.interval_s, labels)
        return {
            "labels": labels,
            "correlation": rho,
            "n_clusters": int(labels.max()) + 1,
            "n_pairs": n_pairs,
            "method": "double differences sharing a reference satellite in time are one "
            "cluster; the median correlation of their overlapping samples is the "
            "intra-cluster correlation (Kish design effect on the pooled degrees "
            "of freedom)",
        }
