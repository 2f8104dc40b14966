"""The set of Gauss-Markov + white-noise models consistent with the pooled spectra.

The bound is one model above the data. Kalman-filter integrity also needs to
know which models the data cannot tell apart (a filter designed with the
wrong time constant can fail to bound its own error covariance even when the
PSD looks close; see docs/method/kalman.rst). This module gives that set.

**Construction.** The main group's windows are pooled on *test bands* (the
bands merged until each is at least the estimator's smoothing width ``2 W``
wide, so that their averages are nearly independent), each window's band
values divided by its level (``PooledLimits.level_log``). In every test band
the pooled value has an exact two-sided chi-square confidence interval at
``(1 - confidence_level) / B`` (Bonferroni over the ``B`` bands). A model
``theta = (sigma_GM, tau, sigma_WN)`` is in the set when the band average it
predicts lies inside every band's interval. The prediction is the *exact*
expectation of the multitaper estimate of a mean-removed window of the
median length (:mod:`psdbound.spectra.expectation`): near the lowest
frequencies the estimate of a steep spectrum lies up to twice above the
band-mean PSD, and a model that ignores it reads the flattening as a short
time constant. If the truth is a GM + white process, all its band
expectations lie in their intervals with probability at least
``confidence_level``, so the set contains it at least that often: no
asymptotic likelihood-ratio approximation, no over-dispersion factor.

**Reported intervals** are the projections of the set on each parameter,
widened by the windows' levels (each window's truth is the group's times its
level: the sigma intervals are scaled by the largest window term of the
bound, ``exp(t / 2)``, up, and by its mirror down), and widened to contain the
bound itself (:meth:`ModelSet.with_model`). An interval that reaches the
search grid's edge is reported as open on that side. Real multipath is not
exactly a first-order GM + white process: when no model fits inside every
band's interval, every interval is widened by the smallest common factor that
lets one fit, and that factor is reported (``widening``). The coverage of the
homogeneous truth is measured in ``benchmarks/bound_coverage.py``.

The earlier construction (a likelihood-ratio region of the band means with a
boxcar model of the estimator's smoothing) contained the homogeneous truth in
70 % (30 s) and 63 % (1 s) of runs against the stated 95 %: the model missed
the estimator's bias at the lowest bands, and the narrow low bands, which
share multitaper ordinates, were counted as independent.

References
----------
.. [1] Percival, D. B., & Walden, A. T. (1993). *Spectral Analysis for Physical
   Applications*, chapter 7. Cambridge University Press.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import optimize, stats

from psdbound.spectra._plane import corners as polygon_corners
from psdbound.spectra.bands import BandSpectra, merge_bands
from psdbound.spectra.expectation import (
    EXACT_BELOW,
    far_lag_kernels,
    gm_band_expectation,
    lag_kernels,
)
from psdbound.spectra.pooled import PooledLimits

__all__ = ["ModelSet", "model_set"]

#: Time constants searched (log-spaced; per tau the admitted variances form an exact polygon).
N_TAU = 96
#: Largest widening of the band intervals tried before no model set is reported.
MAX_WIDENING = 100.0
#: Fewest test bands for three parameters.
MIN_BANDS = 4


@dataclass(frozen=True)
class ModelSet:
    """GM + white-noise models consistent with the main group's pooled spectrum.

    Attributes
    ----------
    best : dict
        The best-fitting model: ``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``.
    tau_interval_s, sigma_gm_interval_m, sigma_wn_interval_m : tuple of float
        Projections of the joint region at ``confidence_level`` (seconds,
        metres, metres).
    open_ends : dict of str to tuple of bool
        Per parameter, whether the lower / upper end reached the search
        grid's edge (the data do not bound it there).
    confidence_level : float
        Level of the joint region.
    chi2_min : float
        Least-squares misfit of the best model to the pooled band values
        (log units, weighted by their variances).
    n_bands : int
        Test bands used.
    widening : float
        Factor by which every band's interval had to widen for a GM + white
        model to fit (1: the data are such a process at the stated level;
        real multipath is not exactly one, and this says by how much).
    includes : tuple of str
        Models the intervals were widened to contain (the bound).
    slices : ndarray, shape (n, 5)
        The set itself, per time constant in it: ``tau_s`` and the least and
        largest GM and white variances (m^2) whose band expectations fit,
        before the windows' levels (:mod:`psdbound.spectra.lowfreq`).
    vertices : ndarray, shape (k, 3)
        The corners of every slice: ``tau_s``, GM variance and white
        variance (m^2). The largest of any linear function of the PSD over
        the set (at the searched time constants) lies at one of them.
    window_factor : float
        Largest factor from the group's PSD to a covered window's
        (``exp`` of the largest window term), >= 1.
    """

    best: dict[str, float]
    tau_interval_s: tuple[float, float]
    sigma_gm_interval_m: tuple[float, float]
    sigma_wn_interval_m: tuple[float, float]
    open_ends: dict[str, tuple[bool, bool]]
    confidence_level: float
    chi2_min: float
    n_bands: int
    widening: float = 1.0
    includes: tuple[str, ...] = ()
    slices: NDArray[np.float64] = field(
        default_factory=lambda: np.zeros((0, 5)), repr=False, compare=False
    )
    vertices: NDArray[np.float64] = field(
        default_factory=lambda: np.zeros((0, 3)), repr=False, compare=False
    )
    window_factor: float = 1.0

    def with_model(self, name: str, sigma_gm_m: float, tau_s: float, sigma_wn_m: float) -> ModelSet:
        """Return the set widened to contain one more model (e.g. the bound itself).

        The set describes the group's windows; the bound lies above them
        with margins of its own, so its parameters can lie outside. A
        Kalman-filter design for "every model of the set" must include the
        bound: the reported intervals are the
        hull of the region and the models added here (named in
        ``includes``).
        """

        def hull(iv: tuple[float, float], v: float) -> tuple[float, float]:
            return (min(iv[0], v), max(iv[1], v))

        return replace(
            self,
            tau_interval_s=hull(self.tau_interval_s, tau_s),
            sigma_gm_interval_m=hull(self.sigma_gm_interval_m, sigma_gm_m),
            sigma_wn_interval_m=hull(self.sigma_wn_interval_m, sigma_wn_m),
            includes=self.includes + (name,),
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form (the ``bound.model_set`` section of result.json)."""
        return {
            "best": dict(self.best),
            "tau_interval_s": list(self.tau_interval_s),
            "sigma_gm_interval_m": list(self.sigma_gm_interval_m),
            "sigma_wn_interval_m": list(self.sigma_wn_interval_m),
            "open_ends": {k: list(v) for k, v in self.open_ends.items()},
            "confidence_level": self.confidence_level,
            "chi2_min": self.chi2_min,
            "n_bands": self.n_bands,
            "widening": self.widening,
            "includes": list(self.includes),
            "method": "the (sigma_GM, tau, sigma_WN) whose exact expected multitaper band "
            "averages lie inside every test band's exact chi-square interval of the main "
            "group's pooled spectrum (Bonferroni over bands), projected on each parameter (a "
            "grid search), widened by the windows' levels and to contain the models named in "
            "'includes' (the bound itself)",
        }


