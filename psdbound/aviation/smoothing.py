"""Carrier smoothing of a first-order Gauss-Markov code error (seeds 000, 001, 004).

* the variance of the running mean of ``k`` unit-variance samples with lag-1
  correlation ``alpha`` (seed 000 eq. 12), the variance inflation vs smoothing
  time relative to a reference (eq. 20, reference 360 s), the standard-deviation
  inflation ``M(t)`` of seed 001 (reference 100 s), and the exact variance of a
  Hatch filter that switches from a running mean to a time constant ``K``
  (seed 000 eqs. 7-8);
* the smoothing-time ratio ``xi(tau)`` of seed 004 (eq. 17 / A7) for an
  exponential smoother with a Gauss-Markov input, exact or as the seed prints it.

All samples are at 1 Hz in the seeds; ``alpha`` is the correlation between
consecutive samples, ``alpha = exp(-dt / tau)`` for a Gauss-Markov error of
time constant ``tau`` (:func:`alpha_from_tau`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import brentq

from psdbound.errors import InputError

__all__ = [
    "SMOOTHING_RATIO_FORMULAS",
    "alpha_for_inflation",
    "alpha_from_tau",
    "hatch_filter_variance",
    "running_mean_variance",
    "smoothing_sigma_factor",
    "smoothing_time_ratio",
    "smoothing_variance_factor",
]

SMOOTHING_RATIO_FORMULAS = ("exact", "seed", "steady_state")


def _alpha(alpha: float) -> float:
    a = float(alpha)
    if not (0.0 <= a < 1.0):
        raise InputError(f"correlation alpha must be in [0, 1), got {alpha!r}")
    return a


# -------------------------------------------------------------- carrier smoothing
def alpha_from_tau(tau_s: float, dt_s: float = 1.0) -> float:
    """Lag-one correlation ``exp(-dt / tau)`` of a Gauss-Markov error sampled every ``dt``.

    Parameters
    ----------
    tau_s : float
        Time constant, seconds (> 0).
    dt_s : float, default 1
        Sampling interval, seconds.

    Returns
    -------
    float
    """
    if not (tau_s > 0 and dt_s > 0):
        raise InputError(f"need tau_s > 0 and dt_s > 0, got {tau_s}, {dt_s}")
    return math.exp(-dt_s / tau_s)


def running_mean_variance(n_samples: ArrayLike, alpha: float) -> NDArray[np.float64]:
    """Variance of the mean of ``k`` consecutive unit-variance AR(1) samples (seed 000 eq. 12).

    ``(1 + a) / (k (1 - a)) - 2 a (1 - a^k) / (k^2 (1 - a)^2)``, with
    ``cov(eta_i, eta_j) = a^|i-j|``; ``1/k`` for ``a = 0``. This is also the
    Hatch filter's variance while it is a running mean (``k <= K``).

    Parameters
    ----------
    n_samples : array_like
        Number of samples averaged ``k`` (>= 1; real values allowed).
    alpha : float
        Correlation between consecutive samples, in ``[0, 1)``.

    Returns
    -------
    ndarray
    """
    a = _alpha(alpha)
    k = np.asarray(n_samples, dtype=float)
    if not (np.isfinite(k).all() and (k >= 1).all()):
        raise InputError("n_samples must be finite and >= 1")
    return (1 + a) / (k * (1 - a)) - 2 * a * (1 - a**k) / (k**2 * (1 - a) ** 2)


def smoothing_variance_factor(
    n_samples: ArrayLike, alpha: float, *, n_ref: float = 360.0
) -> NDArray[np.float64]:
    """Variance inflation vs smoothing time, ``phi_alpha(k)`` of seed 000 eq. (20).

    ``running_mean_variance(k) / running_mean_variance(n_ref)`` for
    ``k <= n_ref`` and 1 beyond (the seed's conservative use of the running-
    mean shape only, with the 360 s convergence reference). Multiplies the
    converged *variance*: ``A_MP(k)``, ``A_noise(k)``.

    Parameters
    ----------
    n_samples : array_like
        Smoothing time in samples (seconds at 1 Hz), >= 1.
    alpha : float
        Correlation between consecutive samples.
    n_ref : float, default 360
        Convergence reference, samples.

    Returns
    -------
    ndarray
    """
    k = np.asarray(n_samples, dtype=float)
    ratio = running_mean_variance(np.minimum(k, n_ref), alpha) / running_mean_variance(n_ref, alpha)
    return np.where(k <= n_ref, ratio, 1.0)


def smoothing_sigma_factor(
    n_samples: ArrayLike, alpha: float, *, n_ref: float = 100.0
) -> NDArray[np.float64]:
    """Standard-deviation inflation ``M(t)`` of seed 001 (reference: the 100 s time constant).

    ``sqrt(running_mean_variance(t) / running_mean_variance(n_ref))`` for
    ``t <= n_ref``; 1 beyond (assumption: the seed gives the formula for the
    smoothing times up to the time constant). The seed uses ``alpha = 0.84``
    so that ``M(1) = 3``.

    Parameters
    ----------
    n_samples : array_like
        Smoothing time in samples (seconds at 1 Hz), >= 1.
    alpha : float
        Correlation between consecutive samples.
    n_ref : float, default 100
        Smoothing time constant, samples.

    Returns
    -------
    ndarray
    """
    return np.sqrt(smoothing_variance_factor(n_samples, alpha, n_ref=n_ref))


def alpha_for_inflation(
    inflation: float, *, n_ref: float, n_samples: float = 1.0, kind: str = "variance"
) -> float:
    """Find the correlation ``alpha`` giving an inflation at ``n_samples`` relative to ``n_ref``.

    Solves ``smoothing_variance_factor(n_samples, alpha, n_ref=n_ref) = inflation``
    (``kind="variance"``, seed 000: 100 -> 0.567, 200 -> 0.287 for
    ``n_ref = 360``) or ``smoothing_sigma_factor(...) = inflation``
    (``kind="sigma"``, seed 001: ``M(1) = 3`` -> 0.844 for ``n_ref = 100``)
    with Brent's method. The inflation decreases with ``alpha`` (from its
    white-noise value at ``alpha = 0`` to 1), so the root is unique.

    Parameters
    ----------
    inflation : float
        Target factor (> 1).
    n_ref : float
        Reference smoothing time, samples.
    n_samples : float, default 1
        Smoothing time at which the target applies (1: no smoothing).
    kind : {"variance", "sigma"}, default "variance"
        Whether ``inflation`` multiplies the variance or the sigma.

    Returns
    -------
    float

    Raises
    ------
    InputError
        If no ``alpha`` in ``[0, 1)`` reaches the target.
    """
    if kind not in ("variance", "sigma"):
        raise InputError(f"kind must be 'variance' or 'sigma', got {kind!r}")
    if not 1 <= n_samples < n_ref:
        raise InputError(f"need 1 <= n_samples < n_ref, got {n_samples}, {n_ref}")
    target = float(inflation) ** 2 if kind == "sigma" else float(inflation)

    def g(a: float) -> float:
        return float(smoothing_variance_factor(n_samples, a, n_ref=n_ref)) - target

    if not target > 1.0:
        raise InputError(f"inflation must be > 1, got {inflation}")
    top = g(0.0)
    if top < 0:
        raise InputError(
            f"inflation {inflation} is above its white-noise maximum "
            f"{math.sqrt(top + target) if kind == 'sigma' else top + target:.6g} "
            "(alpha = 0); no alpha in [0, 1) reaches it"
        )
    if top == 0:
        return 0.0
    hi = 1.0 - 1e-6  # closer to 1 the closed form loses digits to cancellation
    if g(hi) > 0:
        raise InputError(
            f"inflation {inflation} is too close to 1 (needs alpha > {hi}); no reliable root"
        )
    return float(brentq(g, 0.0, hi, xtol=1e-14, rtol=1e-12))


def hatch_filter_variance(
    n_samples: int, alpha: float, *, time_constant: float = 100.0
) -> NDArray[np.float64]:
    """Exact variance of a Hatch-smoothed unit-variance AR(1) error, samples 1 .. n.

    ``eps_k = (1 - 1/k) eps_{k-1} + eta_k / k`` for ``k <= K`` (running mean)
    and ``(1 - 1/K) eps_{k-1} + eta_k / K`` after (seed 000 eqs. 7-8),
    ``eta`` the unit-variance AR(1) error of correlation ``alpha`` started in
    its stationary distribution. Computed by a covariance recursion on
    ``(eps, eta)`` (no closed form needed; equals eq. 12 for ``k <= K``).

    Parameters
    ----------
    n_samples : int
        Number of samples ``n`` (>= 1).
    alpha : float
        Correlation between consecutive samples.
    time_constant : float, default 100
        Smoothing constant ``K``, samples (>= 1).

    Returns
    -------
    ndarray, shape (n,)
        ``var(eps_k)`` for ``k = 1 .. n`` (dimensionless; times the raw variance).
    """
    a = _alpha(alpha)
    n = int(n_samples)
    if n < 1 or not time_constant >= 1:
        raise InputError(
            f"need n_samples >= 1 and time_constant >= 1, got {n_samples}, {time_constant}"
        )
    out = np.empty(n)
    p = np.array([[0.0, 0.0], [0.0, 1.0]])  # (eps_0, eta_0)
    q = 1.0 - a * a
    for k in range(1, n + 1):
        kk = min(float(k), float(time_constant))
        b = 1.0 / kk
        t = np.array([[1.0 - b, b * a], [0.0, a]])
        g = np.array([b, 1.0])
        p = t @ p @ t.T + q * np.outer(g, g)
        out[k - 1] = p[0, 0]
    return out


def smoothing_time_ratio(
    tau_s: ArrayLike,
    *,
    tau_corr_s: float,
    tau_ref_s: float = 100.0,
    dt_s: float = 1.0,
    formula: str = "exact",
) -> NDArray[np.float64]:
    """Smoothing-time ratio ``xi(tau) = sigma(tau) / sigma(tau_ref)`` of seed 004 (eq. 17).

    The smoothed error is ``(T/tau) sum_{i=1}^{tau/T} (1 - T/tau)^(i-1) eta_i``
    (seed 004 eq. A3: an exponential smoother of time constant ``tau``
    truncated to ``tau/T`` samples), ``eta`` Gauss-Markov with
    ``cov = exp(-|i-j| T / tau_corr)``. Formulas:

    ``"exact"`` (default)
        the variance of that sum, ``w^T C w``.
    ``"seed"``
        eq. (A6) as printed: ``sum w_i^2 + 2 sum_{i != j} w_i w_j c_ij`` --
        it counts every off-diagonal pair twice, and reproduces the seed's
        Table 1 (1.1486, 1.3026, 1.3997 for 60, 30, 15 s with
        ``tau_corr = 30 s``, ``T = 1 s``) to 4 decimals.
    ``"steady_state"``
        the untruncated smoother ``y_k = (1 - T/tau) y_{k-1} + (T/tau) eta_k``
        in steady state: ``b^2 (1 + a r) / ((1 - a^2)(1 - a r))``,
        ``a = 1 - T/tau``, ``b = T/tau``, ``r = exp(-T/tau_corr)`` -- the
        actual converged Hatch filter, whose ratios are larger.

    Parameters
    ----------
    tau_s : array_like
        Smoothing time constants, seconds (multiples of ``dt_s`` for
        ``"exact"``/``"seed"``; rounded to the nearest sample count).
    tau_corr_s : float
        Correlation time of the Gauss-Markov input, seconds.
    tau_ref_s : float, default 100
        Reference smoothing time, seconds.
    dt_s : float, default 1
        Sampling interval ``T``, seconds.
    formula : {"exact", "seed", "steady_state"}, default "exact"
        See above.

    Returns
    -------
    ndarray
    """
    if formula not in SMOOTHING_RATIO_FORMULAS:
        raise InputError(f"unknown formula {formula!r}; choose from {SMOOTHING_RATIO_FORMULAS}")
    if not (tau_corr_s > 0 and tau_ref_s > 0 and dt_s > 0):
        raise InputError("tau_corr_s, tau_ref_s and dt_s must be > 0")
    r = math.exp(-dt_s / tau_corr_s)

    def var(tau: float) -> float:
        if not tau >= dt_s:
            raise InputError(f"smoothing time {tau} s must be >= dt_s = {dt_s} s")
        b = dt_s / tau
        a = 1.0 - b
        if formula == "steady_state":
            return b * b * (1 + a * r) / ((1 - a * a) * (1 - a * r))
        n = max(1, int(round(tau / dt_s)))
        i = np.arange(n)
        w = b * a**i
        c = r ** np.abs(i[:, None] - i[None, :])
        full = float(w @ c @ w)
        if formula == "exact":
            return full
        diag = float(w @ w)
        return diag + 2.0 * (full - diag)

    taus = np.asarray(tau_s, dtype=float)
    ref = var(float(tau_ref_s))
    out = np.array([math.sqrt(var(float(t)) / ref) for t in taus.reshape(-1)])
    return out.reshape(taus.shape)
