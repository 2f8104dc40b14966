"""Confidence limits of window spectra: exact pooled limits and per-window deviations.

The pooled bound (:mod:`psdbound.spectra.pooled`) states: *with confidence
``1 - alpha`` the bound lies above the true PSD of at least a fraction ``p``
of the windows, in every band from ``f_min`` to Nyquist*. This module holds
the two limits that statement is built from (docs/method/bound.rst):

**The model.** Window ``w`` has true band-mean PSD ``S_wb`` in band ``b``;
its band average ``S_hat_wb`` with ``nu_wb`` equivalent degrees of freedom
satisfies ``nu_wb S_hat_wb / S_wb ~ chi2(nu_wb)`` (Percival and Walden 1993,
section 7.1). Within a group of windows of one spectral shape,

    log S_wb = mu_b + d_w,

a shape ``mu_b`` common to the group and a level ``d_w`` of each window
(its deviation; a tilt ``d_w + c_w x_b`` in the standardised log frequency
``x_b`` is available for the shape test). The deviations are estimated by
weighted backfitting of the unbiased log band values (Bartlett and Kendall
1946 variances ``psi'(nu/2)``), each window's from its own bands.

**The group limit** (:func:`mean_upper_limit`). Given the deviations,
``sum_w nu_wb S_hat_wb exp(-d_wb) / exp(mu_b)`` is ``chi2(sum_w nu_wb)``:
the exact one-sided upper limit of ``exp(mu_b)`` at level ``a`` is
``sum nu S_hat exp(-d) / chi2.ppf(a, sum nu)``. Windows that are not
independent (a shared reference satellite, a repeat on the next sidereal
day) enter with an effective number of degrees of freedom: within a cluster
of ``m`` windows of intra-cluster correlation ``rho`` the sum is divided by
the design effect ``1 + (m - 1) rho`` (Kish 1965).

**The spread of the windows** (:func:`spread_upper_limit`,
:func:`tolerance_factor`). The windows' levels ``d_w`` are taken as draws
of ``N(0, sigma_d^2)``; each estimate ``d_hat_w`` has its own standard
error. The Q-profile upper confidence limit of ``sigma_d^2`` (Viechtbauer
2007) and the normal quantile ``z*`` for which at most ``k`` of ``M``
windows exceed ``z* sigma_d`` except with a stated probability (a binomial
tail) give the window term ``z* sigma_d,upper``: with homogeneous windows it
shrinks as windows accumulate, and a spread of levels widens it by what the
data show of it.

**Shape.** A window whose spectrum departs from its group's shape by more
than a level and tilt (the residual ``sum_b (r_wb - d_hat_wb)^2 / v_wb``, a
chi-square with ``n_b - p`` degrees of freedom, small p-value at the
Bonferroni level) is moved to a group of its own shape by the caller.

References
----------
Bartlett, M. S., Kendall, D. G. (1946). The statistical analysis of
variance-heterogeneity and the logarithmic transformation. JRSS Suppl. 8, 128-138.

Kish, L. (1965). Survey Sampling. Wiley (the design effect, section 5.4).

Viechtbauer, W. (2007). Confidence intervals for the amount of heterogeneity
in meta-analysis. Statistics in Medicine 26(1), 37-52.

Percival, D. B., Walden, A. T. (1993). Spectral Analysis for Physical
Applications. Cambridge University Press.

Robertson, T., Wright, F. T., Dykstra, R. L. (1988). Order Restricted
Statistical Inference. Wiley (the chi-bar-squared distribution).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import NDArray
from scipy import optimize, special, stats

from psdbound.errors import InputError

__all__ = [
    "SHAPE_MODELS",
    "WindowDeviations",
    "bonferroni_p",
    "design_effect_dof",
    "log_chi2_bias",
    "mean_upper_limit",
    "chi_bar_squared_sf",
    "end_excess_p",
    "simultaneous_factor",
    "spread_upper_limit",
    "tolerance_factor",
    "window_deviations",
]

#: Deviation models of a window from its group's shape.
SHAPE_MODELS = ("level", "tilt")
#: Fewest bands a window needs for a tilt of its own (else its deviation is a level only).
_MIN_BANDS_TILT = 3
_BACKFIT_ITER = 50


def log_chi2_bias(nu: float | NDArray[np.float64]) -> NDArray[np.float64]:
    """Return ``E ln(chi^2_nu / nu) = psi(nu / 2) - ln(nu / 2)``, the log-estimate's bias.

    How far the log of an estimate of ``nu`` degrees of freedom lies, on
    average, below the log of what it estimates.

    Parameters
    ----------
    nu : float or ndarray
        Degrees of freedom (> 0).

    Returns
    -------
    ndarray
        The bias (negative), the shape of ``nu``.
    """
    nu = np.asarray(nu, dtype=float)
    return np.asarray(special.digamma(nu / 2.0) - np.log(nu / 2.0))


def bonferroni_p(p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Combine ``k`` tests of one hypothesis: the smallest p-value times ``k``, at most 1.

    Parameters
    ----------
    p : ndarray, shape (..., k)
        The p-values of each test, along the last axis.

    Returns
    -------
    ndarray, shape (...)
    """
    p = np.asarray(p, dtype=float)
    return np.minimum(1.0, p.shape[-1] * p.min(axis=-1))