def _pooled_test_bands(
    bands: BandSpectra, limits: PooledLimits, smoothing_hz: float, group: int
) -> tuple[BandSpectra, NDArray[np.float64], NDArray[np.float64]]:
    """One group on test bands: level-corrected pooled values and their degrees of freedom."""
    rows = limits.groups == group
    test = merge_bands(bands, min_window_dof=0.0, min_width_hz=2.0 * smoothing_hz)
    level = np.zeros(rows.sum()) if limits.level_log is None else limits.level_log[rows]
    s, nu = test.psd_m2_hz[rows], test.dof[rows]
    ok = np.isfinite(s) & (nu > 0) & (s > 0)
    num = np.where(ok, nu * np.where(ok, s, 0.0) * np.exp(-level)[:, None], 0.0).sum(axis=0)
    dof = np.where(ok, nu, 0.0).sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        pooled = np.where(dof > 0, num / dof, np.nan)
    return test, pooled, dof


def _constraints(
    u: NDArray, e: NDArray, lower: NDArray, upper: NDArray, pooled: NDArray
) -> tuple[NDArray, NDArray, float, float]:
    """``lower <= v u + w e <= upper`` as ``A x <= b`` in scaled variables (and the scales)."""
    sv, sw = float(np.median(pooled / u)), float(np.median(pooled / e))
    a = np.column_stack([u * sv, e * sw]) / pooled[:, None]
    return (np.vstack([a, -a]), np.concatenate([upper / pooled, -lower / pooled]), sv, sw)


def _corners(
    u: NDArray, e: NDArray, lower: NDArray, upper: NDArray, pooled: NDArray
) -> NDArray[np.float64]:
    """Return the corners ``(v, w)`` of one time constant's polygon of admitted variances."""
    a_ub, b_ub, sv, sw = _constraints(u, e, lower, upper, pooled)
    return polygon_corners(a_ub, b_ub) * np.array([sv, sw])


def _feasible(u: NDArray, e: NDArray, lower: NDArray, upper: NDArray, pooled: NDArray) -> bool:
    a_ub, b_ub, _, _ = _constraints(u, e, lower, upper, pooled)
    return polygon_corners(a_ub, b_ub).shape[0] > 0


