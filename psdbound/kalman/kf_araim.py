"""KF-ARAIM building blocks: a position-velocity-clock filter, one multipath state per satellite.

The filter of the worked example (issue 20, part 4): the receiver's
position ``r`` (m), velocity ``v`` (m/s), clock bias ``b`` (m) and drift
``d`` (m/s) -- 8 states -- plus one Gauss-Markov multipath state per
satellite appended by :func:`psdbound.kalman.augment_gm_states`. Over one
interval ``dt``::

    r[k+1] = r + dt v,  v[k+1] = v + w_v      (white acceleration, q_a m^2/s^3 per axis)
    b[k+1] = b + dt d + w_b,  d[k+1] = d + w_d (clock: q_b m^2/s, q_d m^2/s^3)
    y_i    = -u_i . r + b + g_i + e_i         (u_i the unit line of sight to satellite i)

``y_i`` is a carrier-phase (ambiguity-free, e.g. time-differenced or
already fixed) range residual; ``g_i`` the multipath state of the design
model, ``e_i`` its white part.

* :func:`predict_position_covariance` -- the design (filter's own)
  position-error covariance over time; with ``truth=`` also the exact true
  covariance for true multipath processes (covariance analysis).
* :func:`monte_carlo_position_covariance` -- the same filter driven by given
  multipath series per satellite; the position-error covariance from the
  sample paths (the error from the initial state, process noise and other
  noise is added exactly, :func:`psdbound.kalman.analyze_covariance` with
  :class:`~psdbound.kalman.ErrorSequences`).

The design model per satellite is a :class:`~psdbound.kalman.GaussMarkovBound`
(stationary start) or a :class:`~psdbound.kalman.UncertainGMBound` (its
initial variance ``P0``), one for all satellites or one per satellite.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.kalman.analysis import CovarianceAnalysis
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.covariance import analyze_covariance
from psdbound.kalman.process import ErrorProcess
from psdbound.kalman.truth import ErrorSequences
from psdbound.kalman.uncertain import UncertainGMBound

__all__ = [
    "PositionCovariance",
    "monte_carlo_position_covariance",
    "predict_position_covariance",
    "pvt_model",
]

Design = GaussMarkovBound | UncertainGMBound
N_BASE = 8
_POS = slice(0, 3)


def pvt_model(
    los_unit: ArrayLike,
    dt_s: float,
    *,
    accel_psd_m2_s3: float = 1e-2,
    clock_bias_psd_m2_s: float = 1e-4,
    clock_drift_psd_m2_s3: float = 1e-4,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Return the 8-state position-velocity-clock model ``(F, Q, H)`` over one interval.

    Parameters
    ----------
    los_unit : array_like, shape (m, 3)
        Unit line-of-sight vectors receiver -> satellite (any Cartesian frame;
        positions come out in the same frame).
    dt_s : float
        Filter interval, seconds.
    accel_psd_m2_s3 : float, default 1e-2
        White-acceleration PSD per axis, m^2/s^3.
    clock_bias_psd_m2_s : float, default 1e-4
        Clock-bias random-walk PSD, m^2/s.
    clock_drift_psd_m2_s3 : float, default 1e-4
        Clock-drift random-walk PSD, m^2/s^3.

    Returns
    -------
    F, Q : ndarray, shape (8, 8)
        States ``[r (3), v (3), b, d]``.
    H : ndarray, shape (m, 8)
        Rows ``[-u_i, 0, 1, 0]``.

    Raises
    ------
    InputError
        For a bad geometry (not unit vectors, fewer than 4 satellites) or interval.
    """
    u = np.asarray(los_unit, dtype=float)
    if u.ndim != 2 or u.shape[1] != 3 or u.shape[0] < 4:
        raise InputError(f"los_unit must have shape (m >= 4, 3), got {u.shape}")
    if not np.allclose(np.linalg.norm(u, axis=1), 1.0, atol=1e-6):
        raise InputError("los_unit rows must be unit vectors")
    dt = float(dt_s)
    if not dt > 0:
        raise InputError(f"dt_s must be > 0 s, got {dt_s!r}")
    F = np.eye(N_BASE)
    F[0:3, 3:6] = dt * np.eye(3)
    F[6, 7] = dt
    blk = np.array([[dt**3 / 3, dt**2 / 2], [dt**2 / 2, dt]])
    Q = np.zeros((N_BASE, N_BASE))
    for ax in range(3):
        idx = np.ix_([ax, ax + 3], [ax, ax + 3])
        Q[idx] = accel_psd_m2_s3 * blk
    Q[6:8, 6:8] = clock_drift_psd_m2_s3 * blk
    Q[6, 6] += clock_bias_psd_m2_s * dt
    H = np.zeros((u.shape[0], N_BASE))
    H[:, 0:3] = -u
    H[:, 6] = 1.0
    return F, Q, H


