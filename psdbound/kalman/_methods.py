"""Engine of :func:`psdbound.kalman.analyze_covariance`: filter pass and the three truth methods.

The equations are in the docstring of :mod:`psdbound.kalman.covariance`.
Everything here works on the error ``s = [e_b; g_hat]`` (error of the
filter's own states, estimated multipath states) whose update under the
design gains is ``s+ = M_k s- + N_k (mp_k + v_k)``:

* :func:`filter_pass` -- the design-model Kalman covariance and gains;
* :class:`ErrorRecursion` -- ``blockdiag(F, Phi)``, the process noise and
  the ``(M_k, N_k)`` of every step (and of the steady-state gain);
* :func:`state_space_covariance`, :func:`psd_covariance`,
  :func:`monte_carlo_covariance` -- the true covariance for an
  :class:`~psdbound.kalman.process.ErrorProcess` truth (joint state
  propagation), a PSD truth (Toeplitz quadratic form / frequency integral)
  and sample paths (Monte Carlo).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import linalg
from scipy.integrate import trapezoid

from psdbound.errors import InputError
from psdbound.kalman.augment import AugmentedModel
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.process import ErrorProcess
from psdbound.kalman.truth import ErrorSequences, SampledPSD

__all__ = [
    "ErrorRecursion",
    "error_matrices",
    "filter_pass",
    "measurement_sequences",
    "monte_carlo_covariance",
    "psd_covariance",
    "psd_grid",
    "psd_ratios",
    "state_space_covariance",
    "steady_state_filter",
]

Matrix = NDArray[np.float64]


def measurement_sequences(
    H: ArrayLike, R: ArrayLike | None, n_steps: int
) -> tuple[list[Matrix], list[Matrix], bool]:
    """Per-step ``H`` and other-noise ``R`` lists, and whether both are constant.

    Parameters
    ----------
    H : array_like, shape (m, n) or (n_steps, m, n)
        Measurement matrix, constant or per step.
    R : array_like, shape (m, m) or (n_steps, m, m), or None
        Other measurement noise, m^2 (None: zero).
    n_steps : int
        Steps analysed.

    Returns
    -------
    h_list, r_list : list of ndarray
        One matrix per step.
    time_invariant : bool
        True when ``H`` and ``R`` were given as single matrices.
    """
    Hm = np.asarray(H, dtype=float)
    if Hm.ndim == 3:
        if Hm.shape[0] < n_steps:
            raise InputError(f"H has {Hm.shape[0]} steps, the analysis needs {n_steps}")
        h_list = [Hm[k] for k in range(n_steps)]
    elif Hm.ndim == 2:
        h_list = [Hm] * n_steps
    else:
        raise InputError(f"H must have shape (m, n) or (n_steps, m, n), got {Hm.shape}")
    m, _ = h_list[0].shape
    if R is None:
        r_list = [np.zeros((m, m))] * n_steps
    else:
        Rm = np.asarray(R, dtype=float)
        if Rm.ndim == 3:
            if Rm.shape[0] < n_steps or Rm.shape[1:] != (m, m):
                raise InputError(f"R must have shape ({n_steps}, {m}, {m}), got {Rm.shape}")
            r_list = [Rm[k] for k in range(n_steps)]
        elif Rm.shape == (m, m):
            r_list = [Rm] * n_steps
        else:
            raise InputError(f"R must have shape ({m}, {m}) or (n_steps, {m}, {m}), got {Rm.shape}")
    time_invariant = Hm.ndim == 2 and (R is None or np.asarray(R).ndim == 2)
    return h_list, r_list, time_invariant


def filter_pass(
    aug: AugmentedModel,
    h_seq: list[Matrix],
    r_seq: list[Matrix],
    p0: Matrix,
) -> tuple[Matrix, list[Matrix]]:
    """Design-model Kalman covariance recursion (Joseph form): P+ of base states, gains."""
    n = aug.n_base
    N = aug.F.shape[0]
    eye = np.eye(N)
    p = p0.copy()
    p_base = np.empty((len(h_seq), n, n))
    gains = []
    for k, (h, r) in enumerate(zip(h_seq, r_seq, strict=True)):
        if k > 0:
            p = aug.F @ p @ aug.F.T + aug.Q
        s = h @ p @ h.T + r
        kg = np.linalg.solve(s, h @ p).T
        a = eye - kg @ h
        p = a @ p @ a.T + kg @ r @ kg.T
        p = 0.5 * (p + p.T)
        p_base[k] = p[:n, :n]
        gains.append(kg)
    return p_base, gains


def error_matrices(
    kg: Matrix, h: Matrix, scale: NDArray[np.float64], n: int
) -> tuple[Matrix, Matrix]:
    """Update matrices ``(M, N)`` of the error ``s`` for the gain ``kg``."""
    kb, kgm = kg[:n], kg[n:]
    m = scale.size
    d = np.diag(scale)
    mm = np.block([[np.eye(n) - kb @ h, kb @ d], [kgm @ h, np.eye(m) - kgm @ d]])
    nn = np.vstack([-kb, kgm])
    return mm, nn


def steady_state_filter(
    aug: AugmentedModel, ha: Matrix, ra: Matrix, h: Matrix, notes: list[str]
) -> tuple[Matrix, tuple[Matrix, Matrix]] | None:
    """Steady-state filter covariance of the base states and its ``(M, N)``.

    Returns None (and appends the reason to ``notes``) when the Riccati
    equation has no stabilising solution.
    """
    try:
        with warnings.catch_warnings():
            # newer scipy perturbs a singular problem and warns instead of raising;
            # the stability test below decides whether the answer is a steady state
            warnings.simplefilter("ignore", RuntimeWarning)
            pm = linalg.solve_discrete_are(aug.F.T, ha.T, aug.Q, ra)
    except (ValueError, np.linalg.LinAlgError) as exc:
        notes.append(f"no steady state: the Riccati equation has no stabilising solution ({exc})")
        return None
    n = aug.n_base
    kss = linalg.solve(ha @ pm @ ha.T + ra, ha @ pm, assume_a="pos").T
    a = np.eye(aug.F.shape[0]) - kss @ ha
    radius = float(np.max(np.abs(np.linalg.eigvals(a @ aug.F))))
    if not (np.all(np.isfinite(pm)) and radius < 1.0 - 1e-9):
        notes.append(
            "no steady state: the Riccati equation has no stabilising solution (closed-loop "
            f"spectral radius {radius:.6g} >= 1)"
        )
        return None
    pp = a @ pm @ a.T + kss @ ra @ kss.T
    pf_ss = 0.5 * (pp + pp.T)[:n, :n]
    return pf_ss, error_matrices(kss, h, aug.scale, n)


@dataclass(frozen=True)
class ErrorRecursion:
    """The exact recursion of ``s = [e_b; g_hat]`` under the design gains.

    Attributes
    ----------
    n, m : int
        Base states and measurements.
    fs, qs : ndarray, shape (n + m, n + m)
        ``blockdiag(F, diag(Phi))`` and ``blockdiag(Q, 0)``.
    mats : list of (ndarray, ndarray)
        ``(M_k, N_k)`` per step.
    r_other : list of ndarray
        Other (non-multipath) measurement noise per step, m^2.
    p0_base : ndarray, shape (n, n)
        Initial covariance of the base states.
    steady : (ndarray, ndarray) or None
        ``(M, N)`` of the steady-state gain, when a steady state is wanted.
    """

    n: int
    m: int
    fs: Matrix
    qs: Matrix
    mats: list[tuple[Matrix, Matrix]]
    r_other: list[Matrix]
    p0_base: Matrix
    steady: tuple[Matrix, Matrix] | None

    @property
    def ns(self) -> int:
        """Dimension of ``s``."""
        return self.n + self.m

    def other_part(self) -> NDArray[np.float64]:
        """Covariance of s from the initial error, process noise and other noise (no multipath)."""
        n, ns = self.n, self.fs.shape[0]
        z = np.zeros((ns, ns))
        z[:n, :n] = self.p0_base
        out = np.empty((len(self.mats), ns, ns))
        for k, ((mm, nn), rb) in enumerate(zip(self.mats, self.r_other, strict=True)):
            if k > 0:
                z = self.fs @ z @ self.fs.T + self.qs
            z = mm @ z @ mm.T + nn @ rb @ nn.T
            z = 0.5 * (z + z.T)
            out[k] = z
        return out


def psd_grid(nyq: float, extra: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    """Frequency grid on ``[0, nyq]``: linear and logarithmic parts plus ``extra`` knots, Hz."""
    parts = [np.linspace(0.0, nyq, 4097), np.geomspace(nyq * 1e-7, nyq, 4097)]
    parts += [e[(e >= 0) & (e <= nyq)] for e in extra]
    return np.unique(np.concatenate(parts))


def psd_ratios(
    bounds: Sequence[GaussMarkovBound],
    truths: Sequence[ErrorProcess | SampledPSD],
    scale: NDArray[np.float64],
    dt_s: float,
    white_noise: str,
) -> NDArray[np.float64]:
    """Per measurement, the minimum over frequency of bound PSD / true PSD."""
    nyq = 0.5 / float(dt_s)
    ratios = []
    for i, (b, t) in enumerate(zip(bounds, truths, strict=True)):
        extra = [t.f_hz] if isinstance(t, SampledPSD) else []
        grid = psd_grid(nyq, extra)
        sb = b.sampled_psd(grid, dt_s, white_noise=white_noise) * scale[i] ** 2
        st = t.psd(grid)
        with np.errstate(divide="ignore"):
            ratios.append(float(np.min(np.where(st > 0, sb / st, np.inf))))
    return np.array(ratios)


def monte_carlo_covariance(
    rec: ErrorRecursion, truth: ErrorSequences, n_steps: int
) -> tuple[NDArray[np.float64], int]:
    """True covariance from sample paths: ``(p_true, n_paths)``."""
    n, m = rec.n, rec.m
    other = rec.other_part()
    paths = truth.paths(m, n_steps)  # (P, n_steps, m)
    n_paths = paths.shape[0]
    s = np.zeros((n_paths, rec.ns))
    p_true = np.empty((n_steps, n, n))
    for k, (mm, nn) in enumerate(rec.mats):
        if k > 0:
            s = s @ rec.fs.T
        s = s @ mm.T + paths[:, k, :] @ nn.T
        eb = s[:, :n]
        p_true[k] = other[k][:n, :n] + eb.T @ eb / n_paths
    return p_true, n_paths


def state_space_covariance(
    rec: ErrorRecursion, procs: Sequence[ErrorProcess], n_steps: int
) -> tuple[NDArray[np.float64], Matrix | None]:
    """True covariance with the true processes' states appended: ``(p_true, p_true_ss)``."""
    n, m, ns = rec.n, rec.m, rec.ns
    a_t = linalg.block_diag(*[t.a for t in procs])
    q_t = linalg.block_diag(*[t.q_m2 for t in procs])
    c_t = linalg.block_diag(*[t.c[None, :] for t in procs])  # (m, P)
    r_t = np.diag([t.r_m2 for t in procs])
    x0 = linalg.block_diag(*[t.stationary_covariance() for t in procs])
    pdim = a_t.shape[0]
    fz = linalg.block_diag(rec.fs, a_t)
    qz = linalg.block_diag(rec.qs, q_t)

    def joint(mm: Matrix, nn: Matrix) -> tuple[Matrix, Matrix]:
        mz = np.block([[mm, nn @ c_t], [np.zeros((pdim, ns)), np.eye(pdim)]])
        nz = np.vstack([nn, np.zeros((pdim, m))])
        return mz, nz

    z = linalg.block_diag(rec.p0_base, np.zeros((m, m)), x0)
    p_true = np.empty((n_steps, n, n))
    for k, ((mm, nn), rb) in enumerate(zip(rec.mats, rec.r_other, strict=True)):
        if k > 0:
            z = fz @ z @ fz.T + qz
        mz, nz = joint(mm, nn)
        z = mz @ z @ mz.T + nz @ (rb + r_t) @ nz.T
        z = 0.5 * (z + z.T)
        p_true[k] = z[:n, :n]
    pt_ss = None
    if rec.steady is not None:
        mz, nz = joint(*rec.steady)
        acl = mz @ fz
        zz = linalg.solve_discrete_lyapunov(
            acl, mz @ qz @ mz.T + nz @ (rec.r_other[0] + r_t) @ nz.T
        )
        pt_ss = 0.5 * (zz + zz.T)[:n, :n]
    return p_true, pt_ss


