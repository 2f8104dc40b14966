"""Augment a filter's state with one Gauss-Markov multipath state per measurement.

Given a filter's own discrete model over one interval ``dt``::

    x[k+1] = F x[k] + w[k],   w ~ N(0, Q)          (n states)
    y[k]   = H x[k] + v[k],   v ~ N(0, R)          (m measurements)

and a bound per measurement (one satellite / signal each), the augmented
model appends ``m`` states ``g_i``, the elevation-**normalised** multipath of
measurement ``i`` (metres at the mapping's zenith scale; the raw error when
the bound has no mapping)::

    [x; g][k+1] = [[F, 0], [0, diag(Phi_i)]] [x; g][k] + [w; u][k]
    y[k]        = [H, diag(m_i)] [x; g][k] + v[k] + e_wn[k]

    Q_aug = blockdiag(Q, diag(Qd_i)),   R_aug = R + diag(m_i^2 R_i),
    P0 of g_i = sigma_gm_i^2 (stationary), uncorrelated with x.

``Phi_i, Qd_i, R_i`` are the bound's :meth:`~psdbound.kalman.GaussMarkovBound.to_state_space`
at ``dt`` and ``m_i = m(el_i)`` is the mapping factor at the satellite's
elevation (1 without elevation). Because ``g_i`` is normalised, a changing
elevation only changes the measurement matrix and ``R_aug``: call this again
each epoch with the current ``H`` and elevations and keep the filter's
covariance. When a satellite sets, drop its row and column; when one rises,
append a state with variance ``sigma_gm^2`` and zero cross-covariance.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.process import check_covariance

__all__ = ["AugmentedModel", "augment_gm_states", "broadcast_bounds"]


def broadcast_bounds(
    bounds: GaussMarkovBound | Sequence[GaussMarkovBound], n_measurements: int
) -> list[GaussMarkovBound]:
    """Return one bound per measurement (a single bound is repeated).

    Parameters
    ----------
    bounds : GaussMarkovBound or sequence of GaussMarkovBound
        One bound for every measurement, or one per measurement.
    n_measurements : int
        Number of measurements ``m``.

    Returns
    -------
    list of GaussMarkovBound

    Raises
    ------
    InputError
        If the number of bounds is neither 1 nor ``m``, or an item is not a bound.
    """
    if isinstance(bounds, GaussMarkovBound):
        return [bounds] * n_measurements
    out = list(bounds)
    if len(out) != n_measurements:
        raise InputError(
            f"need one bound per measurement: got {len(out)} bounds for {n_measurements} "
            "measurements"
        )
    for i, b in enumerate(out):
        if not isinstance(b, GaussMarkovBound):
            raise InputError(f"bound {i} is a {type(b).__name__}, not a GaussMarkovBound")
    return out


def _matrix(name: str, a: ArrayLike, shape: tuple[int, int]) -> NDArray[np.float64]:
    arr = np.asarray(a, dtype=float)
    if arr.shape != shape:
        raise InputError(f"{name} must have shape {shape}, got {arr.shape}")
    if not np.isfinite(arr).all():
        raise InputError(f"{name} has non-finite entries")
    return arr


@dataclass(frozen=True)
class AugmentedModel:
    """A filter model augmented with Gauss-Markov multipath states.

    Attributes
    ----------
    F, Q : ndarray, shape (n + m, n + m)
        Transition and process-noise covariance over one interval.
    H : ndarray, shape (m, n + m)
        Measurement matrix; the multipath block is ``diag(m_i)``.
    R : ndarray, shape (m, m)
        Measurement-noise covariance including the bound's white noise, m^2.
    p0_gm_m2 : ndarray, shape (m,)
        Stationary (initial) variance of each multipath state, m^2.
    n_base : int
        Number of the filter's own states ``n`` (they come first).
    scale : ndarray, shape (m,)
        Mapping factors ``m(el_i)`` used in ``H`` (1 without elevations).
    phi, qd_m2, r_wn_m2 : ndarray, shape (m,)
        Per-measurement ``Phi_i``, ``Qd_i`` and ``R_i`` (normalised scale).
    dt_s : float
        Filter interval, seconds.
    """

    F: NDArray[np.float64]
    Q: NDArray[np.float64]
    H: NDArray[np.float64]
    R: NDArray[np.float64]
    p0_gm_m2: NDArray[np.float64]
    n_base: int
    scale: NDArray[np.float64]
    phi: NDArray[np.float64]
    qd_m2: NDArray[np.float64]
    r_wn_m2: NDArray[np.float64]
    dt_s: float

    @property
    def gm_slice(self) -> slice:
        """Slice of the multipath states in the augmented state vector."""
        return slice(self.n_base, self.n_base + self.p0_gm_m2.size)

    def initial_covariance(self, p0_base: ArrayLike) -> NDArray[np.float64]:
        """Augmented initial covariance ``blockdiag(p0_base, diag(p0_gm_m2))``.

        Parameters
        ----------
        p0_base : array_like, shape (n, n)
            Initial covariance of the filter's own states.

        Returns
        -------
        ndarray, shape (n + m, n + m)
        """
        n = self.n_base
        p0 = _matrix("p0_base", p0_base, (n, n))
        check_covariance(p0, "p0_base")
        out = np.zeros((n + self.p0_gm_m2.size,) * 2)
        out[:n, :n] = p0
        out[self.gm_slice, self.gm_slice] = np.diag(self.p0_gm_m2)
        return out


def augment_gm_states(
    F: ArrayLike,
    Q: ArrayLike,
    H: ArrayLike,
    R: ArrayLike | None,
    bounds: GaussMarkovBound | Sequence[GaussMarkovBound],
    dt_s: float,
    *,
    elevation_deg: ArrayLike | None = None,
    white_noise: str = "conservative",
) -> AugmentedModel:
    """Append one Gauss-Markov multipath state per measurement to a filter model.

    Parameters
    ----------
    F : array_like, shape (n, n)
        The filter's transition matrix over ``dt_s``.
    Q : array_like, shape (n, n)
        Its process-noise covariance over ``dt_s``.
    H : array_like, shape (m, n)
        Its measurement matrix (one row per satellite / signal).
    R : array_like, shape (m, m), or None
        Its other measurement noise (not multipath), m^2; ``None`` for none.
    bounds : GaussMarkovBound or sequence of GaussMarkovBound
        The multipath bound, one for all measurements or one per measurement.
    dt_s : float
        Filter interval, seconds.
    elevation_deg : array_like, shape (m,), optional
        Current elevations, degrees; the bounds' mappings give ``m(el_i)``.
        Every bound must then have a mapping.
    white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
        How the bound's white noise becomes a per-sample variance when
        ``dt_s`` differs from the data interval (see
        :mod:`psdbound.spectra.models`).

    Returns
    -------
    AugmentedModel

    Raises
    ------
    InputError
        For inconsistent shapes, non-finite entries, a wrong number of bounds
        or elevations, or an elevation for a bound without mapping.
    """
    Hm = np.asarray(H, dtype=float)
    if Hm.ndim != 2:
        raise InputError(f"H must be a 2-D (m, n) matrix, got shape {Hm.shape}")
    m, n = Hm.shape
    if m == 0:
        raise InputError("H has no rows (no measurements to augment)")
    Hm = _matrix("H", Hm, (m, n))
    Fm = _matrix("F", F, (n, n))
    Qm = _matrix("Q", Q, (n, n))
    Rm = np.zeros((m, m)) if R is None else _matrix("R", R, (m, m))
    check_covariance(Qm, "Q")
    check_covariance(Rm, "R")
    bl = broadcast_bounds(bounds, m)
    if elevation_deg is None:
        scale = np.ones(m)
    else:
        el = np.asarray(elevation_deg, dtype=float).reshape(-1)
        if el.size != m:
            raise InputError(f"need one elevation per measurement: got {el.size} for {m}")
        scale = np.empty(m)
        for i, (b, e) in enumerate(zip(bl, el, strict=True)):
            if b.mapping is None:
                raise InputError(
                    f"elevation given for measurement {i} but its bound has no elevation mapping"
                )
            scale[i] = float(b.mapping_factor(e))
    ss = [b.to_state_space(dt_s, white_noise=white_noise) for b in bl]
    phi = np.array([s.phi for s in ss], dtype=float)
    qd = np.array([s.qd_m2 for s in ss], dtype=float)
    r_wn = np.array([s.r_m2 for s in ss], dtype=float)
    N = n + m
    Fa = np.zeros((N, N))
    Fa[:n, :n] = Fm
    Fa[n:, n:] = np.diag(phi)
    Qa = np.zeros((N, N))
    Qa[:n, :n] = Qm
    Qa[n:, n:] = np.diag(qd)
    Ha = np.hstack([Hm, np.diag(scale)])
    Ra = Rm + np.diag(scale**2 * r_wn)
    p0 = np.array([b.sigma_gm_m**2 for b in bl])
    return AugmentedModel(
        F=Fa,
        Q=Qa,
        H=Ha,
        R=Ra,
        p0_gm_m2=p0,
        n_base=n,
        scale=scale,
        phi=phi,
        qd_m2=qd,
        r_wn_m2=r_wn,
        dt_s=float(dt_s),
    )
