"""A constant range bias through a linear Kalman filter, against an alert limit (seed 003).

A filter with model ``x_l = F x_{l-1} + w``, ``z_l = H x_l + v + b_l``
(``cov w = Q``, ``cov v = R``) that does not know about the bias ``b_l``
has the estimation error ``e_l = x_l - x_hat_l`` with mean (seed 003 eq. 3)

    ``E[e_l] = (I - K_l H) F E[e_{l-1}] - K_l b_l``,  ``E[e_0] = 0``

and the covariance the filter itself computes (the bias shifts the error,
it does not widen it). The gains ``K_l`` come from the filter's own
covariance recursion (:func:`kalman_gains`). The position rows of
``E[e_l]`` are the deterministic position error; with the covariance
``C`` of the horizontal error, the probability that the horizontal error
exceeds a horizontal alert limit is :func:`prob_horizontal_exceeds`, and
:func:`fault_threshold` is the smallest bias on one satellite that makes
that probability reach a target (seed 003 eq. 14: ``0.1 P_IR``).

Closed form used in the tests: for a static state without process noise
and a diffuse prior, the filter is recursive least squares, and after ``K``
clean epochs and ``n`` biased ones the mean error is ``n / (K + n) S b``
(``S`` the least-squares projection); from the first epoch on it is ``S b``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import ndtr

from psdbound.errors import InputError

__all__ = [
    "BiasResponse",
    "bias_bound_response",
    "bias_response",
    "fault_threshold",
    "kalman_gains",
    "prob_horizontal_exceeds",
]


def _square(name: str, a: ArrayLike, n: int | None = None) -> NDArray[np.float64]:
    m = np.atleast_2d(np.asarray(a, dtype=float))
    if m.shape[0] != m.shape[1] or (n is not None and m.shape[0] != n):
        raise InputError(f"{name} must be square{'' if n is None else f' ({n} x {n})'}")
    if not np.isfinite(m).all():
        raise InputError(f"{name} has NaN or infinite entries")
    return m


def kalman_gains(
    f: ArrayLike, q: ArrayLike, h: ArrayLike, r: ArrayLike, p0: ArrayLike, n_steps: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Gains and a-posteriori covariances of a time-invariant Kalman filter.

    Parameters
    ----------
    f, q : array_like, shape (nx, nx)
        Transition and process-noise covariance over one step.
    h : array_like, shape (m, nx)
        Measurement matrix.
    r : array_like, shape (m, m)
        Measurement-noise covariance (units of the measurements squared).
    p0 : array_like, shape (nx, nx)
        A-priori covariance before the first update.
    n_steps : int
        Number of updates (>= 1).

    Returns
    -------
    gains : ndarray, shape (n_steps, nx, m)
    p_post : ndarray, shape (n_steps, nx, nx)
    """
    fm = _square("F", f)
    nx = fm.shape[0]
    qm, pm = _square("Q", q, nx), _square("P0", p0, nx)
    hm = np.atleast_2d(np.asarray(h, dtype=float))
    if hm.shape[1] != nx:
        raise InputError(f"H must have {nx} columns, got {hm.shape}")
    rm = _square("R", r, hm.shape[0])
    if n_steps < 1:
        raise InputError("n_steps must be >= 1")
    gains = np.empty((n_steps, nx, hm.shape[0]))
    posts = np.empty((n_steps, nx, nx))
    p = pm
    eye = np.eye(nx)
    for k in range(n_steps):
        if k:
            p = fm @ p @ fm.T + qm
        s = hm @ p @ hm.T + rm
        kk = np.linalg.solve(s, hm @ p).T
        a = eye - kk @ hm
        p = a @ p @ a.T + kk @ rm @ kk.T  # Joseph form
        gains[k], posts[k] = kk, p
    return gains, posts


@dataclass(frozen=True)
class BiasResponse:
    """Mean estimation error caused by measurement biases.

    Attributes
    ----------
    mean_error : ndarray, shape (n_steps, nx)
        ``E[x - x_hat]`` after each update, units of the states.
    covariance : ndarray, shape (n_steps, nx, nx)
        The filter's a-posteriori covariance (the error's, bias aside).
    """

    mean_error: NDArray[np.float64]
    covariance: NDArray[np.float64]

    def horizontal(self, rows: tuple[int, int] = (0, 1)) -> NDArray[np.float64]:
        """Return the horizontal mean error ``(n_steps, 2)`` from two state rows."""
        return self.mean_error[:, list(rows)]

    def peak_to_final(self, rows: tuple[int, int] = (0, 1)) -> float:
        """Largest horizontal error norm over the final one (seed 003: up to about 2)."""
        norm_h = np.linalg.norm(self.horizontal(rows), axis=1)
        return float(norm_h.max() / norm_h[-1]) if norm_h[-1] > 0 else math.inf