@dataclass(frozen=True)
class PositionCovariance:
    """Position-error covariance over time: the design's and the true (or empirical) one.

    Attributes
    ----------
    time_s : ndarray, shape (n_steps,)
        Time of each update, seconds (first update at 0).
    p_design_m2 : ndarray, shape (n_steps, 3, 3)
        The filter's own (design) a-posteriori position covariance, m^2.
    p_true_m2 : ndarray, shape (n_steps, 3, 3), or None
        True position-error covariance (exact, or from sample paths), m^2.
    method : str
        ``"design"``, ``"state_space"`` (exact) or ``"monte_carlo"``.
    analysis : CovarianceAnalysis or None
        The full analysis (all 8 states) when a truth was given.
    """

    time_s: NDArray[np.float64]
    p_design_m2: NDArray[np.float64]
    p_true_m2: NDArray[np.float64] | None
    method: str
    analysis: CovarianceAnalysis | None = None

    @property
    def sigma_design_m(self) -> NDArray[np.float64]:
        """Design standard deviation per axis, shape (n_steps, 3), metres."""
        return np.sqrt(np.diagonal(self.p_design_m2, axis1=1, axis2=2))

    @property
    def sigma_true_m(self) -> NDArray[np.float64] | None:
        """True (or empirical) standard deviation per axis, shape (n_steps, 3), metres."""
        if self.p_true_m2 is None:
            return None
        return np.sqrt(np.diagonal(self.p_true_m2, axis1=1, axis2=2))


def _designs(
    models: Design | Sequence[Design], m: int
) -> tuple[list[GaussMarkovBound], NDArray[np.float64]]:
    items = (
        [models] * m if isinstance(models, GaussMarkovBound | UncertainGMBound) else list(models)
    )
    if len(items) != m:
        raise InputError(f"need one model per satellite: got {len(items)} for {m} satellites")
    bounds, p0 = [], np.empty(m)
    for i, it in enumerate(items):
        if isinstance(it, UncertainGMBound):
            bounds.append(it.bound)
            p0[i] = it.p0_m2
        elif isinstance(it, GaussMarkovBound):
            bounds.append(it)
            p0[i] = it.sigma_gm_m**2
        else:
            raise InputError(f"model {i} is a {type(it).__name__}, not a bound")
    return bounds, p0


def _default_p0(p0_base: ArrayLike | None) -> NDArray[np.float64]:
    if p0_base is None:
        return np.diag([100.0, 100.0, 100.0, 1.0, 1.0, 1.0, 1e4, 100.0])
    return np.asarray(p0_base, dtype=float)


def _run(
    models: Design | Sequence[Design],
    los_unit: ArrayLike,
    dt_s: float,
    n_steps: int,
    truth: ErrorProcess | ErrorSequences | Sequence[ErrorProcess],
    p0_base: ArrayLike | None,
    r_other_m2: ArrayLike | None,
    model_kw: dict[str, float],
) -> CovarianceAnalysis:
    F, Q, H = pvt_model(los_unit, dt_s, **model_kw)
    bounds, p0 = _designs(models, H.shape[0])
    return analyze_covariance(
        F,
        Q,
        H,
        r_other_m2,
        bounds,
        truth,
        dt_s=dt_s,
        n_steps=n_steps,
        p0_base=_default_p0(p0_base),
        p0_gm_m2=p0,
        steady_state=False,
    )


