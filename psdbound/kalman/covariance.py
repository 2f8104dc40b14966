"""Covariance analysis: check that a filter designed with the bound over-estimates its error.

Set-up (method.md section 6; the "sub-optimal filter" analysis of the
airport-surface seed, appendix). The filter's own model ``(F, Q, H, R)``
(kinematics, clocks, non-multipath noise) is right; multipath is modelled in
the filter by the bound (one Gauss-Markov state per measurement, see
:func:`psdbound.kalman.augment_gm_states`); the **true** multipath is another
stationary zero-mean process, independent across measurements, given as

* an :class:`ErrorProcess` (discrete state-space model, exact),
* a :class:`SampledPSD` (one-sided PSD samples of the sampled error), or
* :class:`ErrorSequences` (sample paths, e.g. measured multipath: Monte Carlo).

The Kalman gains ``K_k`` come from the filter's design model. With
``s = [e_b; g_hat]`` (error of the filter's own states, estimated multipath
states) the true error obeys, exactly::

    predict:  s- = blockdiag(F, Phi) s+ + [w; 0]
    update:   s+ = M_k s- + N_k (mp_k + v_k),
              M_k = [[I - K_b H, K_b D], [K_g H, I - K_g D]],  N_k = [-K_b; K_g]

(``K = [K_b; K_g]``, ``D = diag(m(el_i))``, ``mp`` the true multipath, ``v``
the other measurement noise). Its covariance is computed:

* for an :class:`ErrorProcess`: by appending the true process's states to
  ``s`` and propagating the joint covariance (time-varying recursion) and, in
  steady state, with the steady-state gain from
  :func:`scipy.linalg.solve_discrete_are` and a discrete Lyapunov equation
  (:func:`scipy.linalg.solve_discrete_lyapunov`);
* for a :class:`SampledPSD`: the autocovariance ``r(k)`` is the exact cosine
  transform of the piecewise-linear PSD; the step-by-step covariance is the
  exact quadratic form of the filter's impulse response with the Toeplitz
  covariance of ``mp`` (an ``O(n_steps^2)`` recursion, no realisation
  fitted); the steady state is the frequency-domain integral
  ``int_0^fN Re[G(f) S(f) G(f)^H] df`` of the steady-state filter's transfer
  function ``G`` from multipath to ``e_b``;
* for :class:`ErrorSequences`: by running the error recursion on every
  path and averaging ``e e^T`` (Monte Carlo; the terms from process noise,
  other noise and the initial error are added exactly). No steady state.

Why the check can pass: the filter is linear in the measurements, so
``P_true - P_filter`` is the filter's response to the difference between the
true and the bound autocovariance. If the true sampled PSD is under the
bound's at every frequency, that difference has a non-negative spectrum,
its Toeplitz covariance matrices are positive semi-definite, and
``P_true <= P_filter`` in the matrix (Loewner) order at **every** step and in
steady state -- for every linear combination of the states, not only the
diagonal. :attr:`CovarianceAnalysis.max_eig_ratio` is the largest
generalised eigenvalue of ``(P_true, P_filter)`` over all steps, i.e. the
worst ratio of true to filter variance over all combinations; a value above
1 is a violation. (The PSD condition is sufficient, not necessary: a truth
exceeding the bound only where the filter does not listen can still pass.)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import linalg
from scipy.integrate import trapezoid

from psdbound.errors import InputError
from psdbound.kalman.augment import AugmentedModel, augment_gm_states, broadcast_bounds
from psdbound.kalman.bound import GaussMarkovBound

__all__ = [
    "CovarianceAnalysis",
    "ErrorProcess",
    "ErrorSequences",
    "SampledPSD",
    "analyze_covariance",
]


# --------------------------------------------------------------------------- truths
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
        a = np.atleast_2d(np.asarray(self.a, dtype=float))
        p = a.shape[0]
        if a.shape != (p, p) or p == 0:
            raise InputError(f"ErrorProcess: a must be square, got shape {a.shape}")
        q = np.atleast_2d(np.asarray(self.q_m2, dtype=float))
        c = np.atleast_1d(np.asarray(self.c, dtype=float)).reshape(-1)
        if q.shape != (p, p):
            raise InputError(f"ErrorProcess: q_m2 must have shape {(p, p)}, got {q.shape}")
        if c.shape != (p,):
            raise InputError(f"ErrorProcess: c must have {p} entries, got {c.size}")
        for name, arr in (("a", a), ("q_m2", q), ("c", c)):
            if not np.isfinite(arr).all():
                raise InputError(f"ErrorProcess: {name} has non-finite entries")
        if not np.allclose(q, q.T, rtol=1e-10, atol=1e-14 * max(1.0, np.abs(q).max())):
            raise InputError("ErrorProcess: q_m2 must be symmetric")
        if np.linalg.eigvalsh(q).min() < -1e-12 * max(1e-300, np.abs(q).max()):
            raise InputError("ErrorProcess: q_m2 must be positive semi-definite")
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


@dataclass(frozen=True)
class SampledPSD:
    """A true error given as one-sided PSD samples of the sequence at the filter interval.

    The PSD (m^2/Hz, one-sided, aliases already folded in, on
    ``[0, 1/(2 dt)]``) is linearly interpolated between the samples and held
    constant from the first sample down to 0 Hz and from the last up to the
    Nyquist frequency.

    Parameters
    ----------
    f_hz : array_like
        Strictly increasing frequencies in ``[0, 1/(2 dt_s)]``, Hz.
    psd_m2_hz : array_like
        PSD values (>= 0), m^2/Hz.
    dt_s : float
        Sampling interval of the sequence (the filter interval), seconds.
    label : str
        Free text.
    """

    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    dt_s: float
    label: str = "PSD samples"

    def __post_init__(self) -> None:
        f = np.asarray(self.f_hz, dtype=float).reshape(-1)
        s = np.asarray(self.psd_m2_hz, dtype=float).reshape(-1)
        dt = float(self.dt_s)
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"SampledPSD: dt_s must be > 0 s, got {self.dt_s!r}")
        if f.size == 0 or f.shape != s.shape:
            raise InputError("SampledPSD: f_hz and psd_m2_hz must be non-empty and of equal size")
        if not (np.isfinite(f).all() and np.isfinite(s).all()):
            raise InputError("SampledPSD: non-finite frequencies or PSD values")
        if (s < 0).any():
            raise InputError("SampledPSD: PSD values must be >= 0")
        if (np.diff(f) <= 0).any():
            raise InputError("SampledPSD: frequencies must be strictly increasing")
        nyq = 0.5 / dt
        if f[0] < 0 or f[-1] > nyq * (1 + 1e-9):
            raise InputError(
                f"SampledPSD: frequencies must lie in [0, {nyq:g}] Hz (Nyquist of dt = {dt:g} s); "
                f"got {f[0]:g} .. {f[-1]:g} Hz. Fold a continuous PSD first."
            )
        object.__setattr__(self, "f_hz", f)
        object.__setattr__(self, "psd_m2_hz", s)
        object.__setattr__(self, "dt_s", dt)

    @classmethod
    def from_process(
        cls,
        process: ErrorProcess | GaussMarkovBound,
        f_hz: ArrayLike,
        *,
        dt_s: float | None = None,
        white_noise: str = "conservative",
    ) -> SampledPSD:
        """Sample the PSD of a process or a bound on a frequency grid.

        Parameters
        ----------
        process : ErrorProcess or GaussMarkovBound
            The process.
        f_hz : array_like
            Frequencies, Hz, in ``[0, 1/(2 dt)]``.
        dt_s : float, optional
            Interval for a bound (default its data interval); for a process it
            must be omitted or equal the process's interval.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            For a bound: see :meth:`GaussMarkovBound.white_variance_m2`.

        Returns
        -------
        SampledPSD
        """
        f = np.asarray(f_hz, dtype=float)
        if isinstance(process, GaussMarkovBound):
            dt = process.dt_s if dt_s is None else float(dt_s)
            psd = process.sampled_psd(f, dt, white_noise=white_noise)
            return cls(f, psd, dt, f"PSD of {process}")
        if dt_s is not None and not math.isclose(float(dt_s), process.dt_s, rel_tol=1e-12):
            raise InputError(
                f"dt_s = {dt_s} s differs from the process's interval {process.dt_s} s"
            )
        return cls(f, process.psd(f), process.dt_s, f"PSD of {process.label}")

    def _knots(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        nyq = 0.5 / self.dt_s
        f, s = self.f_hz, self.psd_m2_hz
        if f[0] > 0:
            f, s = np.r_[0.0, f], np.r_[s[0], s]
        if f[-1] < nyq:
            f, s = np.r_[f, nyq], np.r_[s, s[-1]]
        else:
            f = f.copy()
            f[-1] = nyq
        return f, s

    def psd(self, f_hz: ArrayLike) -> NDArray[np.float64]:
        """Interpolated one-sided PSD, m^2/Hz.

        Parameters
        ----------
        f_hz : array_like
            Frequencies, Hz.

        Returns
        -------
        ndarray
        """
        f, s = self._knots()
        return np.interp(np.asarray(f_hz, dtype=float), f, s)

    @property
    def variance_m2(self) -> float:
        """Variance, the integral of the PSD over ``[0, f_N]``, m^2."""
        return float(self.acf(1)[0])

    def acf(self, n_lags: int) -> NDArray[np.float64]:
        """Autocovariance at lags ``0 .. n_lags - 1`` samples, m^2.

        ``r(k) = int_0^fN S(f) cos(2 pi f k dt) df``, integrated exactly for
        the piecewise-linear PSD (no quadrature error).

        Parameters
        ----------
        n_lags : int
            Number of lags.

        Returns
        -------
        ndarray, shape (n_lags,)
        """
        f, s = self._knots()
        h = np.diff(f)
        slope = np.diff(s) / h
        out = np.empty(int(n_lags))
        if out.size == 0:
            return out
        out[0] = float(np.sum(0.5 * (s[1:] + s[:-1]) * h))
        k = np.arange(1, out.size)
        if k.size:
            w = 2.0 * np.pi * k * self.dt_s  # rad per Hz
            # int S cos(w f) = [S sin(w f)/w] + slope * [cos(w f)/w^2] per segment;
            # cos(b) - cos(a) = -2 sin((a+b)/2) sin((b-a)/2) (no cancellation).
            ends = (s[-1] * np.sin(w * f[-1]) - s[0] * np.sin(w * f[0])) / w
            mid = 0.5 * (f[1:] + f[:-1])
            dcos = -2.0 * np.sin(np.outer(w, mid)) * np.sin(np.outer(w, 0.5 * h))
            out[1:] = ends + (dcos @ slope) / w**2
        return out


@dataclass(frozen=True)
class ErrorSequences:
    """A true error given as independent sample paths (Monte Carlo).

    Parameters
    ----------
    samples_m : array_like, shape (n_paths, n_steps) or (n_paths, n_steps, m)
        Error sample paths at the filter interval, metres (raw scale at each
        measurement). A 2-D array is split among the ``m`` measurements:
        measurement ``j`` takes paths ``j, j + m, j + 2m, ...``. Paths should
        be zero-mean and independent across measurements; the second moment
        about zero is what is averaged.
    dt_s : float
        Sampling interval, seconds.
    label : str
        Free text.
    """

    samples_m: NDArray[np.float64]
    dt_s: float
    label: str = "sample paths"

    def __post_init__(self) -> None:
        x = np.asarray(self.samples_m, dtype=float)
        if x.ndim not in (2, 3) or x.shape[0] == 0 or x.shape[1] == 0:
            raise InputError(
                f"ErrorSequences: samples_m must have shape (n_paths, n_steps[, m]), got {x.shape}"
            )
        if not np.isfinite(x).all():
            raise InputError("ErrorSequences: samples_m has non-finite values")
        dt = float(self.dt_s)
        if not (math.isfinite(dt) and dt > 0):
            raise InputError(f"ErrorSequences: dt_s must be > 0 s, got {self.dt_s!r}")
        object.__setattr__(self, "samples_m", x)
        object.__setattr__(self, "dt_s", dt)

    def paths(self, n_measurements: int, n_steps: int) -> NDArray[np.float64]:
        """Return the paths as ``(n_paths, n_steps, m)``, metres.

        Parameters
        ----------
        n_measurements : int
            Number of measurements ``m``.
        n_steps : int
            Steps needed.

        Returns
        -------
        ndarray
        """
        x = self.samples_m
        if x.shape[1] < n_steps:
            raise InputError(
                f"ErrorSequences: paths have {x.shape[1]} steps, the analysis needs {n_steps}"
            )
        if x.ndim == 3:
            if x.shape[2] != n_measurements:
                raise InputError(
                    f"ErrorSequences: {x.shape[2]} measurements in the paths, the filter has "
                    f"{n_measurements}"
                )
            return x[:, :n_steps, :]
        n_paths = x.shape[0] // n_measurements
        if n_paths < 2:
            raise InputError(
                f"ErrorSequences: {x.shape[0]} paths give fewer than 2 per measurement for "
                f"{n_measurements} measurements"
            )
        y = x[: n_paths * n_measurements, :n_steps].reshape(n_paths, n_measurements, n_steps)
        return np.transpose(y, (0, 2, 1))


Truth = ErrorProcess | SampledPSD | ErrorSequences


# --------------------------------------------------------------------------- result
@dataclass(frozen=True)
class CovarianceAnalysis:
    """True vs filter covariance of the filter's own states, step by step and in steady state.

    Attributes
    ----------
    p_filter_m2 : ndarray, shape (n_steps, n, n)
        The filter's own a-posteriori covariance of its ``n`` base states.
    p_true_m2 : ndarray, shape (n_steps, n, n)
        The true a-posteriori error covariance of those states.
    p_filter_ss_m2, p_true_ss_m2 : ndarray, shape (n, n), or None
        Steady state (time-invariant model, not for Monte Carlo).
    method : str
        ``"state_space"``, ``"psd"`` or ``"monte_carlo"``.
    dt_s : float
        Filter interval, seconds.
    psd_ratio_min : ndarray, shape (m,), or None
        Per measurement, the minimum over frequency of bound PSD / true PSD
        (>= 1 when the true PSD is under the bound); None for Monte Carlo.
    n_paths : int or None
        Number of Monte Carlo paths.
    labels : list of str
        Description of the true process per measurement.
    notes : list of str
        Why a steady state is missing, if it is.
    """

    p_filter_m2: NDArray[np.float64]
    p_true_m2: NDArray[np.float64]
    p_filter_ss_m2: NDArray[np.float64] | None
    p_true_ss_m2: NDArray[np.float64] | None
    method: str
    dt_s: float
    psd_ratio_min: NDArray[np.float64] | None = None
    n_paths: int | None = None
    labels: list[str] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)

    @property
    def n_steps(self) -> int:
        """Number of filter steps analysed."""
        return self.p_filter_m2.shape[0]

    @property
    def variance_ratio(self) -> NDArray[np.float64]:
        """Per step and state, true variance / filter variance, shape (n_steps, n)."""
        pf = np.diagonal(self.p_filter_m2, axis1=1, axis2=2)
        pt = np.diagonal(self.p_true_m2, axis1=1, axis2=2)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(pf > 0, pt / pf, np.where(pt > 0, np.inf, 1.0))

    @cached_property
    def eig_ratio(self) -> NDArray[np.float64]:
        """Per step, the largest generalised eigenvalue of ``(P_true, P_filter)``.

        The worst ratio of true to filter variance over every linear
        combination of the states (``P_true <= P_filter`` iff <= 1).
        """
        return _max_gen_eig(self.p_true_m2, self.p_filter_m2)

    @property
    def max_variance_ratio(self) -> float:
        """Largest true/filter variance ratio over steps, states and the steady state."""
        v = float(self.variance_ratio.max())
        if self.p_true_ss_m2 is not None and self.p_filter_ss_m2 is not None:
            pf = np.diag(self.p_filter_ss_m2)
            pt = np.diag(self.p_true_ss_m2)
            v = max(v, float(np.max(pt / pf)))
        return v

    @property
    def max_eig_ratio(self) -> float:
        """Largest generalised eigenvalue over steps and the steady state."""
        v = float(self.eig_ratio.max())
        if self.p_true_ss_m2 is not None and self.p_filter_ss_m2 is not None:
            v = max(v, float(_max_gen_eig(self.p_true_ss_m2, self.p_filter_ss_m2)))
        return v

    @property
    def worst_step(self) -> int:
        """Step (0-based) of the largest generalised eigenvalue."""
        return int(np.argmax(self.eig_ratio))

    def bounded(self, *, rtol: float = 1e-9) -> bool:
        """Whether the filter's covariance bounds the true one everywhere.

        Parameters
        ----------
        rtol : float, default 1e-9
            Allowed relative excess (round-off). For Monte Carlo, set it from
            the sampling error (roughly ``3 sqrt(2 / n_paths)``).

        Returns
        -------
        bool
            ``max_eig_ratio <= 1 + rtol``.
        """
        return self.max_eig_ratio <= 1.0 + rtol

    def summary(self) -> str:
        """Return a short text table of the analysis."""
        vr = self.variance_ratio
        lines = [
            "=" * 66,
            "Covariance analysis: true vs filter error covariance".center(66),
            "=" * 66,
            f"{'method':<34}{self.method:>32s}",
            f"{'steps x dt':<34}{self.n_steps:>22d} x {self.dt_s:g} s",
            f"{'max true/filter variance (diag)':<34}{self.max_variance_ratio:>32.6f}",
            f"{'max generalised eigenvalue':<34}{self.max_eig_ratio:>32.6f}",
            f"{'worst step':<34}{self.worst_step:>32d}",
            f"{'final-step ratio per state':<34}" + " ".join(f"{x:.4f}" for x in vr[-1]).rjust(32),
        ]
        if self.p_true_ss_m2 is not None and self.p_filter_ss_m2 is not None:
            ss = np.diag(self.p_true_ss_m2) / np.diag(self.p_filter_ss_m2)
            lines.append(
                f"{'steady-state ratio per state':<34}" + " ".join(f"{x:.4f}" for x in ss).rjust(32)
            )
        if self.psd_ratio_min is not None:
            lines.append(
                f"{'min bound/true PSD ratio':<34}{float(self.psd_ratio_min.min()):>32.4f}"
            )
        if self.n_paths is not None:
            lines.append(f"{'Monte Carlo paths':<34}{self.n_paths:>32d}")
        lines.append(f"{'bounded':<34}{str(self.bounded()):>32s}")
        lines.extend(f"note: {n}" for n in self.notes)
        lines.append("=" * 66)
        return "\n".join(lines)


def _max_gen_eig_one(p_true: NDArray[np.float64], p_filter: NDArray[np.float64]) -> float:
    """Largest generalised eigenvalue for a possibly singular filter covariance."""
    w, v = np.linalg.eigh(p_filter)
    tol = 1e-12 * max(float(w.max()), 1e-300)
    keep = w > tol
    null = v[:, ~keep]
    if null.size and float(np.abs(null.T @ p_true @ null).max()) > tol:
        return math.inf
    if not keep.any():
        return 1.0
    u = v[:, keep] / np.sqrt(w[keep])
    return float(np.linalg.eigvalsh(u.T @ p_true @ u).max())


def _max_gen_eig(p_true: NDArray[np.float64], p_filter: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest eigenvalue of ``P_f^-1/2 P_t P_f^-T/2`` for stacks of matrices (batched)."""
    pf = 0.5 * (p_filter + np.swapaxes(p_filter, -1, -2))
    pt = 0.5 * (p_true + np.swapaxes(p_true, -1, -2))
    try:
        linv = np.linalg.inv(np.linalg.cholesky(pf))
    except np.linalg.LinAlgError:
        flat_t = pt.reshape((-1,) + pt.shape[-2:])
        flat_f = pf.reshape((-1,) + pf.shape[-2:])
        vals = [_max_gen_eig_one(t, f) for t, f in zip(flat_t, flat_f, strict=True)]
        return np.array(vals).reshape(pt.shape[:-2])
    z = linv @ pt @ np.swapaxes(linv, -1, -2)
    return np.linalg.eigvalsh(0.5 * (z + np.swapaxes(z, -1, -2)))[..., -1]


