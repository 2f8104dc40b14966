"""Covariance analysis: check that a filter designed with the bound over-estimates its error.

Set-up (docs/method/kalman.rst; the "sub-optimal filter" analysis of the
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

Layout: this module is the front, :func:`analyze_covariance`. The truths are
:class:`ErrorProcess` (:mod:`psdbound.kalman.process`), :class:`SampledPSD`
and :class:`ErrorSequences` (:mod:`psdbound.kalman.truth`); the result is
:class:`CovarianceAnalysis` (:mod:`psdbound.kalman.analysis`); the three
methods are in ``psdbound.kalman._methods``.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import linalg

from psdbound.errors import InputError
from psdbound.kalman._methods import (
    ErrorRecursion,
    error_matrices,
    filter_pass,
    measurement_sequences,
    monte_carlo_covariance,
    psd_covariance,
    psd_ratios,
    state_space_covariance,
    steady_state_filter,
)
from psdbound.kalman.analysis import CovarianceAnalysis
from psdbound.kalman.augment import AugmentedModel, augment_gm_states, broadcast_bounds
from psdbound.kalman.bound import GaussMarkovBound
from psdbound.kalman.process import ErrorProcess
from psdbound.kalman.truth import ErrorSequences, SampledPSD, Truth, broadcast_truth

__all__ = [
    "CovarianceAnalysis",
    "ErrorProcess",
    "ErrorSequences",
    "SampledPSD",
    "analyze_covariance",
]


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
    p0_gm_m2: ArrayLike | None = None,
) -> CovarianceAnalysis:
    """Compare a bound-designed filter's covariance with its true error covariance.

    The filter is the model ``(F, Q, H, R)`` augmented with one Gauss-Markov
    state per measurement from ``bounds`` (:func:`augment_gm_states`),
    initialised with ``blockdiag(p0_base, sigma_gm^2)`` (or ``p0_gm_m2``),
    first measurement at step 0. The truth has the same ``F, Q, H, R`` and initial error, and the
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
        White-noise convention of the bound at ``dt_s`` (:mod:`psdbound.spectra.models`).
    steady_state : bool, default True
        Also compute the steady state (needs constant ``H`` and ``R``, a
        truth that is not sample paths, and a stabilising Riccati solution --
        e.g. not a filter whose states have no process noise). When it cannot
        be computed the steady-state fields are None and ``notes`` says why.
    p0_gm_m2 : float or array_like, shape (m,), optional
        The filter's initial variance of each multipath state (normalised
        scale), m^2; default the bounds' stationary ``sigma_gm^2``. A
        non-stationary design model gives its own here
        (:meth:`psdbound.kalman.UncertainGMBound.p0_m2`).

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
    h_list, r_list, time_invariant = measurement_sequences(H, R, n_steps)
    m, n = h_list[0].shape
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
    if p0_gm_m2 is not None:
        aug = replace(aug, p0_gm_m2=_checked_p0_gm(p0_gm_m2, m))
    bl = broadcast_bounds(bounds, m)
    truths = broadcast_truth(truth, m, float(dt_s))
    p0b = np.asarray(p0_base, dtype=float)
    p0 = aug.initial_covariance(p0b)
    ha_list, ra_list = _augmented_measurements(aug, h_list, r_list, time_invariant)
    p_filter, gains = filter_pass(aug, ha_list, ra_list, p0)
    sequences = isinstance(truths, ErrorSequences)

    # filter steady state
    notes: list[str] = []
    if steady_state and not time_invariant:
        notes.append("no steady state: H or R varies with time")
    if steady_state and sequences:
        notes.append("no steady state from sample paths (Monte Carlo)")
    pf_ss = steady = None
    if steady_state and time_invariant and not sequences:
        found = steady_state_filter(aug, ha_list[0], ra_list[0], h_list[0], notes)
        if found is not None:
            pf_ss, steady = found

    rec = ErrorRecursion(
        n=n,
        m=m,
        fs=linalg.block_diag(aug.F[:n, :n], np.diag(aug.phi)),
        qs=linalg.block_diag(aug.Q[:n, :n], np.zeros((m, m))),
        mats=[error_matrices(kg, h, aug.scale, n) for kg, h in zip(gains, h_list, strict=True)],
        r_other=r_list,
        p0_base=p0b,
        steady=steady,
    )
    true = _true_covariance(rec, truths, bl, aug, dt_s, white_noise, n_steps)
    return CovarianceAnalysis(
        p_filter_m2=p_filter,
        p_true_m2=true.p_true,
        p_filter_ss_m2=pf_ss,
        p_true_ss_m2=true.p_true_ss,
        method=true.method,
        dt_s=float(dt_s),
        psd_ratio_min=true.psd_ratio,
        n_paths=true.n_paths,
        labels=true.labels,
        notes=notes,
    )


def _checked_p0_gm(p0_gm_m2: ArrayLike, m: int) -> NDArray[np.float64]:
    """Return the initial variances of the ``m`` multipath states, m^2, checked."""
    p0g = np.broadcast_to(np.asarray(p0_gm_m2, dtype=float), (m,)).copy()
    if not (np.isfinite(p0g).all() and (p0g >= 0).all()):
        raise InputError("p0_gm_m2 must be finite and >= 0")
    return p0g


def _augmented_measurements(
    aug: AugmentedModel,
    h_list: list[NDArray[np.float64]],
    r_list: list[NDArray[np.float64]],
    time_invariant: bool,
) -> tuple[list[NDArray[np.float64]], list[NDArray[np.float64]]]:
    """Return ``H`` and ``R`` (m^2) of the augmented filter per step; check ``R`` is definite."""
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
    return ha_list, ra_list


@dataclass(frozen=True)
class _TrueCovariance:
    """The true error covariance (m^2) per step and in steady state, and how it was computed."""

    method: str
    labels: list[str]
    p_true: NDArray[np.float64]
    p_true_ss: NDArray[np.float64] | None = None
    psd_ratio: NDArray[np.float64] | None = None
    n_paths: int | None = None


def _true_covariance(
    rec: ErrorRecursion,
    truths: list[Truth] | ErrorSequences,
    bl: list[GaussMarkovBound],
    aug: AugmentedModel,
    dt_s: float,
    white_noise: str,
    n_steps: int,
) -> _TrueCovariance:
    """Propagate the true error: Monte Carlo, state space or PSD, after the truth's kind."""
    if isinstance(truths, ErrorSequences):
        p_true, n_paths = monte_carlo_covariance(rec, truths, n_steps)
        return _TrueCovariance("monte_carlo", [truths.label] * rec.m, p_true, n_paths=n_paths)
    psd_ratio = psd_ratios(bl, truths, aug.scale, dt_s, white_noise)
    labels = [t.label for t in truths]
    if all(isinstance(t, ErrorProcess) for t in truths):
        p_true, pt_ss = state_space_covariance(rec, truths, n_steps)  # type: ignore[arg-type]
        return _TrueCovariance("state_space", labels, p_true, pt_ss, psd_ratio)
    p_true, pt_ss = psd_covariance(rec, truths, n_steps, float(dt_s))
    return _TrueCovariance("psd", labels, p_true, pt_ss, psd_ratio)