def predict_position_covariance(
    models: Design | Sequence[Design],
    los_unit: ArrayLike,
    dt_s: float,
    n_steps: int,
    *,
    truth: ErrorProcess | Sequence[ErrorProcess] | None = None,
    p0_base: ArrayLike | None = None,
    r_other_m2: ArrayLike | None = None,
    **model_kw: float,
) -> PositionCovariance:
    """Design position-error covariance of the PVT + multipath filter over time.

    Parameters
    ----------
    models : GaussMarkovBound or UncertainGMBound, or a sequence (one per satellite)
        Multipath design model(s) on the raw range (no elevation mapping).
    los_unit : array_like, shape (m, 3)
        Unit line-of-sight vectors (constant geometry).
    dt_s : float
        Filter interval, seconds.
    n_steps : int
        Number of updates.
    truth : ErrorProcess or sequence of ErrorProcess, optional
        True multipath (one for all satellites, independent copies, or one
        per satellite): adds the exact true covariance.
    p0_base : array_like, shape (8, 8), optional
        Initial covariance of ``[r, v, b, d]``; default
        ``diag(100, 100, 100, 1, 1, 1, 1e4, 100)`` (m^2, (m/s)^2).
    r_other_m2 : array_like, shape (m, m), optional
        Other (non-multipath) measurement noise, m^2.
    **model_kw : float
        ``accel_psd_m2_s3``, ``clock_bias_psd_m2_s``, ``clock_drift_psd_m2_s3``
        of :func:`pvt_model`.

    Returns
    -------
    PositionCovariance
    """
    dt = float(dt_s)
    u = np.asarray(los_unit, dtype=float)
    t = truth
    if t is None:
        # the design itself as truth: no extra cost worth avoiding, and P_true is then P_design
        t = ErrorProcess.white(0.0, dt)
    res = _run(models, u, dt, n_steps, t, p0_base, r_other_m2, model_kw)
    return PositionCovariance(
        time_s=np.arange(res.n_steps) * dt,
        p_design_m2=res.p_filter_m2[:, _POS, _POS],
        p_true_m2=None if truth is None else res.p_true_m2[:, _POS, _POS],
        method="design" if truth is None else res.method,
        analysis=None if truth is None else res,
    )


def monte_carlo_position_covariance(
    models: Design | Sequence[Design],
    los_unit: ArrayLike,
    multipath_m: ArrayLike,
    dt_s: float,
    *,
    p0_base: ArrayLike | None = None,
    r_other_m2: ArrayLike | None = None,
    **model_kw: float,
) -> PositionCovariance:
    """Drive the filter with given multipath series and return the position-error covariance.

    Parameters
    ----------
    models : GaussMarkovBound or UncertainGMBound, or a sequence (one per satellite)
        Multipath design model(s).
    los_unit : array_like, shape (m, 3)
        Unit line-of-sight vectors.
    multipath_m : array_like, shape (n_paths, n_steps, m)
        Multipath (plus any white noise) per path, step and satellite, metres;
        independent, zero-mean paths.
    dt_s : float
        Interval of the series and of the filter, seconds.
    p0_base, r_other_m2, **model_kw
        As in :func:`predict_position_covariance`.

    Returns
    -------
    PositionCovariance
        ``p_true_m2`` from the paths (``method = "monte_carlo"``); its
        relative sampling error is about ``sqrt(2 / n_paths)``.

    Raises
    ------
    InputError
        If the series do not have one column per satellite.
    """
    x = np.asarray(multipath_m, dtype=float)
    u = np.asarray(los_unit, dtype=float)
    if x.ndim != 3 or x.shape[2] != u.shape[0]:
        raise InputError(
            f"multipath_m must have shape (n_paths, n_steps, {u.shape[0]}), got {x.shape}"
        )
    res = _run(
        models,
        u,
        float(dt_s),
        x.shape[1],
        ErrorSequences(x, float(dt_s)),
        p0_base,
        r_other_m2,
        model_kw,
    )
    return PositionCovariance(
        time_s=np.arange(res.n_steps) * float(dt_s),
        p_design_m2=res.p_filter_m2[:, _POS, _POS],
        p_true_m2=res.p_true_m2[:, _POS, _POS],
        method="monte_carlo",
        analysis=res,
    )