# --------------------------------------------------------------------------- engine
def _broadcast_truth(truth: object, m: int, dt_s: float) -> list[Truth] | ErrorSequences:
    if isinstance(truth, ErrorSequences):
        if not math.isclose(truth.dt_s, dt_s, rel_tol=1e-9):
            raise InputError(
                f"true sequences are at dt = {truth.dt_s:g} s, the filter at {dt_s:g} s"
            )
        return truth
    if isinstance(truth, ErrorProcess | SampledPSD):
        items: list[object] = [truth] * m
    elif isinstance(truth, Sequence):
        items = list(truth)
        if len(items) != m:
            raise InputError(f"need one true process per measurement: got {len(items)} for {m}")
    else:
        raise InputError(
            "truth must be an ErrorProcess, a SampledPSD, a sequence of them (one per "
            f"measurement) or ErrorSequences; got {type(truth).__name__}"
        )
    kinds = {type(t) for t in items}
    if not kinds <= {ErrorProcess, SampledPSD}:
        raise InputError("true processes must be ErrorProcess or SampledPSD objects")
    for i, t in enumerate(items):
        if not math.isclose(t.dt_s, dt_s, rel_tol=1e-9):  # type: ignore[attr-defined]
            raise InputError(
                f"true process {i} is sampled at {t.dt_s:g} s, the filter runs at {dt_s:g} s"  # type: ignore[attr-defined]
            )
    return items  # type: ignore[return-value]