def mean_upper_limit(
    psd_m2_hz: NDArray[np.float64],
    dof: NDArray[np.float64],
    a: float,
    *,
    effective_dof: float | None = None,
) -> float:
    """Exact one-sided upper confidence limit of a common PSD from chi-square estimates.

    Parameters
    ----------
    psd_m2_hz : ndarray
        Independent estimates ``S_hat_i`` of one PSD value, m^2/Hz, each
        with ``nu_i S_hat_i / S ~ chi2(nu_i)``.
    dof : ndarray
        Their degrees of freedom ``nu_i`` (> 0).
    a : float
        One-sided error probability, in (0, 1).
    effective_dof : float, optional
        Degrees of freedom of the pooled estimate when the estimates are not
        independent (:func:`design_effect_dof`); default ``sum nu_i``.

    Returns
    -------
    float
        ``nu S_pool / chi2.ppf(a, nu)`` with ``S_pool = sum nu_i S_hat_i /
        sum nu_i`` and ``nu`` the (effective) degrees of freedom, m^2/Hz:
        ``P(S <= limit) = 1 - a`` exactly when the chi-square model holds.
    """
    s = np.asarray(psd_m2_hz, dtype=float)
    nu = np.asarray(dof, dtype=float)
    if s.size == 0 or np.any(nu <= 0) or not 0.0 < a < 1.0:
        raise InputError("mean_upper_limit needs estimates, positive dof and a in (0, 1)")
    pooled = float(np.sum(nu * s) / np.sum(nu))
    nu_eff = float(np.sum(nu)) if effective_dof is None else float(effective_dof)
    return nu_eff * pooled / float(stats.chi2.ppf(a, nu_eff))


def design_effect_dof(
    dof: NDArray[np.float64], clusters: NDArray[np.int64] | None, rho: float
) -> float:
    """Effective degrees of freedom of a pooled estimate from clustered windows.

    Parameters
    ----------
    dof : ndarray
        Degrees of freedom of each window's estimate.
    clusters : ndarray of int or None
        Cluster label of each window (windows that share an error source:
        one reference satellite at one time, one satellite on consecutive
        sidereal days); None: all independent.
    rho : float
        Intra-cluster correlation of the estimates, in [0, 1].

    Returns
    -------
    float
        ``sum_c (sum_{w in c} nu_w) / (1 + (m_c - 1) rho)`` (Kish's design
        effect per cluster of ``m_c`` windows), at most ``sum nu``.
    """
    nu = np.asarray(dof, dtype=float)
    if clusters is None or rho <= 0.0:
        return float(nu.sum())
    total = 0.0
    for c in np.unique(clusters):
        sel = clusters == c
        total += float(nu[sel].sum()) / (1.0 + (int(sel.sum()) - 1) * min(rho, 1.0))
    return total


def simultaneous_factor(a: float, n_windows: int, *, n_params: int = 1) -> float:
    """One-sided factor ``k``: every window's ``d <= d_hat + k se`` with probability ``>= 1 - a``.

    ``z_{1 - a / M}`` for a level (Bonferroni over the ``M`` windows: valid
    whatever their dependence); for a level and a tilt, Scheffe's
    ``sqrt(chi2_2^{-1}(1 - a / M))``, which holds at every frequency at once.
    """
    q = a / max(n_windows, 1)
    if n_params <= 1:
        return float(stats.norm.isf(q))
    return float(np.sqrt(stats.chi2.isf(q, n_params)))


