"""True error processes in discrete state-space form, for the covariance analysis.

An :class:`ErrorProcess` is a stationary zero-mean error sequence
``xi[k+1] = A xi[k] + w[k]``, ``e[k] = c . xi[k] + u[k]`` at an interval
``dt_s``: exact second-order statistics (stationary covariance,
autocovariance, PSD), constructors for the usual multipath models (first- and
second-order Gauss-Markov, white noise, the bound itself) and the exact
discretisation of a continuous model by Van Loan's method
(:meth:`ErrorProcess.from_continuous`). Independent processes add
(:meth:`ErrorProcess.__add__`) by stacking their states.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import linalg

from psdbound.errors import InputError
from psdbound.kalman.bound import GaussMarkovBound

__all__ = ["ErrorProcess", "check_covariance"]


@dataclass(frozen=True)
class ErrorProcess:
    """A stationary error sequence in discrete state-space form.

    ``xi[k+1] = A xi[k] + w[k]``, ``w ~ N(0, Q)``; error
    ``e[k] = c . xi[k] + u[k]``, ``u ~ N(0, r)`` (white), metres, at interval
    ``dt_s``. ``A`` must be stable (spectral radius < 1); the process starts
    in its stationary distribution.

    Parameters
    ----------
    a : array_like, shape (p, p)
        Transition matrix over ``dt_s``.
    q_m2 : array_like, shape (p, p)
        Process-noise covariance, m^2 (symmetric, positive semi-definite).
    c : array_like, shape (p,)
        Output vector.
    r_m2 : float
        White output-noise variance, m^2.
    dt_s : float
        Sampling interval, seconds.
    label : str
        Free text for summaries.
    """

    a: NDArray[np.float64]
    q_m2: NDArray[np.float64]
    c: NDArray[np.float64]
    r_m2: float
    dt_s: float
    label: str = ""

    def __post_init__(self) -> None:
        a, q, c = _checked_matrices(self.a, self.q_m2, self.c)
        check_covariance(q)
        rho = float(np.abs(np.linalg.eigvals(a)).max())
        if rho >= 1.0:
            raise InputError(
                f"ErrorProcess: a has spectral radius {rho:.6g} >= 1 (not a stationary process)"
            )
        r = float(self.r_m2)
        if not (math.isfinite(r) and r >= 0):
            raise InputError(f"ErrorProcess: r_m2 must be >= 0, got {self.r_m2!r}")
        dt = float(self.dt_s)
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"ErrorProcess: dt_s must be > 0 s, got {self.dt_s!r}")
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "q_m2", 0.5 * (q + q.T))
        object.__setattr__(self, "c", c)
        object.__setattr__(self, "r_m2", r)
        object.__setattr__(self, "dt_s", dt)

    # ---- constructors
    @classmethod
    def gauss_markov(cls, sigma_m: float, tau_s: float, dt_s: float) -> ErrorProcess:
        """First-order Gauss-Markov process ``sigma^2 exp(-|t|/tau)`` sampled at ``dt_s``.

        Parameters
        ----------
        sigma_m : float
            Standard deviation, metres.
        tau_s : float
            Time constant, seconds.
        dt_s : float
            Sampling interval, seconds.

        Returns
        -------
        ErrorProcess
        """
        if not (sigma_m >= 0 and tau_s > 0):
            raise InputError(f"need sigma_m >= 0 and tau_s > 0, got {sigma_m}, {tau_s}")
        phi = math.exp(-dt_s / tau_s)
        return cls(
            [[phi]],
            [[sigma_m**2 * -math.expm1(-2.0 * dt_s / tau_s)]],
            [1.0],
            0.0,
            dt_s,
            f"GM {sigma_m:g} m {tau_s:g} s",
        )

    @classmethod
    def white(cls, sigma_m: float, dt_s: float) -> ErrorProcess:
        """White sequence of per-sample standard deviation ``sigma_m`` at ``dt_s``.

        Parameters
        ----------
        sigma_m : float
            Standard deviation per sample, metres.
        dt_s : float
            Sampling interval, seconds.

        Returns
        -------
        ErrorProcess
        """
        if not sigma_m >= 0:
            raise InputError(f"need sigma_m >= 0, got {sigma_m}")
        return cls([[0.0]], [[0.0]], [0.0], sigma_m**2, dt_s, f"white {sigma_m:g} m")

    @classmethod
    def from_continuous(
        cls,
        a_c: ArrayLike,
        q_c: ArrayLike,
        c: ArrayLike,
        dt_s: float,
        *,
        r_m2: float = 0.0,
        label: str = "",
    ) -> ErrorProcess:
        """Exact discretisation of ``dxi = A_c xi dt + dW`` (``E[dW dW^T] = Q_c dt``).

        ``A = expm(A_c dt)`` and ``Q = int_0^dt expm(A_c s) Q_c expm(A_c s)^T ds``
        (Van Loan's method).

        Parameters
        ----------
        a_c : array_like, shape (p, p)
            Continuous dynamics matrix, 1/s (stable).
        q_c : array_like, shape (p, p)
            Continuous white-noise spectral density matrix, m^2/s.
        c : array_like, shape (p,)
            Output vector.
        dt_s : float
            Sampling interval, seconds.
        r_m2 : float, default 0
            White output-noise variance per sample, m^2.
        label : str
            Free text.

        Returns
        -------
        ErrorProcess
        """
        ac = np.atleast_2d(np.asarray(a_c, dtype=float))
        qc = np.atleast_2d(np.asarray(q_c, dtype=float))
        p = ac.shape[0]
        if ac.shape != (p, p) or qc.shape != (p, p):
            raise InputError("from_continuous: a_c and q_c must be square and of equal size")
        big = np.zeros((2 * p, 2 * p))
        big[:p, :p] = -ac
        big[:p, p:] = qc
        big[p:, p:] = ac.T
        e = linalg.expm(big * dt_s)
        a = e[p:, p:].T
        q = a @ e[:p, p:]
        return cls(a, 0.5 * (q + q.T), c, r_m2, dt_s, label)

    @classmethod
    def second_order(
        cls, sigma_m: float, omega0_rad_s: float, dt_s: float, *, damping: float = 1.0
    ) -> ErrorProcess:
        """Second-order Gauss-Markov process ``x'' + 2 z w0 x' + w0^2 x = white``.

        Scaled to stationary variance ``sigma_m^2`` (spectral density
        ``4 z w0^3 sigma^2``); continuous one-sided PSD
        ``8 z w0^3 sigma^2 / ((w0^2 - w^2)^2 + (2 z w0 w)^2)``, ``w = 2 pi f``,
        falling as ``f^-4``. Damping 1 is the critically damped case; small
        damping gives a resonance near ``w0``.

        Parameters
        ----------
        sigma_m : float
            Standard deviation, metres.
        omega0_rad_s : float
            Natural angular frequency, rad/s.
        dt_s : float
            Sampling interval, seconds.
        damping : float, default 1
            Damping ratio ``z`` (> 0).

        Returns
        -------
        ErrorProcess
        """
        if not (sigma_m >= 0 and omega0_rad_s > 0 and damping > 0):
            raise InputError("second_order needs sigma_m >= 0, omega0_rad_s > 0, damping > 0")
        w, z = float(omega0_rad_s), float(damping)
        ac = np.array([[0.0, 1.0], [-w * w, -2.0 * z * w]])
        qc = np.array([[0.0, 0.0], [0.0, 4.0 * z * w**3 * sigma_m**2]])
        return cls.from_continuous(
            ac, qc, [1.0, 0.0], dt_s, label=f"2nd-order {sigma_m:g} m w0={w:g} z={z:g}"
        )

    @classmethod
    def from_bound(
        cls,
        bound: GaussMarkovBound,
        dt_s: float | None = None,
        *,
        elevation_deg: float | None = None,
        white_noise: str = "conservative",
    ) -> ErrorProcess:
        """Build the bound itself as a process (``Phi, Qd, R`` of its state-space export).

        Parameters
        ----------
        bound : GaussMarkovBound
            The bound.
        dt_s : float, optional
            Interval, seconds; default the bound's data interval.
        elevation_deg : float, optional
            Elevation, degrees: scale by ``m(el)`` (needs a mapping).
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            See :meth:`GaussMarkovBound.white_variance_m2`.

        Returns
        -------
        ErrorProcess
        """
        dt = bound.dt_s if dt_s is None else dt_s
        phi, qd, r = bound.to_state_space(dt, elevation_deg=elevation_deg, white_noise=white_noise)
        return cls([[phi]], [[qd]], [1.0], r, dt, f"bound {bound}")

    # ---- algebra
    def __add__(self, other: ErrorProcess) -> ErrorProcess:
        """Sum of two independent processes (block-diagonal states)."""
        if not isinstance(other, ErrorProcess):
            return NotImplemented
        if not math.isclose(self.dt_s, other.dt_s, rel_tol=1e-12):
            raise InputError(
                f"cannot add processes sampled at {self.dt_s:g} s and {other.dt_s:g} s"
            )
        return ErrorProcess(
            linalg.block_diag(self.a, other.a),
            linalg.block_diag(self.q_m2, other.q_m2),
            np.concatenate([self.c, other.c]),
            self.r_m2 + other.r_m2,
            self.dt_s,
            f"{self.label} + {other.label}",
        )

    def scaled(self, factor: float) -> ErrorProcess:
        """Return the process multiplied by ``factor`` (PSD by ``factor^2``).

        Parameters
        ----------
        factor : float
            Scale factor.

        Returns
        -------
        ErrorProcess
        """
        f = float(factor)
        return ErrorProcess(
            self.a, self.q_m2, self.c * f, self.r_m2 * f * f, self.dt_s, f"{f:g} x ({self.label})"
        )

    # ---- second-order statistics
    @property
    def n_states(self) -> int:
        """Number of states ``p``."""
        return self.a.shape[0]

    def stationary_covariance(self) -> NDArray[np.float64]:
        """Stationary state covariance ``X = A X A^T + Q``, m^2."""
        x = linalg.solve_discrete_lyapunov(self.a, self.q_m2)
        return 0.5 * (x + x.T)

    @property
    def variance_m2(self) -> float:
        """Stationary variance of the error, m^2."""
        return float(self.c @ self.stationary_covariance() @ self.c + self.r_m2)

    def acf(self, n_lags: int) -> NDArray[np.float64]:
        """Autocovariance at lags ``0 .. n_lags - 1`` samples, m^2.

        ``r(k) = c A^k X c^T + r delta_k`` with ``X`` the stationary covariance.

        Parameters
        ----------
        n_lags : int
            Number of lags.

        Returns
        -------
        ndarray, shape (n_lags,)
        """
        x = self.stationary_covariance()
        out = np.empty(int(n_lags))
        v = x @ self.c
        for k in range(out.size):
            out[k] = self.c @ v
            v = self.a @ v
        if out.size:
            out[0] += self.r_m2
        return out

    def psd(self, f_hz: ArrayLike) -> NDArray[np.float64]:
        """One-sided PSD of the sampled error on ``[0, 1/(2 dt)]``, m^2/Hz.

        ``2 dt (g Q g^H + r)``, ``g = c (z I - A)^-1``, ``z = exp(i 2 pi f dt)``.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz.

        Returns
        -------
        ndarray
        """
        f = np.asarray(f_hz, dtype=float)
        z = np.exp(2j * np.pi * f.reshape(-1) * self.dt_s)
        p = self.n_states
        m = z[:, None, None] * np.eye(p)[None] - self.a[None]
        g = np.linalg.solve(
            np.transpose(m, (0, 2, 1)), np.broadcast_to(self.c, (z.size, p))[..., None]
        )
        g = g[..., 0]
        val = np.einsum("ki,ij,kj->k", g, self.q_m2, g.conj()).real
        return (2.0 * self.dt_s * (val + self.r_m2)).reshape(f.shape)


def _checked_matrices(
    a_in: ArrayLike, q_in: ArrayLike, c_in: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Return ``a``, ``q_m2`` and ``c`` as float arrays of matching shapes, finite."""
    a = np.atleast_2d(np.asarray(a_in, dtype=float))
    p = a.shape[0]
    if a.shape != (p, p) or p == 0:
        raise InputError(f"ErrorProcess: a must be square, got shape {a.shape}")
    q = np.atleast_2d(np.asarray(q_in, dtype=float))
    c = np.atleast_1d(np.asarray(c_in, dtype=float)).reshape(-1)
    if q.shape != (p, p):
        raise InputError(f"ErrorProcess: q_m2 must have shape {(p, p)}, got {q.shape}")
    if c.shape != (p,):
        raise InputError(f"ErrorProcess: c must have {p} entries, got {c.size}")
    for name, arr in (("a", a), ("q_m2", q), ("c", c)):
        if not np.isfinite(arr).all():
            raise InputError(f"ErrorProcess: {name} has non-finite entries")
    return a, q, c


def check_covariance(q: NDArray[np.float64], name: str = "ErrorProcess: q_m2") -> None:
    """Raise :class:`InputError` unless a covariance matrix is symmetric and positive semi-definite.

    Parameters
    ----------
    q : ndarray, shape (n, n)
        The matrix (finite entries), in its own unit squared.
    name : str
        How to name it in the message.

    Raises
    ------
    InputError
        Not symmetric (relative tolerance 1e-10), or an eigenvalue below
        ``-1e-12`` times its largest entry.
    """
    if not np.allclose(q, q.T, rtol=1e-10, atol=1e-14 * max(1.0, np.abs(q).max())):
        raise InputError(f"{name} must be symmetric")
    if q.size and np.linalg.eigvalsh(q).min() < -1e-12 * max(1e-300, np.abs(q).max()):
        raise InputError(f"{name} must be positive semi-definite (a covariance)")