def _filter_pass(
    aug: AugmentedModel,
    h_seq: list[NDArray[np.float64]],
    r_seq: list[NDArray[np.float64]],
    p0: NDArray[np.float64],
) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
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


def _error_matrices(
    kg: NDArray[np.float64], h: NDArray[np.float64], scale: NDArray[np.float64], n: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    kb, kgm = kg[:n], kg[n:]
    m = scale.size
    d = np.diag(scale)
    mm = np.block([[np.eye(n) - kb @ h, kb @ d], [kgm @ h, np.eye(m) - kgm @ d]])
    nn = np.vstack([-kb, kgm])
    return mm, nn


def _other_part(
    aug: AugmentedModel,
    fs: NDArray[np.float64],
    qs: NDArray[np.float64],
    mats: list[tuple[NDArray[np.float64], NDArray[np.float64]]],
    r_base_seq: list[NDArray[np.float64]],
    p0_base: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Covariance of s from the initial error, process noise and other noise (no multipath)."""
    n = aug.n_base
    ns = fs.shape[0]
    z = np.zeros((ns, ns))
    z[:n, :n] = p0_base
    out = np.empty((len(mats), ns, ns))
    for k, ((mm, nn), rb) in enumerate(zip(mats, r_base_seq, strict=True)):
        if k > 0:
            z = fs @ z @ fs.T + qs
        z = mm @ z @ mm.T + nn @ rb @ nn.T
        z = 0.5 * (z + z.T)
        out[k] = z
    return out


def _psd_grid(nyq: float, extra: list[NDArray[np.float64]]) -> NDArray[np.float64]:
    parts = [np.linspace(0.0, nyq, 4097), np.geomspace(nyq * 1e-7, nyq, 4097)]
    parts += [e[(e >= 0) & (e <= nyq)] for e in extra]
    return np.unique(np.concatenate(parts))


def analyze_covariance(
    F: ArrayLike,
    Q: ArrayLike,
    H: ArrayLike,
    R: ArrayLike | None,
    bounds: GaussMarkovBound | Sequence[GaussMarkovBound],
    truth: ErrorProcess | SampledPSD | ErrorSequences | Sequence[ErrorProcess | SampledPSD],
    *,
    dt_s: float,
    n_steps: int,
    p0_base: ArrayLike,
    elevation_deg: ArrayLike | None = None,
    white_noise: str = "conservative",
    steady_state: bool = True,
) -> CovarianceAnalysis:
    """Compare a bound-designed filter's covariance with its true error covariance.

    The filter is the model ``(F, Q, H, R)`` augmented with one Gauss-Markov
    state per measurement from ``bounds`` (:func:`augment_gm_states`),
    initialised with ``blockdiag(p0_base, sigma_gm^2)``, first measurement at
    step 0. The truth has the same ``F, Q, H, R`` and initial error, and the
    true multipath ``truth`` (independent across measurements, stationary
    from step 0, raw metres at the measurement). See the module docstring for
    the equations.

    Parameters
    ----------
    F, Q : array_like, shape (n, n)
        The filter's own transition and process noise over ``dt_s``.
    H : array_like, shape (m, n) or (n_steps, m, n)
        Measurement matrix, constant or per step.
    R : array_like, shape (m, m) or (n_steps, m, m), or None
        Other (non-multipath) measurement noise, m^2.
    bounds : GaussMarkovBound or sequence of GaussMarkovBound
        The design multipath bound (one for all or one per measurement).
    truth : ErrorProcess, SampledPSD, ErrorSequences, or sequence
        The true multipath: one process for all measurements (independent
        copies), one per measurement, or sample paths.
    dt_s : float
        Filter interval, seconds (the truth must be at the same interval).
    n_steps : int
        Number of filter steps (measurement updates) to analyse.
    p0_base : array_like, shape (n, n)
        Initial covariance of the filter's own states.
    elevation_deg : array_like, shape (m,), optional
        Elevations for the bounds' mappings (design side only; give the
        truth in raw metres).
    white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
        White-noise convention of the bound at ``dt_s`` (:mod:`psdbound.kalman.bound`).
    steady_state : bool, default True
        Also compute the steady state (needs constant ``H`` and ``R``, a
        truth that is not sample paths, and a stabilising Riccati solution --
        e.g. not a filter whose states have no process noise). When it cannot
        be computed the steady-state fields are None and ``notes`` says why.

    Returns
    -------
    CovarianceAnalysis

    Raises
    ------
    InputError
        For inconsistent shapes or intervals, or a measurement covariance
        that is not positive definite.

    Notes
    -----
    Cost: the state-space path is ``O(n_steps (n + m + p)^3)``; the PSD path
    is ``O(n_steps^2 (n + m)^2 m)`` (a few seconds for 1000 steps).
    """
    n_steps = int(n_steps)
    if n_steps < 1:
        raise InputError(f"n_steps must be >= 1, got {n_steps}")
    Hm = np.asarray(H, dtype=float)
    if Hm.ndim == 3:
        if Hm.shape[0] < n_steps:
            raise InputError(f"H has {Hm.shape[0]} steps, the analysis needs {n_steps}")
        h_list = [Hm[k] for k in range(n_steps)]
    elif Hm.ndim == 2:
        h_list = [Hm] * n_steps
    else:
        raise InputError(f"H must have shape (m, n) or (n_steps, m, n), got {Hm.shape}")
    m, n = h_list[0].shape
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
    aug = augment_gm_states(
        F,
        Q,
        h_list[0],
        r_list[0],
        bounds,
        dt_s,
        elevation_deg=elevation_deg,
        white_noise=white_noise,
    )
    bl = broadcast_bounds(bounds, m)
    truths = _broadcast_truth(truth, m, float(dt_s))
    p0b = np.asarray(p0_base, dtype=float)
    p0 = aug.initial_covariance(p0b)
    dscale = np.diag(aug.scale)
    ha_list = [np.hstack([h, dscale]) for h in h_list]
    wn = np.diag(aug.scale**2 * aug.r_wn_m2)
    ra_list = [r + wn for r in r_list]
    ra_check = ra_list[:1] if time_invariant else ra_list
    if np.linalg.eigvalsh(np.array(ra_check)).min() <= 0:
        raise InputError(
            "the filter's measurement covariance R (+ the bound's white noise) must be "
            "positive definite"
        )
    p_filter, gains = _filter_pass(aug, ha_list, ra_list, p0)
    mats = [_error_matrices(kg, h, aug.scale, n) for kg, h in zip(gains, h_list, strict=True)]
    fs = linalg.block_diag(aug.F[:n, :n], np.diag(aug.phi))
    qs = linalg.block_diag(aug.Q[:n, :n], np.zeros((m, m)))
    ns = n + m
    want_ss = steady_state and time_invariant and not isinstance(truths, ErrorSequences)

    # filter steady state
    pf_ss = None
    mm_ss = nn_ss = None
    notes: list[str] = []
    if steady_state and not time_invariant:
        notes.append("no steady state: H or R varies with time")
    if steady_state and isinstance(truths, ErrorSequences):
        notes.append("no steady state from sample paths (Monte Carlo)")
    pm = None
    if want_ss:
        try:
            pm = linalg.solve_discrete_are(aug.F.T, ha_list[0].T, aug.Q, ra_list[0])
        except (ValueError, np.linalg.LinAlgError) as exc:
            notes.append(
                f"no steady state: the Riccati equation has no stabilising solution ({exc})"
            )
            want_ss = False
    if want_ss and pm is not None:
        h0 = ha_list[0]
        kss = linalg.solve(h0 @ pm @ h0.T + ra_list[0], h0 @ pm, assume_a="pos").T
        a = np.eye(aug.F.shape[0]) - kss @ h0
        pp = a @ pm @ a.T + kss @ ra_list[0] @ kss.T
        pf_ss = 0.5 * (pp + pp.T)[:n, :n]
        mm_ss, nn_ss = _error_matrices(kss, h_list[0], aug.scale, n)

    psd_ratio = None
    nyq = 0.5 / float(dt_s)
    if not isinstance(truths, ErrorSequences):
        ratios = []
        for i, (b, t) in enumerate(zip(bl, truths, strict=True)):
            extra = [t.f_hz] if isinstance(t, SampledPSD) else []
            grid = _psd_grid(nyq, extra)
            sb = b.sampled_psd(grid, dt_s, white_noise=white_noise) * aug.scale[i] ** 2
            st = t.psd(grid)
            with np.errstate(divide="ignore"):
                ratios.append(float(np.min(np.where(st > 0, sb / st, np.inf))))
        psd_ratio = np.array(ratios)

    labels: list[str]
    n_paths = None
    pt_ss = None
    if isinstance(truths, ErrorSequences):
        method = "monte_carlo"
        labels = [truths.label] * m
        other = _other_part(aug, fs, qs, mats, r_list, p0b)
        paths = truths.paths(m, n_steps)  # (P, n_steps, m)
        n_paths = paths.shape[0]
        s = np.zeros((n_paths, ns))
        p_true = np.empty((n_steps, n, n))
        for k, (mm, nn) in enumerate(mats):
            if k > 0:
                s = s @ fs.T
            s = s @ mm.T + paths[:, k, :] @ nn.T
            eb = s[:, :n]
            p_true[k] = other[k][:n, :n] + eb.T @ eb / n_paths
    elif all(isinstance(t, ErrorProcess) for t in truths):
        method = "state_space"
        procs: list[ErrorProcess] = truths  # type: ignore[assignment]
        labels = [t.label for t in procs]
        a_t = linalg.block_diag(*[t.a for t in procs])
        q_t = linalg.block_diag(*[t.q_m2 for t in procs])
        c_t = linalg.block_diag(*[t.c[None, :] for t in procs])  # (m, P)
        r_t = np.diag([t.r_m2 for t in procs])
        x0 = linalg.block_diag(*[t.stationary_covariance() for t in procs])
        pdim = a_t.shape[0]
        fz = linalg.block_diag(fs, a_t)
        qz = linalg.block_diag(qs, q_t)

        def joint(
            mm: NDArray[np.float64], nn: NDArray[np.float64]
        ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
            mz = np.block([[mm, nn @ c_t], [np.zeros((pdim, ns)), np.eye(pdim)]])
            nz = np.vstack([nn, np.zeros((pdim, m))])
            return mz, nz

        z = linalg.block_diag(p0b, np.zeros((m, m)), x0)
        p_true = np.empty((n_steps, n, n))
        for k, ((mm, nn), rb) in enumerate(zip(mats, r_list, strict=True)):
            if k > 0:
                z = fz @ z @ fz.T + qz
            mz, nz = joint(mm, nn)
            z = mz @ z @ mz.T + nz @ (rb + r_t) @ nz.T
            z = 0.5 * (z + z.T)
            p_true[k] = z[:n, :n]
        if want_ss:
            mz, nz = joint(mm_ss, nn_ss)  # type: ignore[arg-type]
            acl = mz @ fz
            zz = linalg.solve_discrete_lyapunov(acl, mz @ qz @ mz.T + nz @ (r_list[0] + r_t) @ nz.T)
            pt_ss = 0.5 * (zz + zz.T)[:n, :n]
    else:
        method = "psd"
        items: list[ErrorProcess | SampledPSD] = list(truths)
        labels = [t.label for t in items]
        acfs = np.column_stack([t.acf(n_steps) for t in items])  # (n_steps, m)
        other = _other_part(aug, fs, qs, mats, r_list, p0b)
        psi = np.zeros((n_steps, ns, m))
        v = np.zeros((ns, ns))
        p_true = np.empty((n_steps, n, n))
        r0 = np.diag(acfs[0])
        for k, (mm, nn) in enumerate(mats):
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
        if want_ss:
            acl = mm_ss @ fs  # type: ignore[operator]
            vo = linalg.solve_discrete_lyapunov(
                acl,
                mm_ss @ qs @ mm_ss.T + nn_ss @ r_list[0] @ nn_ss.T,  # type: ignore[operator,union-attr]
            )
            grid = _psd_grid(nyq, [t.f_hz for t in items if isinstance(t, SampledPSD)])
            zf = np.exp(-2j * np.pi * grid * float(dt_s))
            lhs = np.eye(ns)[None] - zf[:, None, None] * acl[None]
            g = np.linalg.solve(lhs, np.broadcast_to(nn_ss, (grid.size, ns, m)))[:, :n, :]
            sp = np.column_stack([t.psd(grid) for t in items])  # (nf, m)
            integrand = np.einsum("fim,fm,fjm->fij", g, sp, g.conj()).real
            vm = trapezoid(integrand, grid, axis=0)
            pt_ss = 0.5 * ((vo[:n, :n] + vm) + (vo[:n, :n] + vm).T)

    return CovarianceAnalysis(
        p_filter_m2=p_filter,
        p_true_m2=p_true,
        p_filter_ss_m2=pf_ss,
        p_true_ss_m2=pt_ss,
        method=method,
        dt_s=float(dt_s),
        psd_ratio_min=psd_ratio,
        n_paths=n_paths,
        labels=labels,
        notes=notes,
    )