@dataclass(frozen=True)
class WindowDeviations:
    """Each window's deviation from its group's common log spectrum.

    Attributes
    ----------
    mu : ndarray, shape (B,)
        Common log band level of the group (reference window, deviation 0).
    dev : ndarray, shape (M, B)
        Estimated log deviation ``d_hat_wb`` of each window (extrapolated by
        its level and tilt to the bands it has no data in).
    se : ndarray, shape (M, B)
        Standard error of ``d_hat_wb``.
    n_params : ndarray of int, shape (M,)
        Parameters of each window's deviation (1: level, 2: level and tilt).
    coef, cov : ndarray, shapes (M, 2) and (M, 2, 2)
        Each window's level and tilt (0 for a level-only deviation) and
        their covariance (:meth:`at` evaluates them anywhere).
    shape_p : ndarray, shape (M,)
        p-value of each window's excess above its group's shape after its
        own level: ``T = sum_b max(0, e_wb)^2`` of the standardised
        residuals, a chi-bar-squared variable under the model
        (:func:`chi_bar_squared_sf`), and the largest standardised partial
        sum of the residuals from either end of the band range
        (:func:`end_excess_p`: a slow reflector lifts a few of the lowest
        bands only); the smaller p-value, doubled. Both assume independent
        bands: give bands at least the estimator's smoothing wide.
        One-sided on purpose: a window below its group's shape in some band
        (the mean removal empties the lowest frequencies of some windows) is
        covered by the group's limits; one above is not. 1 when nothing is
        left to test.
    shape_tests : ndarray, shape (M, 2)
        The two p-values ``shape_p`` combines (:func:`bonferroni_p`), for a
        caller that adds a test of its own.
    lowest_residual : ndarray, shape (M,)
        Each window's standardised residual in its lowest band with an
        estimate (the one the residuals above are made of; NaN for a window
        with nothing left to test), for a caller that joins it to a test of
        the frequencies below.
    """

    mu: NDArray[np.float64]
    dev: NDArray[np.float64]
    se: NDArray[np.float64]
    n_params: NDArray[np.int64]
    shape_p: NDArray[np.float64]
    coef: NDArray[np.float64] | None = None
    cov: NDArray[np.float64] | None = None
    shape_tests: NDArray[np.float64] | None = None
    lowest_residual: NDArray[np.float64] | None = None

    def at(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Deviations and their standard errors at standardised log frequencies ``x``.

        Returns arrays of shape (M, len(x)): each window's level (and tilt)
        evaluated at ``x``, and its standard error.
        """
        design = _design(np.asarray(x, dtype=float), "tilt")
        assert self.coef is not None and self.cov is not None
        se = np.sqrt(np.maximum(np.einsum("bi,mij,bj->mb", design, self.cov, design), 0.0))
        return self.coef @ design.T, se


def _design(x: NDArray[np.float64], model: str) -> NDArray[np.float64]:
    cols = [np.ones_like(x)] + ([x] if model == "tilt" else [])
    return np.stack(cols, axis=1)


def _normal_inverses(
    w: NDArray[np.float64], design: NDArray[np.float64], n_params: NDArray[np.int64]
) -> NDArray[np.float64]:
    """Each window's weighted least-squares covariance, ``pinv(X' W X)``, shape (M, 2, 2).

    ``w`` is 0 in the cells without an estimate, so they add nothing; a
    window with ``n_params`` 1 uses the first (level) column only.
    """
    cov = np.zeros((w.shape[0], 2, 2))
    for p in (1, 2):
        rows = n_params == p
        if rows.any():
            d = design[:, :p]
            cov[rows, :p, :p] = np.linalg.pinv(np.einsum("mb,bi,bj->mij", w[rows], d, d))
    return cov


def window_deviations(
    z: NDArray[np.float64],
    v: NDArray[np.float64],
    ok: NDArray[np.bool_],
    x: NDArray[np.float64],
    *,
    model: str = "tilt",
    dof: NDArray[np.float64] | None = None,
) -> WindowDeviations:
    """Estimate each window's level (and tilt) deviation from the group's shape.

    Parameters
    ----------
    z, v : ndarray, shape (M, B)
        Unbiased log band values and their sampling variances
        (:meth:`psdbound.spectra.bands.BandSpectra.log_unbiased`).
    ok : ndarray of bool, shape (M, B)
        Cells with an estimate.
    x : ndarray, shape (B,)
        Standardised log frequency of each band (the tilt's regressor).
    model : {"tilt", "level"}, default "tilt"
        Deviation model (:data:`SHAPE_MODELS`).
    dof : ndarray, shape (M, B), optional
        Degrees of freedom of the band values. Given, the shape test uses
        the Wilson-Hilferty cube root of each ratio estimate / fit, close
        to normal in the tails where the log of a chi-square with few
        degrees of freedom is not (its long lower tail made the log-scale
        test reject a common shape for about 0.6 % of homogeneous windows at
        a nominal 0.4 %); otherwise the log residuals.

    Returns
    -------
    WindowDeviations
    """
    if model not in SHAPE_MODELS:
        raise InputError(f"unknown deviation model {model!r}; choose from {SHAPE_MODELS}")
    m, n_b = z.shape
    w = np.where(ok, 1.0 / np.where(ok, v, 1.0), 0.0)
    zz = np.where(ok, z, 0.0)
    n_ok = ok.sum(axis=1)
    n_par = np.where((model == "tilt") & (n_ok >= _MIN_BANDS_TILT), 2, 1).astype(np.int64)
    wsum = np.maximum(w.sum(axis=0), 1e-300)
    mu = (w * zz).sum(axis=0) / wsum
    full = _design(x, "tilt")
    # the weights and designs do not change between backfitting sweeps: invert once
    cov = _normal_inverses(w, full, n_par)
    fitted = np.stack([np.ones(m, dtype=bool), n_par == 2], axis=1)  # the parameters refitted
    coef = np.zeros((m, 2))
    dev = np.zeros((m, n_b))
    for _ in range(_BACKFIT_ITER):
        coef = np.where(fitted, np.einsum("mij,mj->mi", cov, (w * (zz - mu)) @ full), coef)
        coef -= coef.mean(axis=0)  # identifiability: deviations average to 0 over the windows
        new = coef @ full.T
        mu_new = (w * (zz - new)).sum(axis=0) / wsum
        done = np.allclose(new, dev, atol=1e-9) and np.allclose(mu_new, mu, atol=1e-9)
        dev, mu = new, mu_new
        if done:
            break
    if m == 1:
        cov = np.zeros_like(cov)  # one window: its deviation from itself is 0 exactly
    se = np.sqrt(np.maximum(np.einsum("bi,mij,bj->mb", full, cov, full), 0.0))
    std = (zz - mu[None, :] - dev) * np.sqrt(w)
    if dof is not None:
        nu = np.where(ok, dof, 2.0)
        log_ratio = zz - mu[None, :] - dev + log_chi2_bias(nu)
        with np.errstate(over="ignore", invalid="ignore"):
            spread = np.sqrt(2.0 / (9.0 * nu))
            std = (np.cbrt(np.exp(log_ratio)) - (1.0 - 2.0 / (9.0 * nu))) / spread
    # one-sided: only a window above its group's shape can be left uncovered by the group
    above = np.where(ok, np.maximum(std, 0.0) ** 2, 0.0).sum(axis=1)
    p_spread = np.array(
        [
            chi_bar_squared_sf(t, int(k)) if k > n else 1.0
            for t, k, n in zip(above, n_ok, n_par, strict=True)
        ]
    )
    testable = n_ok > n_par
    p_end = np.array([end_excess_p(std[i, ok[i]]) if testable[i] else 1.0 for i in range(m)])
    tests = np.column_stack([p_spread, p_end])
    first = np.argmax(ok, axis=1)  # each window's lowest band with an estimate
    low = np.where(testable, std[np.arange(m), first], np.nan)
    return WindowDeviations(mu, dev, se, n_par, bonferroni_p(tests), coef, cov, tests, low)


def spread_upper_limit(d: NDArray[np.float64], se: NDArray[np.float64], a: float) -> float:
    """Q-profile upper confidence limit of the between-window variance of the levels.

    Parameters
    ----------
    d : ndarray
        Estimated levels of ``M`` windows.
    se : ndarray
        Their standard errors (> 0).
    a : float
        One-sided error probability.

    Returns
    -------
    float
        ``sigma^2`` solving ``Q(sigma^2) = chi2_{M-1}^{-1}(a)``, with
        ``Q(s2) = sum (d - dbar(s2))^2 / (se^2 + s2)`` the generalised Cochran
        statistic (Viechtbauer 2007); 0 when even ``Q(0)`` lies below that
        quantile, and 0 for one window. The limit exceeds the true variance
        with probability ``1 - a`` for normal levels and errors.
    """
    d, se = np.asarray(d, dtype=float), np.asarray(se, dtype=float)
    m = d.size
    if m < 2:
        return 0.0
    v = np.maximum(se**2, 1e-300)
    crit = float(stats.chi2.ppf(a, m - 1))

    def q(s2: float) -> float:
        w = 1.0 / (v + s2)
        mean = np.sum(w * d) / np.sum(w)
        return float(np.sum(w * (d - mean) ** 2)) - crit

    if q(0.0) <= 0.0:
        return 0.0
    hi = max(float(np.var(d)) * 10.0, float(v.max()))
    while q(hi) > 0.0:
        hi *= 10.0
    return float(optimize.brentq(q, 0.0, hi, xtol=1e-12 * hi))


def tolerance_factor(n_windows: int, n_allowed: int, a: float) -> float:
    """Return ``z*``: more than ``n_allowed`` windows exceed it with probability ``<= a``.

    Parameters
    ----------
    n_windows : int
        Windows ``M``.
    n_allowed : int
        Windows allowed above the limit, ``k``.
    a : float
        Error probability.

    Returns
    -------
    float
        ``z* = Phi^{-1}(1 - q)`` with ``q`` the largest exceedance probability
        whose binomial tail ``P(Bin(M, q) > k)`` is at most ``a``.
    """
    if n_windows < 1:
        return 0.0

    def tail(log_q: float) -> float:
        return float(stats.binom.sf(n_allowed, n_windows, np.exp(log_q))) - a

    lo, hi = np.log(1e-15), np.log(0.5)
    if tail(hi) <= 0.0:
        return 0.0
    return float(stats.norm.isf(np.exp(optimize.brentq(tail, lo, hi, xtol=1e-10))))


def chi_bar_squared_sf(t: float, n: int) -> float:
    """Survival function of ``sum_i max(0, e_i)^2`` for ``n`` independent standard normals.

    ``P(T > t) = sum_k C(n, k) 2^-n P(chi2_k > t)`` (the chi-bar-squared
    distribution of one-sided tests; Robertson, Wright and Dykstra 1988).
    """
    if t <= 0.0:
        return 1.0
    k = np.arange(1, n + 1)
    # chdtrc(k, t) is what stats.chi2.sf(t, k) computes (bit for bit), without the
    # distribution framework's overhead: this runs once per window and model
    return float(np.sum(_chi_bar_weights(n) * special.chdtrc(k, t)))


@lru_cache(maxsize=64)
def _chi_bar_weights(n: int) -> NDArray[np.float64]:
    """``C(n, k) 2^-n`` for ``k = 1..n`` (binomial probabilities), read-only."""
    weights = np.asarray(stats.binom.pmf(np.arange(1, n + 1), n, 0.5), dtype=np.float64)
    weights.setflags(write=False)
    return weights


def end_excess_p(e: NDArray[np.float64]) -> float:
    """p-value of the largest partial sum of residuals from either end of the bands.

    ``T = max_j S_j / sqrt(j)`` over the sums of the first ``j`` and of the
    last ``j`` standardised residuals (bands in frequency order); the
    p-value is the Bonferroni bound ``2 n Phi(-T)``, capped at 1. Powerful
    against a window whose spectrum departs from its group's at one end only
    (a slow reflector at the lowest frequencies, a shorter time constant at
    the highest), which a sum of squares over all bands dilutes.
    """
    e = np.asarray(e, dtype=float)
    n = e.size
    if n == 0:
        return 1.0
    j = np.sqrt(np.arange(1, n + 1))
    t = max(float(np.max(np.cumsum(e) / j)), float(np.max(np.cumsum(e[::-1]) / j)))
    return float(min(1.0, 2.0 * n * special.ndtr(-t)))  # = stats.norm.sf(t), bit for bit