def bias_response(
    f: ArrayLike,
    q: ArrayLike,
    h: ArrayLike,
    r: ArrayLike,
    bias_m: ArrayLike,
    *,
    n_steps: int,
    onset_step: int = 0,
    p0: ArrayLike | None = None,
) -> BiasResponse:
    """Propagate a constant bias vector, present from ``onset_step`` on, through the filter.

    Parameters
    ----------
    f, q, h, r : array_like
        The filter model (see :func:`kalman_gains`).
    bias_m : array_like, shape (m,)
        Bias on each measurement, measurement units (e.g. metres on one
        satellite, zeros elsewhere).
    n_steps : int
        Number of updates.
    onset_step : int, default 0
        First update (0-based) that sees the bias.
    p0 : array_like, optional
        A-priori covariance; default a diffuse ``1e8 I``.

    Returns
    -------
    BiasResponse
    """
    hm = np.atleast_2d(np.asarray(h, dtype=float))
    nx = hm.shape[1]
    b = np.asarray(bias_m, dtype=float).reshape(-1)
    if b.size != hm.shape[0] or not np.isfinite(b).all():
        raise InputError(f"bias_m must hold {hm.shape[0]} finite values")
    if not 0 <= onset_step < n_steps:
        raise InputError(f"need 0 <= onset_step < n_steps, got {onset_step}, {n_steps}")
    pm = 1e8 * np.eye(nx) if p0 is None else p0
    gains, posts = kalman_gains(f, q, hm, r, pm, n_steps)
    fm = np.asarray(f, dtype=float)
    e = np.zeros(nx)
    out = np.empty((n_steps, nx))
    for k in range(n_steps):
        bk = b if k >= onset_step else 0.0 * b
        e = (np.eye(nx) - gains[k] @ hm) @ (fm @ e) - gains[k] @ bk
        out[k] = e
    return BiasResponse(out, posts)


def bias_bound_response(
    f: ArrayLike,
    q: ArrayLike,
    h: ArrayLike,
    r: ArrayLike,
    bias_bound_m: ArrayLike,
    *,
    n_steps: int,
    p0: ArrayLike | None = None,
) -> NDArray[np.float64]:
    """Worst-case mean error of each state for biases known only by a bound ``|b_i| <= B_i``.

    The paired overbound of a range error gives a bias bound ``B_i`` of
    unknown sign ([Rife2006]_). The mean error is linear in the biases,
    ``E[e_l] = sum_i M_l[:, i] b_i`` (``M_l[:, i]``: the response to a unit
    bias on measurement ``i``, :func:`bias_response`), so its largest value
    per state is ``sum_i |M_l[:, i]| B_i`` -- the filter's counterpart of the
    ``sum |S_vert,i| b_i`` added to a snapshot VPL
    (:func:`psdbound.aviation.budget.vpl`).

    Parameters
    ----------
    f, q, h, r : array_like
        The filter model (see :func:`kalman_gains`).
    bias_bound_m : array_like, shape (m,)
        Bias bound of each measurement, >= 0, measurement units.
    n_steps : int
        Number of updates.
    p0 : array_like, optional
        A-priori covariance; default a diffuse ``1e8 I``.

    Returns
    -------
    ndarray, shape (n_steps, nx)
        ``sum_i |M_l[j, i]| B_i`` per update ``l`` and state ``j``, state units.
    """
    hm = np.atleast_2d(np.asarray(h, dtype=float))
    bound = np.asarray(bias_bound_m, dtype=float).reshape(-1)
    if bound.size != hm.shape[0] or not (np.isfinite(bound).all() and (bound >= 0).all()):
        raise InputError(f"bias_bound_m must hold {hm.shape[0]} finite values >= 0")
    out = np.zeros((n_steps, hm.shape[1]))
    for i in np.flatnonzero(bound > 0):
        unit = np.zeros(bound.size)
        unit[i] = 1.0
        resp = bias_response(f, q, hm, r, unit, n_steps=n_steps, p0=p0).mean_error
        out += np.abs(resp) * bound[i]
    return out


