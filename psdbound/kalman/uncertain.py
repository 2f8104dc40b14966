"""A Kalman-filter design model safe for every Gauss-Markov process in a parameter set.

The fit gives one model ``(sigma_GM, tau, sigma_WN)``, but the true multipath's
time constant and variance are uncertain. A stationary first-order
Gauss-Markov (GM) model with the wrong ``tau`` does not bound a Kalman
filter's error covariance even when its PSD looks close. This module builds
a design model that does, for **every** stationary GM process in the set::

    tau in [tau_lo, tau_hi] (s),   sigma in [sigma_lo, sigma_hi] (m)

following [Langel2021]_ (non-stationary GM overbound with a minimum initial
variance) and [GarciaCrespillo2023]_ (frequency-domain conditions, tighter
choice of the design time constant). See docs/method/kalman.rst, section
"Uncertain Gauss-Markov parameters", for the equations and the checks.

The design model (continuous time, exported exactly at any filter interval)
is a GM process with time constant ``tau_d`` and steady-state variance
``sigma_d^2``, **started** with variance ``P0`` (not necessarily
``sigma_d^2``)::

    g[k+1] = Phi g[k] + w[k],  Phi = exp(-dt / tau_d),
    w ~ N(0, sigma_d^2 (1 - Phi^2)),   g[0] ~ N(0, P0)

Conditions (all three are checked by :func:`verify_design` with the exact
covariance analysis of :func:`psdbound.kalman.analyze_covariance`):

1. PSD dominance of the steady-state part over every process of the set.
   For first-order GM spectra the ratio of two PSDs is monotone in
   ``omega^2``, so it suffices at ``f = 0`` and ``f -> infinity``::

       sigma_d^2 tau_d >= sigma_hi^2 tau_hi,   sigma_d^2 / tau_d >= sigma_hi^2 / tau_lo

   i.e. ``sigma_d^2 = sigma_hi^2 max(tau_hi / tau_d, tau_d / tau_lo)``. The
   continuous conditions imply those of the sampled (aliased) spectra at any
   interval (``x coth x`` increasing, ``tanh(x) / x`` decreasing).
2. Minimum initial variance. With ``P0 < sigma_d^2`` the design covariance
   is the stationary one minus the rank-one term
   ``(sigma_d^2 - P0) Phi^(i + j)``; the largest removable amount is set by
   the tightest process of the set. In the continuous-time limit::

       P0_min = 2 sigma_hi^2 max(tau_d / (tau_lo + tau_d), tau_hi / (tau_hi + tau_d))

   which for the [Langel2021]_ choice ``tau_d = tau_lo`` is
   ``2 sigma_hi^2 tau_hi / (tau_lo + tau_hi)`` (between ``sigma_hi^2`` and
   ``2 sigma_hi^2``, below ``sigma_d^2 = sigma_hi^2 tau_hi / tau_lo``). The
   exact discrete-time minimum at a filter interval is
   :func:`minimum_initial_variance_m2` (always below the continuous value, so
   the closed form is safe at any interval).
3. White noise: the design's white part is the set's largest (``sigma_wn``).

Choices of ``tau_d`` (:meth:`GaussMarkovSet.design`): ``"langel2021"``
(``tau_d = tau_lo``, the default), ``"tight"`` (``tau_d = sqrt(tau_lo tau_hi)``,
the smallest steady-state variance ``sigma_hi^2 sqrt(tau_hi / tau_lo)``,
[GarciaCrespillo2023]_) or a number of seconds in the interval.
``stationary=True`` starts the model at ``sigma_d^2`` (the stationary
frequency-domain model). :meth:`GaussMarkovSet.naive` is the single model
that is *not* safe (mid-interval ``tau``, largest ``sigma``, stationary),
kept for the side-by-side comparison.

Provenance: the model structure (non-stationary GM, ``tau_lo``,
PSD-dominating steady state, minimum initial variance) follows the two
papers; the closed form of ``P0_min`` above was derived and checked here
(exact discrete minimum, :func:`minimum_initial_variance_m2`, converging to it
as ``dt -> 0``; covariance analysis over parameter grids in
tests/kalman/test_uncertain.py). Compare it with the papers' equations
before quoting it as theirs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import solve_toeplitz

from psdbound.common.options import Number
from psdbound.errors import InputError
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.covariance import analyze_covariance
from psdbound.kalman.process import ErrorProcess

__all__ = [
    "DesignCheck",
    "GaussMarkovSet",
    "UncertainGMBound",
    "UncertainGMStateSpace",
    "minimum_initial_variance_m2",
    "verify_design",
]


_POSITIVE = Number(lo=0.0, lo_open=True)
_NON_NEGATIVE = Number(lo=0.0)


def _positive(name: str, v: float, *, zero_ok: bool = False) -> float:
    return float((_NON_NEGATIVE if zero_ok else _POSITIVE)(name, v))


class UncertainGMStateSpace(NamedTuple):
    """Discrete state-space model of the design: ``(phi, qd_m2, r_m2, p0_m2)``.

    Attributes
    ----------
    phi : float
        Transition ``exp(-dt / tau_d)`` over one filter interval.
    qd_m2 : float
        Process-noise variance ``sigma_d^2 (1 - phi^2)``, m^2 (constant: the
        non-stationarity is only in the initial variance).
    r_m2 : float
        White measurement-noise variance per filter sample, m^2.
    p0_m2 : float
        Initial variance of the Gauss-Markov state, m^2.
    """

    phi: float
    qd_m2: float
    r_m2: float
    p0_m2: float


@dataclass(frozen=True)
class GaussMarkovSet:
    """The set of stationary first-order Gauss-Markov processes a design must bound.

    Parameters
    ----------
    tau_lo_s, tau_hi_s : float
        Time-constant interval, seconds (``0 < tau_lo_s <= tau_hi_s``).
    sigma_lo_m, sigma_hi_m : float
        Standard-deviation interval, metres (``0 <= sigma_lo_m <= sigma_hi_m``).
        Only ``sigma_hi_m`` enters the design (a smaller variance is bounded
        a fortiori); ``sigma_lo_m`` spans the verification grid.
    sigma_wn_m : float, default 0
        Largest white-noise standard deviation per data sample, metres.
    dt_s : float, default 1
        Data interval the white noise is stated at, seconds.
    """

    tau_lo_s: float
    tau_hi_s: float
    sigma_lo_m: float
    sigma_hi_m: float
    sigma_wn_m: float = 0.0
    dt_s: float = 1.0

    def __post_init__(self) -> None:
        lo, hi = _positive("tau_lo_s", self.tau_lo_s), _positive("tau_hi_s", self.tau_hi_s)
        slo = _positive("sigma_lo_m", self.sigma_lo_m, zero_ok=True)
        shi = _positive("sigma_hi_m", self.sigma_hi_m)
        if hi < lo:
            raise InputError(f"tau interval is empty: [{lo:g}, {hi:g}] s")
        if shi < slo:
            raise InputError(f"sigma interval is empty: [{slo:g}, {shi:g}] m")
        object.__setattr__(self, "tau_lo_s", lo)
        object.__setattr__(self, "tau_hi_s", hi)
        object.__setattr__(self, "sigma_lo_m", slo)
        object.__setattr__(self, "sigma_hi_m", shi)
        object.__setattr__(
            self, "sigma_wn_m", _positive("sigma_wn_m", self.sigma_wn_m, zero_ok=True)
        )
        object.__setattr__(self, "dt_s", _positive("dt_s", self.dt_s))

    # ------------------------------------------------------------------ designs
    def design(
        self, tau_s: float | str = "langel2021", *, stationary: bool = False
    ) -> UncertainGMBound:
        """Return the KF-safe design model for every process of the set.

        Parameters
        ----------
        tau_s : {"langel2021", "tight"} or float, default "langel2021"
            Design time constant: ``tau_lo`` ([Langel2021]_), the geometric
            mean ``sqrt(tau_lo tau_hi)`` (smallest steady-state variance,
            [GarciaCrespillo2023]_) or a value in ``[tau_lo, tau_hi]``, seconds.
        stationary : bool, default False
            Start at the steady-state variance instead of the minimum ``P0``.

        Returns
        -------
        UncertainGMBound
            ``sigma_d^2 = sigma_hi^2 max(tau_hi / tau_d, tau_d / tau_lo)`` and
            ``P0 = 2 sigma_hi^2 max(tau_d / (tau_lo + tau_d), tau_hi / (tau_hi + tau_d))``
            (module docstring).

        Raises
        ------
        InputError
            For an unknown name or a time constant outside the interval.
        """
        lo, hi, s2 = self.tau_lo_s, self.tau_hi_s, self.sigma_hi_m**2
        if isinstance(tau_s, str):
            if tau_s == "langel2021":
                td = lo
            elif tau_s == "tight":
                td = math.sqrt(lo * hi)
            else:
                raise InputError(f"tau_s must be 'langel2021', 'tight' or seconds, got {tau_s!r}")
            label = tau_s
        else:
            td = _positive("tau_s", tau_s)
            if not (lo * (1 - 1e-12) <= td <= hi * (1 + 1e-12)):
                raise InputError(f"design tau_s = {td:g} s is outside [{lo:g}, {hi:g}] s")
            label = f"tau_d={td:g} s"
        var_ss = s2 * max(hi / td, td / lo)
        p0 = var_ss if stationary else 2.0 * s2 * max(td / (lo + td), hi / (hi + td))
        kind = "stationary" if stationary else "non-stationary"
        return UncertainGMBound(self, td, math.sqrt(var_ss), min(p0, var_ss), f"{label}, {kind}")

    def naive(self, tau_s: float | None = None) -> UncertainGMBound:
        """Return a single stationary model that is **not** safe (comparison only).

        Parameters
        ----------
        tau_s : float, optional
            Its time constant, seconds; default the mid-interval
            ``(tau_lo + tau_hi) / 2``.

        Returns
        -------
        UncertainGMBound
            ``sigma_d = sigma_hi``, ``P0 = sigma_hi^2``; for comparison only.
        """
        td = 0.5 * (self.tau_lo_s + self.tau_hi_s) if tau_s is None else _positive("tau_s", tau_s)
        s = self.sigma_hi_m
        return UncertainGMBound(self, td, s, s * s, f"naive tau={td:g} s, stationary")

    # ------------------------------------------------------------ truths
    def grid(self, n_tau: int = 5, n_sigma: int = 2) -> list[tuple[float, float]]:
        """Grid of true ``(tau_s, sigma_m)`` in the set, endpoints included.

        Parameters
        ----------
        n_tau : int, default 5
            Time constants, geometrically spaced, seconds.
        n_sigma : int, default 2
            Standard deviations, linearly spaced, metres.

        Returns
        -------
        list of (float, float)
        """
        taus = np.geomspace(self.tau_lo_s, self.tau_hi_s, max(int(n_tau), 1))
        sigmas = np.linspace(self.sigma_hi_m, self.sigma_lo_m, max(int(n_sigma), 1))
        return [(float(t), float(s)) for t in taus for s in sigmas]

    def process(
        self, tau_s: float, sigma_m: float, dt_s: float, *, white_noise: str = "conservative"
    ) -> ErrorProcess:
        """One true process of the set at the filter interval (GM plus the set's white noise).

        Parameters
        ----------
        tau_s : float
            Time constant, seconds.
        sigma_m : float
            Standard deviation, metres.
        dt_s : float
            Filter interval, seconds.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            Convention for the set's white noise at ``dt_s``.

        Returns
        -------
        ErrorProcess
        """
        gm = ErrorProcess.gauss_markov(sigma_m, tau_s, dt_s)
        if self.sigma_wn_m == 0:
            return gm
        r = self.as_bound_template().white_variance_m2(dt_s, white_noise=white_noise)
        return gm + ErrorProcess.white(math.sqrt(r), dt_s)

    def as_bound_template(self) -> GaussMarkovBound:
        """Return a bound carrying the set's white noise (for the white-noise conventions)."""
        return GaussMarkovBound.from_params(
            self.sigma_hi_m, self.tau_lo_s, self.sigma_wn_m, self.dt_s
        )


@dataclass(frozen=True)
class UncertainGMBound:
    """A Gauss-Markov design model with a (possibly) non-stationary start.

    Build it with :meth:`GaussMarkovSet.design` (or :meth:`GaussMarkovSet.naive`).

    Parameters
    ----------
    gm_set : GaussMarkovSet
        The set it was designed for.
    tau_s : float
        Design time constant ``tau_d``, seconds.
    sigma_gm_m : float
        Steady-state standard deviation ``sigma_d``, metres.
    p0_m2 : float
        Initial variance ``P0`` of the Gauss-Markov state, m^2.
    method : str
        How it was chosen (informational).
    """

    gm_set: GaussMarkovSet
    tau_s: float
    sigma_gm_m: float
    p0_m2: float
    method: str = ""

    @property
    def bound(self) -> GaussMarkovBound:
        """The steady-state part and the white noise as a :class:`GaussMarkovBound`."""
        s = self.gm_set
        return GaussMarkovBound.from_params(self.sigma_gm_m, self.tau_s, s.sigma_wn_m, s.dt_s)

    @property
    def stationary(self) -> bool:
        """Whether the model starts at its steady-state variance."""
        return math.isclose(self.p0_m2, self.sigma_gm_m**2, rel_tol=1e-12)

    def to_state_space(
        self, dt_s: float, *, white_noise: str = "conservative"
    ) -> UncertainGMStateSpace:
        """Discrete model ``(phi, qd_m2, r_m2, p0_m2)`` for a filter interval.

        Parameters
        ----------
        dt_s : float
            Filter interval, seconds.
        white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
            White-noise convention (:meth:`GaussMarkovBound.white_variance_m2`).

        Returns
        -------
        UncertainGMStateSpace
            Initialise the state with ``p0_m2``; ``phi`` and ``qd_m2`` are
            constant over time.
        """
        phi, qd, r = self.bound.to_state_space(dt_s, white_noise=white_noise)
        return UncertainGMStateSpace(float(phi), float(qd), float(r), self.p0_m2)

    def variance_m2(self, n_steps: int, dt_s: float) -> NDArray[np.float64]:
        """Design variance of the Gauss-Markov state at steps ``0 .. n_steps - 1``, m^2.

        ``V_k = Phi^(2k) P0 + sigma_d^2 (1 - Phi^(2k))``: from ``P0`` to ``sigma_d^2``.

        Parameters
        ----------
        n_steps : int
            Number of steps.
        dt_s : float
            Interval, seconds.

        Returns
        -------
        ndarray, shape (n_steps,)
        """
        decay = np.exp(-2.0 * np.arange(int(n_steps)) * float(dt_s) / self.tau_s)
        return decay * self.p0_m2 + self.sigma_gm_m**2 * (1.0 - decay)

    def __str__(self) -> str:
        return (
            f"UncertainGMBound({self.method}: tau_d={self.tau_s:.3g} s, "
            f"sigma_d={100 * self.sigma_gm_m:.4g} cm, "
            f"sqrt(P0)={100 * math.sqrt(self.p0_m2):.4g} cm)"
        )


def minimum_initial_variance_m2(
    tau_d_s: float,
    sigma_d_m: float,
    gm_set: GaussMarkovSet,
    dt_s: float,
    n_steps: int,
    *,
    n_tau: int = 21,
) -> float:
    """Exact discrete-time minimum initial variance of a design over a horizon, m^2.

    The design covariance over ``n_steps`` samples is ``D + T`` with ``T`` the
    true (stationary) covariance, ``D`` the Toeplitz matrix of
    ``sigma_d^2 Phi_d^k - sigma^2 Phi^k`` (positive semi-definite under the PSD
    condition) minus ``c v v^T``, ``v_k = Phi_d^k``, ``c = sigma_d^2 - P0``.
    Design covariance >= true covariance (Loewner order, every linear
    functional of the error sequence, hence every linear filter) iff
    ``c <= 1 / (v^T D^-1 v)``; the largest ``P0`` over ``sigma = sigma_hi`` and
    the time constants of the set is returned (it increases with the horizon).

    Parameters
    ----------
    tau_d_s, sigma_d_m : float
        Design time constant (s) and steady-state standard deviation (m).
    gm_set : GaussMarkovSet
        The set.
    dt_s : float
        Filter interval, seconds.
    n_steps : int
        Horizon, samples (``O(n_steps^2)`` per time constant).
    n_tau : int, default 21
        Time constants tried (geometric grid, endpoints included).

    Returns
    -------
    float
        ``P0_min`` (0 if the whole stationary variance can be removed; the
        stationary variance if the PSD condition is tight at a frequency the
        design's decay reaches).

    Raises
    ------
    InputError
        If the design's PSD does not dominate a process of the set.
    """
    k = np.arange(int(n_steps))
    pd = math.exp(-dt_s / tau_d_s)
    sd2 = sigma_d_m**2
    v = pd**k
    worst = 0.0
    for tau in np.geomspace(gm_set.tau_lo_s, gm_set.tau_hi_s, max(int(n_tau), 2)):
        col = sd2 * v - gm_set.sigma_hi_m**2 * math.exp(-dt_s / tau) ** k
        if np.linalg.eigvalsh(np.array([[col[0], col[1]], [col[1], col[0]]])).min() < 0:
            raise InputError(f"the design's PSD does not dominate the process tau = {tau:g} s")
        try:
            x = solve_toeplitz(col, v)
        except np.linalg.LinAlgError:
            return sd2
        info = float(v @ x)
        if not (math.isfinite(info) and info > 0):
            return sd2
        worst = max(worst, sd2 - 1.0 / info)
    return max(worst, 0.0)


@dataclass(frozen=True)
class DesignCheck:
    """Result of :func:`verify_design`: worst generalised eigenvalue per true process.

    Attributes
    ----------
    design : UncertainGMBound
        The checked design.
    truths : list of (float, float)
        The true ``(tau_s, sigma_m)`` checked.
    max_eig : ndarray, shape (n_truths,)
        Per truth, the largest generalised eigenvalue of ``(P_true, P_filter)``
        over every step (transient included) and the steady state.
    worst_step : ndarray of int, shape (n_truths,)
        Step of that eigenvalue.
    notes : list of str
        Notes of the analyses (e.g. why a steady state is missing).
    """

    design: UncertainGMBound
    truths: list[tuple[float, float]]
    max_eig: NDArray[np.float64]
    worst_step: NDArray[np.int64]
    notes: list[str] = field(default_factory=list)

    @property
    def worst(self) -> float:
        """Largest eigenvalue over all truths."""
        return float(self.max_eig.max())

    @property
    def worst_truth(self) -> tuple[float, float]:
        """The ``(tau_s, sigma_m)`` of the largest eigenvalue."""
        return self.truths[int(np.argmax(self.max_eig))]

    def bounded(self, *, rtol: float = 1e-9) -> bool:
        """Whether the design bounds every truth checked (``worst <= 1 + rtol``).

        Parameters
        ----------
        rtol : float, default 1e-9
            Allowed relative excess (round-off).

        Returns
        -------
        bool
        """
        return self.worst <= 1.0 + rtol


def verify_design(
    design: UncertainGMBound,
    F: ArrayLike,
    Q: ArrayLike,
    H: ArrayLike,
    R: ArrayLike | None,
    *,
    dt_s: float,
    n_steps: int,
    p0_base: ArrayLike,
    truths: list[tuple[float, float]] | None = None,
    steady_state: bool = True,
    white_noise: str = "conservative",
) -> DesignCheck:
    """Check a design against true processes of its set with the covariance analysis.

    For each true ``(tau, sigma)`` (independent copies on every measurement)
    :func:`psdbound.kalman.analyze_covariance` compares the filter designed
    with ``design`` (steady-state part, white noise and initial variance
    ``P0``) with its true error covariance, step by step from the first
    update and in steady state.

    Parameters
    ----------
    design : UncertainGMBound
        The design model.
    F, Q, H, R : array_like
        The filter's own model (see :func:`~psdbound.kalman.analyze_covariance`).
    dt_s : float
        Filter interval, seconds.
    n_steps : int
        Steps analysed (cover the transient: several ``tau_hi``).
    p0_base : array_like, shape (n, n)
        Initial covariance of the filter's own states.
    truths : list of (float, float), optional
        True ``(tau_s, sigma_m)``; default ``design.gm_set.grid()``.
    steady_state : bool, default True
        Include the steady state.
    white_noise : {"psd", "per_sample", "conservative"}, default "conservative"
        White-noise convention.

    Returns
    -------
    DesignCheck
    """
    gm_set = design.gm_set
    grid = gm_set.grid() if truths is None else [(float(t), float(s)) for t, s in truths]
    eig = np.empty(len(grid))
    steps = np.empty(len(grid), dtype=np.int64)
    notes: list[str] = []
    for i, (tau, sigma) in enumerate(grid):
        res = analyze_covariance(
            F,
            Q,
            H,
            R,
            design.bound,
            gm_set.process(tau, sigma, dt_s, white_noise=white_noise),
            dt_s=dt_s,
            n_steps=n_steps,
            p0_base=p0_base,
            p0_gm_m2=design.p0_m2,
            steady_state=steady_state,
            white_noise=white_noise,
        )
        eig[i] = res.max_eig_ratio
        steps[i] = res.worst_step
        notes.extend(n for n in res.notes if n not in notes)
    return DesignCheck(design, grid, eig, steps, notes)
