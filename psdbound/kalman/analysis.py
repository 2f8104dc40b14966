"""Result of the covariance analysis: true vs filter error covariance.

:class:`CovarianceAnalysis` holds both covariances step by step and in
steady state, with the comparison measures (per-state variance ratios and the
largest generalised eigenvalue of ``(P_true, P_filter)``, i.e. the worst ratio
over every linear combination of the states). It is returned by
:func:`psdbound.kalman.analyze_covariance`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

__all__ = ["CovarianceAnalysis"]


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