def _min_widening(
    unit: NDArray, e: NDArray, lower: NDArray, upper: NDArray, pooled: NDArray
) -> float:
    """Smallest factor ``c >= 1`` by which every band's interval must widen for some model to fit.

    Bisection in ``log c`` (to 1 %) up to :data:`MAX_WIDENING` over every fourth time
    constant (conservative: a coarser grid needs at least as much); ``inf`` beyond.
    """
    coarse = unit[::4]  # a coarser tau grid: the factor found is at least the finest's

    def any_fits(c: float) -> bool:
        return any(_feasible(u, e, lower / c, upper * c, pooled) for u in coarse)

    if any_fits(1.0):
        return 1.0
    if not any_fits(MAX_WIDENING):
        return float("inf")
    lo, hi = 0.0, float(np.log(MAX_WIDENING))
    while hi - lo > 0.01:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if any_fits(float(np.exp(mid))) else (mid, hi)
    return float(np.exp(hi))


def _best(
    unit: NDArray, e: NDArray, pooled: NDArray, dof: NDArray, taus: NDArray, ok: NDArray
) -> tuple[dict[str, float], float]:
    """Return the model of least weighted log misfit among the feasible time constants."""
    best, out = np.inf, {}
    for i in np.flatnonzero(ok):
        a = np.column_stack([unit[i], e]) / pooled[:, None]
        x, _ = optimize.nnls(a * np.sqrt(dof)[:, None], np.sqrt(dof))
        model = a @ x
        misfit = float(np.sum(np.log(np.maximum(model, 1e-300)) ** 2 * dof / 2.0))
        if misfit < best:
            best = misfit
            out = {
                "sigma_gm_m": float(np.sqrt(x[0])),
                "tau_s": float(taus[i]),
                "sigma_wn_m": float(np.sqrt(x[1])),
            }
    return out, best


def _band_intervals(
    pooled: NDArray, dof: NDArray, confidence_level: float, n_b: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return each test band's exact chi-square interval at ``(1 - confidence_level) / B``."""
    a = (1.0 - confidence_level) / n_b
    lower = dof * pooled / stats.chi2.isf(a / 2.0, dof)
    upper = dof * pooled / stats.chi2.ppf(a / 2.0, dof)
    return lower, upper


def _tau_grid(dt_s: float, f_lo_hz: float, t_s: float, tau_max_s: float) -> NDArray[np.float64]:
    """Return the time constants searched, ``dt / 2`` up beyond the lowest band, 2 T, 2 tau_max."""
    return np.geomspace(
        0.5 * dt_s, max(10.0 / (2.0 * np.pi * f_lo_hz), 2.0 * t_s, 2.0 * tau_max_s), N_TAU
    )


def _unit_expectations(
    lo: NDArray, hi: NDArray, taus: NDArray, dt_s: float, t_s: float, smoothing_hz: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]] | None:
    """Return the expected band averages per unit GM variance (per tau) and per unit white noise.

    The multitaper estimate of a mean-removed window of ``t_s`` seconds; exact (lag kernels)
    below :data:`EXACT_BELOW` smoothing widths. None when a band holds no Fourier frequency.
    """
    n = int(round(t_s / dt_s))
    nw = smoothing_hz * t_s
    low = lo < EXACT_BELOW * smoothing_hz
    kernels = np.zeros((lo.size, n))
    white_unit = np.full(lo.size, 2.0 * dt_s)  # white noise: unbiased away from zero frequency
    if low.any():
        kernels[low], has = lag_kernels(n, dt_s, lo[low], hi[low], nw=nw)
        if not has.all():
            return None
        white_unit[low] = 2.0 * dt_s * kernels[low, 0]  # R(l) = variance at l = 0 only
    if (~low).any():
        kernels[~low] = far_lag_kernels(n, dt_s, lo[~low], hi[~low], nw=nw)[0]
    # expected band averages per unit GM variance, every band at once (one autocorrelation)
    return gm_band_expectation(kernels, taus, dt_s), white_unit


def _corner_extents(corners: list[NDArray], idx: NDArray) -> NDArray[np.float64]:
    """Return the extents ``(v_min, v_max, w_min, w_max)`` of the admitted taus' polygons."""
    return np.array(
        [
            [c[:, 0].min(), c[:, 0].max(), c[:, 1].min(), c[:, 1].max()]
            for c in (corners[i] for i in idx)
        ]
    )


def _window_half_term(limits: PooledLimits, group: int) -> float:
    """Return half the largest window term of a group (the sigmas' widening, log scale)."""
    return (
        float(np.nanmax(limits.window_term_log[group])) / 2.0
        if (limits.window_term_log is not None)
        else 0.0
    )


