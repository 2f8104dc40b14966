"""The lowest Fourier frequencies, resolved: the bound's expected estimate above the data's.

Below ``f_min`` the statement rests on the model set
(:mod:`psdbound.spectra.lowfreq`): the bound lies above every first-order
Gauss-Markov + white-noise model the data admit. A truth of another shape (a
fast reflector and a slow one in the same windows) is admitted as the single
model that fits its bands best, and the multitaper of the statement (``NW =
4``) smooths over ``+- 4 / T``, so the slow component's power at the lowest
Fourier frequencies ``1 / T, 2 / T, ...`` shows in no band. Measured on two
Gauss-Markov components (``tau`` 3-20 s and ``T / 10 .. T / 3``, equal
sigmas, 1 s, 15-40 windows): the bound lay 1.5-4 times under the truth's PSD
at ``1 / T`` in 9 of 12 seeds with the low-frequency status "covered".

**Check.** Each window (mean removed) is estimated at its lowest Fourier
frequencies ``j / T_i`` below ``f_min`` with a narrow multitaper
(:func:`psdbound.spectra.ordinates.lowest_ordinates`, ``NW = 1.5``, two
tapers: resolution ``+- 1.5 / T``). A sum of such
estimates over a shape group's windows has, under a model, an exact
expectation (:func:`psdbound.spectra.expectation.lag_kernels`: taper, mean
removal and the sampled autocovariance) that is linear in the two variances
and monotone in the PSD (its kernel is non-negative): a bound that lies above
the truth at every frequency has the larger expectation. The sum is about
``E chi^2_nu / nu`` with ``nu`` the windows' effective degrees of freedom
(:meth:`~psdbound.spectra.ordinates.LowestOrdinates.dof`: overlapping
ordinates carry fewer than four each; counted as four, a small group's limit
was too low); its upper limit at ``(1 -
confidence_level) / R`` (Bonferroni over the ``R`` rows; a small group's
ordinates merged until a row has 40 degrees of freedom, as its bands are) is
required of the bound's expectation, a linear constraint of its programs
(:func:`psdbound.spectra.pooled.fit_limits`, ``extra``). Where the tightest
bound already meets it nothing changes. This is a condition on each group's
mean at those frequencies, not the per-window statement above ``f_min``.

Only for data that went through no filter (:func:`psdbound.bound_series`):
after the GNSS high-pass the lowest frequencies hold the filter's response,
and the removed slow multipath is the error model's slow component.

References
----------
.. [1] Percival, D. B., & Walden, A. T. (1993). *Spectral Analysis for Physical
   Applications*, sections 7.3 and 7.5 (multitaper expectation and degrees of
   freedom). Cambridge University Press.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.spectra.bands import BandSpectra
from psdbound.spectra.bound import BoundFit, ExtraRows, Floor
from psdbound.spectra.expectation import lag_kernels
from psdbound.spectra.ordinates import LOWEST_NW, LowestOrdinates
from psdbound.spectra.pooled import MIN_GROUP_DOF, PooledLimits, fit_limits

__all__ = ["LowestFrequencies", "cover_lowest"]


@dataclass(frozen=True)
class LowestFrequencies:
    """What the bound's expected estimate is at the lowest Fourier frequencies.

    Attributes
    ----------
    groups : ndarray of int, shape (R,)
        Shape group of each checked row.
    j : ndarray of int, shape (R,)
        Lowest Fourier index of each row (a small group's ordinates are
        merged into runs of at least :data:`MIN_GROUP_DOF` degrees of freedom).
    upper_m2_hz : ndarray, shape (R,)
        Upper limit of the group's mean estimate over the row (m^2/Hz).
    before, after : ndarray, shape (R,)
        Bound's expectation over that limit, before and after the raise.
    raised : bool
        Whether the bound was raised to meet the limits.
    confidence_level : float
        Level of the limits (Bonferroni over the rows).
    rows : callable or None
        The constraints (``extra`` of :func:`psdbound.spectra.pooled.fit_limits`),
        for a later refit to keep.
    """

    groups: NDArray[np.int64]
    j: NDArray[np.int64]
    upper_m2_hz: NDArray[np.float64]
    before: NDArray[np.float64]
    after: NDArray[np.float64]
    raised: bool
    confidence_level: float
    rows: ExtraRows | None = field(default=None, repr=False, compare=False)

    def sentence(self) -> str:
        """Return this part of the statement, in words."""
        text = (
            f"at the lowest Fourier frequencies j / T (j = 1..{int(self.j.max())}) the bound's "
            f"expected narrow-multitaper estimate lies above the {100 * self.confidence_level:g} "
            f"% upper limit of each shape group's mean estimate"
        )
        if self.raised:
            text += f" (the bound was raised for it: it lay {self.before.min():.2f} times that)"
        return text

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "groups": self.groups.tolist(),
            "j": self.j.tolist(),
            "upper_m2_hz": self.upper_m2_hz.tolist(),
            "before": self.before.tolist(),
            "after": self.after.tolist(),
            "raised": self.raised,
            "confidence_level": self.confidence_level,
            "statement": self.sentence(),
        }


@dataclass(frozen=True)
class _Requirement:
    """Per row (a group's run of ordinates): mean lag kernels, white weight and upper limit."""

    groups: NDArray[np.int64]
    j: NDArray[np.int64]  # the lowest ordinate of each row's run
    kernels: NDArray[np.float64]  # (R, n_max): mean over the group's windows and the run
    white: NDArray[np.float64]  # (R,)
    upper: NDArray[np.float64]  # (R,)
    dt_s: float

    def rows(self, tau_s: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return the rows ``a @ (sigma_gm^2, sigma_wn^2) >= b`` at ``tau_s`` (a, b)."""
        lags = np.arange(self.kernels.shape[1])
        gm = 2.0 * self.dt_s * self.kernels @ np.exp(-lags * self.dt_s / tau_s)
        return np.column_stack([gm, self.white]), self.upper

    def ratio(self, fit: BoundFit) -> NDArray[np.float64]:
        """Return the bound's expectation over each limit."""
        a, b = self.rows(fit.tau_s)
        return (a @ np.array([fit.sigma_gm_m**2, fit.sigma_wn_m**2])) / b


def _runs(lo: LowestOrdinates, rows: NDArray[np.int64]) -> list[NDArray[np.int64]]:
    """Consecutive ordinates merged until each run has :data:`MIN_GROUP_DOF` (the last: the rest).

    Degrees of freedom of the group's windows together (:meth:`LowestOrdinates.dof`).
    """
    out, start = [], 0
    for stop in range(1, lo.j.size + 1):
        run = np.arange(start, stop)
        if lo.dof(rows, run) >= MIN_GROUP_DOF or stop == lo.j.size:
            out.append(run)
            start = stop
    return out


def _group_kernels(lo: LowestOrdinates, rows: NDArray[np.int64]) -> NDArray[np.float64]:
    """Mean lag kernels of a group's windows at each ordinate, shape (J, n_max).

    The kernels depend on a window's length only: each length is computed once.
    """
    out = np.zeros((lo.j.size, int(lo.n.max())))
    lengths, counts = np.unique(lo.n[rows], return_counts=True)
    for n, count in zip(lengths.tolist(), counts.tolist(), strict=True):
        f0 = 1.0 / (n * lo.dt_s)
        k = lag_kernels(n, lo.dt_s, (lo.j - 0.5) * f0, (lo.j + 0.5) * f0, nw=LOWEST_NW)[0]
        out[:, :n] += count * k
    return out / rows.size


def _requirement(
    lo: LowestOrdinates, groups: NDArray[np.int64], confidence_level: float
) -> _Requirement:
    """Mean lag kernels and upper limits of every group's runs of ordinates.

    A run's summed estimate over the group's windows and its ordinates has
    the degrees of freedom of :meth:`LowestOrdinates.dof` (adjacent ordinates
    overlap: fewer than ``2 K`` each); a small group's ordinates are merged
    until a run has :data:`MIN_GROUP_DOF`, as its bands are. The upper limit is
    ``nu mean / chi^2_nu(alpha)`` at ``alpha = (1 - level) / R``.
    """
    gs = np.unique(groups[groups >= 0])
    per = {int(g): np.flatnonzero(groups == g) for g in gs}
    runs = {g: _runs(lo, r) for g, r in per.items()}
    alpha = (1.0 - confidence_level) / sum(len(v) for v in runs.values())
    out_g, out_j, kern, upper = [], [], [], []
    for g, rows in per.items():
        k_all = _group_kernels(lo, rows)
        mean = lo.estimate_m2_hz[rows].mean(axis=0)
        for run in runs[g]:
            nu = lo.dof(rows, run)
            out_g.append(g)
            out_j.append(int(lo.j[run[0]]))
            kern.append(k_all[run].mean(axis=0))
            upper.append(nu * float(mean[run].mean()) / float(stats.chi2.ppf(alpha, nu)))
    kernels = np.vstack(kern)
    return _Requirement(
        np.array(out_g),
        np.array(out_j),
        kernels,
        2.0 * lo.dt_s * kernels[:, 0],
        np.array(upper),
        lo.dt_s,
    )


def cover_lowest(
    fit: BoundFit,
    lowest: LowestOrdinates,
    limits: PooledLimits,
    bands: BandSpectra,
    floor: Floor | None = None,
    *,
    objective: str = "variance",
    n_grid: int = 64,
) -> tuple[BoundFit, LowestFrequencies]:
    """Raise the bound, where needed, above the groups' lowest-frequency upper limits.

    Parameters
    ----------
    fit : BoundFit
        The bound after the low-frequency rule.
    lowest : LowestOrdinates
        The windows' estimates at their lowest Fourier frequencies.
    limits : PooledLimits
        The pooled limits (their groups, confidence level).
    bands : BandSpectra
        The statement's bands.
    floor : (ndarray, ndarray), optional
        Points the bound already lies above (Hz, m^2/Hz: the envelopes of
        the low-frequency rule and of :mod:`psdbound.spectra.unresolved`),
        kept as constraints of a refit.
    objective : {"variance", "area"}, default "variance"
        Tightness objective of a refit.
    n_grid : int, default 64
        ``tau`` grid size of a refit.

    Returns
    -------
    fit : BoundFit
        The bound (unchanged when it already meets every limit).
    LowestFrequencies
        The check, before and after.
    """
    req = _requirement(lowest, limits.groups, limits.confidence_level)
    before = req.ratio(fit)
    raised = bool(np.any(before < 1.0 - 1e-9))
    if raised:
        fit = fit_limits(
            limits,
            bands,
            lowest.dt_s,
            objective=objective,
            n_grid=n_grid,
            floor=floor,
            extra=req.rows,
        )
    return fit, LowestFrequencies(
        req.groups,
        req.j,
        req.upper,
        before,
        req.ratio(fit),
        raised,
        limits.confidence_level,
        req.rows,
    )