def psd_covariance(
    rec: ErrorRecursion, items: Sequence[ErrorProcess | SampledPSD], n_steps: int, dt_s: float
) -> tuple[NDArray[np.float64], Matrix | None]:
    """True covariance from the truths' autocovariances and PSDs: ``(p_true, p_true_ss)``."""
    n, m, ns, fs = rec.n, rec.m, rec.ns, rec.fs
    acfs = np.column_stack([t.acf(n_steps) for t in items])  # (n_steps, m)
    other = rec.other_part()
    psi = np.zeros((n_steps, ns, m))
    v = np.zeros((ns, ns))
    p_true = np.empty((n_steps, n, n))
    r0 = np.diag(acfs[0])
    for k, (mm, nn) in enumerate(rec.mats):
        if k == 0:
            v = nn @ r0 @ nn.T
            psi[0] = nn
        else:
            ak = mm @ fs
            # X = sum_j psi_j diag(r(k - j)), j = 0 .. k-1
            x = np.einsum("jsm,jm->sm", psi[:k], acfs[k:0:-1])
            v = ak @ v @ ak.T + ak @ x @ nn.T + nn @ x.T @ ak.T + nn @ r0 @ nn.T
            psi[:k] = np.einsum("ab,jbm->jam", ak, psi[:k])
            psi[k] = nn
        v = 0.5 * (v + v.T)
        p_true[k] = other[k][:n, :n] + v[:n, :n]
    if rec.steady is None:
        return p_true, None
    mm_ss, nn_ss = rec.steady
    acl = mm_ss @ fs
    vo = linalg.solve_discrete_lyapunov(
        acl, mm_ss @ rec.qs @ mm_ss.T + nn_ss @ rec.r_other[0] @ nn_ss.T
    )
    nyq = 0.5 / float(dt_s)
    grid = psd_grid(nyq, [t.f_hz for t in items if isinstance(t, SampledPSD)])
    zf = np.exp(-2j * np.pi * grid * float(dt_s))
    lhs = np.eye(ns)[None] - zf[:, None, None] * acl[None]
    g = np.linalg.solve(lhs, np.broadcast_to(nn_ss, (grid.size, ns, m)))[:, :n, :]
    sp = np.column_stack([t.psd(grid) for t in items])  # (nf, m)
    integrand = np.einsum("fim,fm,fjm->fij", g, sp, g.conj()).real
    vm = trapezoid(integrand, grid, axis=0)
    pt_ss = 0.5 * ((vo[:n, :n] + vm) + (vo[:n, :n] + vm).T)
    return p_true, pt_ss