def model_set(
    bands: BandSpectra,
    limits: PooledLimits,
    dt_s: float,
    *,
    confidence_level: float = 0.95,
    smoothing_hz: float = 0.0,
    tau_max_s: float = 0.0,
    group: int = 0,
) -> tuple[ModelSet | None, str]:
    """Return the GM + white-noise models consistent with the pooled spectrum.

    Parameters
    ----------
    bands : BandSpectra
        Band-averaged window PSDs (:func:`psdbound.spectra.bands.band_spectra`),
        with the windows' durations.
    limits : PooledLimits
        The pooled limits (for the groups and the windows' levels).
    dt_s : float
        Sampling interval, seconds.
    confidence_level : float, default 0.95
        Level of the set.
    smoothing_hz : float, default 0
        Half-width ``W`` of the multitaper smoothing, Hz (its
        ``params["bandwidth_hz"]``); the exact expectation needs it.
    tau_max_s : float, default 0
        The search reaches at least twice this time constant, seconds (so
        that whether the data bound ``tau`` below a prior maximum can be
        read from the set).
    group : int, default 0
        The shape group whose windows the set describes (0: the main one;
        :attr:`PooledLimits.groups`).

    Returns
    -------
    ModelSet or None
        None when there are too few test bands, the estimator is not the
        multitaper, or no GM + white model lies inside every band's
        interval (the data are not such a process at this level).
    reason : str
        Why there is no set (empty otherwise).
    """
    if smoothing_hz <= 0 or bands.duration_s is None:
        return None, "the model set needs the multitaper estimator (its exact expectation)"
    test, pooled, dof = _pooled_test_bands(bands, limits, smoothing_hz, group)
    have = np.isfinite(pooled) & (dof > 0)
    n_b = int(have.sum())
    if n_b < MIN_BANDS:
        return None, f"{n_b} test bands with data, at least {MIN_BANDS} needed"
    lo, hi = test.edges_hz[:-1][have], np.minimum(test.edges_hz[1:][have], 0.5 / dt_s)
    pooled, dof = pooled[have], dof[have]
    lower, upper = _band_intervals(pooled, dof, confidence_level, n_b)
    t_s = float(np.median(test.duration_s[limits.groups == group]))
    taus = _tau_grid(dt_s, float(lo[0]), t_s, tau_max_s)
    expected = _unit_expectations(lo, hi, taus, dt_s, t_s, smoothing_hz)
    if expected is None:
        return None, "a test band holds no Fourier frequency of the median window"
    unit, white_unit = expected
    widening = _min_widening(unit, white_unit, lower, upper, pooled)
    if not np.isfinite(widening):
        return None, (
            f"no Gauss-Markov + white-noise model lies inside every band's "
            f"{100 * confidence_level:g} % interval, even widened "
            f"{MAX_WIDENING:g} times"
        )
    lower, upper = lower / widening, upper * widening
    # per tau, the corners of the polygon of admitted (v, w): its extents, and the largest of
    # any linear function of the PSD over it, lie there
    corners = [_corners(unit[i], white_unit, lower, upper, pooled) for i in range(taus.size)]
    ok = np.array([c.size > 0 for c in corners])
    idx = np.flatnonzero(ok)
    if idx.size == 0:  # the widening's feasibility is a linear program, to its tolerance
        return None, "no Gauss-Markov + white-noise model lies inside every band's interval"
    ext = _corner_extents(corners, idx)
    best, misfit = _best(unit, white_unit, pooled, dof, taus, ok)
    widen = _window_half_term(limits, group)
    gm = np.sqrt(np.maximum(ext[:, :2], 0.0))
    wn = np.sqrt(np.maximum(ext[:, 2:], 0.0))
    out = ModelSet(
        best=best,
        tau_interval_s=(float(taus[idx].min()), float(taus[idx].max())),
        sigma_gm_interval_m=(float(gm.min() * np.exp(-widen)), float(gm.max() * np.exp(widen))),
        sigma_wn_interval_m=(float(wn.min() * np.exp(-widen)), float(wn.max() * np.exp(widen))),
        open_ends={
            "tau_s": (bool(idx.min() == 0), bool(idx.max() == N_TAU - 1)),
            "sigma_gm_m": (False, bool(idx.max() == N_TAU - 1)),
            "sigma_wn_m": (False, False),
        },
        confidence_level=float(confidence_level),
        chi2_min=misfit,
        n_bands=n_b,
        widening=widening,
        slices=np.column_stack([taus[idx], ext]),
        vertices=np.vstack(
            [np.column_stack([np.full(len(corners[i]), taus[i]), corners[i]]) for i in idx]
        ),
        window_factor=float(np.exp(2.0 * widen)),
    )
    return out, ""