def prob_horizontal_exceeds(mean_m: ArrayLike, cov_m2: ArrayLike, alert_limit_m: float) -> float:
    """``P(|e| > AL)`` for a 2-D Gaussian horizontal error ``e ~ N(mean, cov)``.

    Integrates, in the covariance's principal axes, the exact probability
    outside the disk along one axis given the other, with tail functions
    (no ``1 - P`` cancellation: accurate down to about 1e-300).

    Parameters
    ----------
    mean_m : array_like, shape (2,)
        Mean horizontal error, metres.
    cov_m2 : array_like, shape (2, 2)
        Covariance, m^2 (positive definite).
    alert_limit_m : float
        Horizontal alert limit, metres (> 0).

    Returns
    -------
    float
    """
    mu = np.asarray(mean_m, dtype=float).reshape(-1)
    c = np.asarray(cov_m2, dtype=float)
    if mu.size != 2 or c.shape != (2, 2) or not alert_limit_m > 0:
        raise InputError("need a 2-vector mean, a 2x2 covariance and an alert limit > 0")
    w, v = np.linalg.eigh(c)
    if not (w > 0).all():
        raise InputError("the horizontal covariance must be positive definite")
    m = v.T @ mu
    s = np.sqrt(w)
    al = float(alert_limit_m)

    def inside_strip(x1: float) -> float:
        half = math.sqrt(max(al * al - x1 * x1, 0.0))
        return float(ndtr((-half - m[1]) / s[1]) + ndtr((m[1] - half) / s[1]))

    def integrand(x1: float) -> float:
        u = (x1 - m[0]) / s[0]
        return inside_strip(x1) * math.exp(-0.5 * u * u) / (s[0] * math.sqrt(2.0 * math.pi))

    outside = float(ndtr((-al - m[0]) / s[0]) + ndtr((m[0] - al) / s[0]))
    part, _ = quad(
        integrand,
        -al,
        al,
        points=[float(np.clip(m[0], -al, al))],
        limit=200,
        epsabs=0.0,
        epsrel=1e-9,
    )
    return outside + part


def fault_threshold(
    error_per_metre: ArrayLike,
    cov_m2: ArrayLike,
    alert_limit_m: float,
    target_probability: float,
    *,
    nominal_mean_m: ArrayLike = (0.0, 0.0),
    sign: float = 1.0,
    max_bias_m: float = 1e4,
) -> float:
    """Smallest bias (one sign) whose horizontal error exceeds AL with ``target_probability``.

    The mean horizontal error is ``nominal + b * error_per_metre`` (linear
    in the bias: e.g. the final value of :func:`bias_response` for a 1 m
    bias); solves ``P(|e| > AL) = target`` for ``b`` along ``sign``.

    Parameters
    ----------
    error_per_metre : array_like, shape (2,)
        Horizontal mean error per metre of bias, m/m.
    cov_m2 : array_like, shape (2, 2)
        Horizontal error covariance, m^2.
    alert_limit_m : float
        Alert limit, metres.
    target_probability : float
        E.g. ``0.1 * P_IR`` (seed 003 eq. 14).
    nominal_mean_m : array_like, default (0, 0)
        Mean error from the nominal biases, metres.
    sign : float, default 1
        Search positive (+1) or negative (-1) biases.
    max_bias_m : float, default 1e4
        Search limit, metres.

    Returns
    -------
    float
        The bias magnitude, metres (0 if the nominal case already exceeds).
    """
    if not 0 < target_probability < 1:
        raise InputError("target_probability must be in (0, 1)")
    d = np.asarray(error_per_metre, dtype=float) * math.copysign(1.0, sign)
    m0 = np.asarray(nominal_mean_m, dtype=float)

    def g(b: float) -> float:
        p = prob_horizontal_exceeds(m0 + b * d, cov_m2, alert_limit_m)
        return math.log(max(p, 1e-320)) - math.log(target_probability)

    if g(0.0) >= 0:
        return 0.0
    if g(max_bias_m) < 0:
        raise InputError(f"no bias below {max_bias_m} m reaches probability {target_probability}")
    return float(brentq(g, 0.0, max_bias_m, xtol=1e-9))
