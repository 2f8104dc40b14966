"""The set of Gauss-Markov + white-noise models consistent with the pooled spectra.

The bound is one model above the data. Kalman-filter integrity also needs to
know which models the data cannot tell apart (a filter designed with the
wrong time constant can fail to bound its own error covariance even when the
PSD looks close; see docs/method/kalman.rst). This module gives that set.

The main group's windows are pooled band by band exactly as for the bound
(:func:`psdbound.spectra.pooled.pool_bands`): the random-effects mean of the
unbiased log band PSDs, ``y_b``, with its variance ``s_b^2`` (sampling
variance plus the DerSimonian-Laird between-window spread). A model
``theta = (sigma_GM, tau, sigma_WN)`` predicts the band average of its
sampled PSD, ``m_b(theta)``, and is judged by

    chi2(theta) = sum_b (y_b - log m_b(theta))^2 / s_b^2.

The set is the likelihood-ratio region

    chi2(theta) - chi2_min <= phi * chi2_3^{-1}(level),

with ``phi = max(1, chi2_min / (B - 3))`` inflating it when the model does
not fit the band means to within their stated errors (over-dispersion, the
usual quasi-likelihood correction), and the reported intervals are the
projections of this joint region onto each parameter: every model in the
box of intervals need not be in the region, but every model of the region
is in the box, which is what a design for "every process in the set" needs
(Langel et al. 2021; Garcia Crespillo et al. 2023). The region is found on
a grid (48 time constants, 81 GM variances and 41 white-noise levels per
time constant, then a finer grid over that region); an interval that reaches
the coarse grid's edge is reported as open on that side.

Bands below two smoothing half-widths of the estimator (multitaper
``W = NW / (N dt)``) are not used: there the estimates are biased low (the
taper smoothing of the spectral peak at zero frequency and each window's
mean removal), which no sampling variance describes. Measured coverage of
the joint 95 % set on simulated windows (``tests/spectra/test_intervals.py``
and 60-trial runs): 85 % (40 trials, seed 20) to 100 % (60 trials, seed 5)
for tau = 30 s in 16 windows of 1200 s, 92 % for
tau = 10 s in 8 windows, 88 % for tau = 120 s in 16 windows of 1200 s (a
time constant a tenth of the window length is poorly determined and the
residual low-frequency bias shows: the tau interval then spans a factor of
about 6). Starting the bands at three half-widths gave 95 % and 90 % for the
last two but a tau interval 2.5 times wider in the first.

References
----------
.. [1] Venzon, D. J., & Moolgavkar, S. H. (1988). A method for computing
   profile-likelihood-based confidence intervals. *Applied Statistics*,
   37(1), 87-94.
.. [2] McCullagh, P., & Nelder, J. A. (1989). *Generalized Linear Models*
   (2nd ed.), section 4.5 (over-dispersion). Chapman & Hall.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.spectra.bands import BandSpectra
from psdbound.spectra.models import gm_psd_sampled
from psdbound.spectra.pooled import PooledLimits, random_effects_mean

__all__ = ["ModelSet", "model_set"]

#: Grid sizes: time constants, GM variances per time constant, white-noise levels.
N_TAU, N_VAR, N_WHITE = 48, 81, 41
#: Points per band for the band average of a model PSD.
_POINTS_PER_BAND = 24
#: Bands are used from this many estimator smoothing half-widths up.
LOW_BAND_FACTOR = 2.0
#: Fewest bands for three parameters and a dispersion estimate.
MIN_BANDS = 5


@dataclass(frozen=True)
class ModelSet:
    """GM + white-noise models consistent with the main group's pooled spectrum.

    Attributes
    ----------
    best : dict
        The best-fitting model: ``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``.
    tau_interval_s, sigma_gm_interval_m, sigma_wn_interval_m : tuple of float
        Projections of the joint region at ``confidence_level`` (seconds,
        metres, metres).
    open_ends : dict of str to tuple of bool
        Per parameter, whether the lower / upper end reached the search
        grid's edge (the data do not bound it there).
    confidence_level : float
        Level of the joint region.
    chi2_min : float
        Smallest chi-square over the grid.
    n_bands : int
        Bands used.
    dispersion : float
        ``max(1, chi2_min / (n_bands - 3))``.
    """

    best: dict[str, float]
    tau_interval_s: tuple[float, float]
    sigma_gm_interval_m: tuple[float, float]
    sigma_wn_interval_m: tuple[float, float]
    open_ends: dict[str, tuple[bool, bool]]
    confidence_level: float
    chi2_min: float
    n_bands: int
    dispersion: float
    includes: tuple[str, ...] = ()

    def with_model(self, name: str, sigma_gm_m: float, tau_s: float,
                   sigma_wn_m: float) -> ModelSet:  # fmt: skip
        """Return the set widened to contain one more model (e.g. the bound itself).

        The likelihood-ratio region describes the group's *mean* spectrum;
        the bound lies above the windows that differ from it, so its
        parameters can lie outside. A Kalman-filter design for "every model
        of the set" must include the bound: the reported intervals are the
        hull of the region and the models added here (named in
        ``includes``).
        """
        def hull(iv: tuple[float, float], v: float) -> tuple[float, float]:
            return (min(iv[0], v), max(iv[1], v))

        return replace(self, tau_interval_s=hull(self.tau_interval_s, tau_s),
                       sigma_gm_interval_m=hull(self.sigma_gm_interval_m, sigma_gm_m),
                       sigma_wn_interval_m=hull(self.sigma_wn_interval_m, sigma_wn_m),
                       includes=self.includes + (name,))  # fmt: skip

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready form (the ``bound.model_set`` section of result.json)."""
        return {
            "best": dict(self.best),
            "tau_interval_s": list(self.tau_interval_s),
            "sigma_gm_interval_m": list(self.sigma_gm_interval_m),
            "sigma_wn_interval_m": list(self.sigma_wn_interval_m),
            "open_ends": {k: list(v) for k, v in self.open_ends.items()},
            "confidence_level": self.confidence_level,
            "chi2_min": self.chi2_min,
            "n_bands": self.n_bands,
            "dispersion": self.dispersion,
            "includes": list(self.includes),
            "method": "joint likelihood-ratio region of (sigma_GM, tau, sigma_WN) for the main "
            "group's pooled band means (random-effects variances, over-dispersion scaled), "
            "projected on each parameter (a grid search), widened to contain the models named "
            "in 'includes' (the bound itself)",
        }


def _main_group_means(
    bands: BandSpectra, limits: PooledLimits
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """Random-effects mean log PSD of group 0 per band, its variance, and which bands have one."""
    z, v = bands.log_unbiased()
    rows = limits.groups == 0
    z, v = z[rows], v[rows]
    ok = np.isfinite(z) & np.isfinite(v)
    n_b = z.shape[1]
    y, s2 = np.full(n_b, np.nan), np.full(n_b, np.nan)
    for b in range(n_b):
        use = ok[:, b]
        if use.sum() >= 1:
            tau2 = float(limits.tau2[0, b]) if np.isfinite(limits.tau2[0, b]) else 0.0
            _, y[b], s2[b] = random_effects_mean(z[use, b], v[use, b], tau2)
    have = np.isfinite(y) & np.isfinite(s2) & (s2 > 0)
    return y, s2, have


def _region(
    y: NDArray[np.float64],
    s2: NDArray[np.float64],
    f_pts: NDArray[np.float64],
    dt_s: float,
    taus: NDArray[np.float64],
    steps: NDArray[np.float64],
    whites: NDArray[np.float64],
    threshold: float,
    chi2_floor: float | None,
) -> dict[str, Any]:
    """Chi-square on a (tau, GM variance, white level) grid and the region under the threshold.

    The GM variance grid of each tau is ``steps`` times the level that matches
    the band means at that tau (the region is narrow in variance for a given
    tau, wide across taus). ``chi2_floor``: a smaller minimum found before.
    """
    n_b = y.size
    unit = np.stack([gm_psd_sampled(f_pts, 1.0, t, dt_s).mean(axis=1) for t in taus])
    var = np.exp(np.median(y[None, :] - np.log(unit), axis=1))[:, None] * steps[None, :]
    chi2 = np.empty((taus.size, steps.size, whites.size))
    for i in range(taus.size):
        model = var[i][:, None, None] * unit[i][None, None, :] + whites[None, :, None]
        chi2[i] = np.sum((y - np.log(model)) ** 2 / s2, axis=2)
    k = np.unravel_index(int(np.argmin(chi2)), chi2.shape)
    c_min = float(chi2[k]) if chi2_floor is None else min(float(chi2[k]), chi2_floor)
    dispersion = max(1.0, c_min / max(n_b - 3, 1))
    ti, vi, wi = np.nonzero(chi2 <= c_min + dispersion * threshold)
    sigma_wn = np.sqrt(whites / (2.0 * dt_s))
    return {
        "index": (ti, vi, wi),
        "chi2_min": c_min,
        "dispersion": dispersion,
        "best": {"sigma_gm_m": float(np.sqrt(var[k[0], k[1]])), "tau_s": float(taus[k[0]]),
                 "sigma_wn_m": float(sigma_wn[k[2]])},  # fmt: skip
        "taus": taus[ti],
        "sigma_gm": np.sqrt(var[ti, vi]),
        "sigma_wn": sigma_wn[wi],
    }


def model_set(
    bands: BandSpectra,
    limits: PooledLimits,
    dt_s: float,
    *,
    confidence_level: float = 0.95,
    smoothing_hz: float = 0.0,
) -> tuple[ModelSet | None, str]:
    """Return the GM + white-noise models consistent with the pooled spectrum.

    Parameters
    ----------
    bands : BandSpectra
        Band-averaged window PSDs (:func:`psdbound.spectra.bands.band_spectra`).
    limits : PooledLimits
        The pooled limits (for the groups and between-window spreads).
    dt_s : float
        Sampling interval, seconds.
    confidence_level : float, default 0.95
        Level of the joint region.
    smoothing_hz : float, default 0
        Half-width of the estimator's spectral smoothing, Hz (multitaper:
        ``W = NW / (N dt)``, in its ``params["bandwidth_hz"]``): an estimate
        at ``f`` is the PSD averaged over ``f +- W``, which flattens a
        Gauss-Markov spectrum near zero frequency; the model is averaged the
        same way, else a long window's flattened low end reads as a long
        time constant.

    Returns
    -------
    ModelSet or None
        None when there are fewer than ``MIN_BANDS`` bands with data.
    reason : str
        Why there is no set (empty otherwise).

    Examples
    --------
    >>> fit = psdbound.fit()  # doctest: +SKIP
    >>> fit.bound_results.model_set.tau_interval_s  # doctest: +SKIP
    """
    y, s2, have = _main_group_means(bands, limits)
    # below a few smoothing widths the estimates are biased low (taper smoothing of the
    # spectral peak at 0 and the windows' own mean removal): those bands are not used
    have &= bands.edges_hz[:-1] >= LOW_BAND_FACTOR * smoothing_hz
    n_b = int(have.sum())
    if n_b < MIN_BANDS:
        return None, f"{n_b} frequency bands with data, at least {MIN_BANDS} needed"
    lo = bands.edges_hz[:-1][have]
    hi = np.minimum(bands.edges_hz[1:][have], 0.5 / dt_s)
    y, s2 = y[have], s2[have]
    # what a band average of the estimates expects: the PSD averaged uniformly in frequency
    # over the band widened by the estimator's smoothing half-width (folded at 0 and Nyquist)
    frac = np.linspace(0.0, 1.0, _POINTS_PER_BAND)
    f_pts = (lo - smoothing_hz)[:, None] + (hi - lo + 2.0 * smoothing_hz)[:, None] * frac
    nyq = 0.5 / dt_s
    f_pts = np.abs(f_pts)
    f_pts = np.where(f_pts > nyq, 2.0 * nyq - f_pts, f_pts)
    taus = np.geomspace(dt_s, 10.0 / (2.0 * np.pi * float(lo[0])), N_TAU)
    whites = np.concatenate([[0.0], float(np.exp(y.min())) * np.geomspace(1e-3, 10.0, N_WHITE - 1)])
    steps = np.geomspace(1e-2, 1e2, N_VAR)
    threshold = float(stats.chi2.ppf(confidence_level, 3))
    # a coarse grid over everything, then a fine one over the coarse region (+- 3 steps)
    coarse = _region(y, s2, f_pts, dt_s, taus, steps, whites, threshold, None)
    ti, vi, wi = coarse["index"]
    open_ends = {
        "tau_s": (bool(ti.min() == 0), bool(ti.max() == N_TAU - 1)),
        "sigma_gm_m": (bool(vi.min() == 0), bool(vi.max() == N_VAR - 1)),
        "sigma_wn_m": (False, bool(wi.max() == N_WHITE - 1)),  # 0 is a true lower end
    }

    def around(grid: NDArray[np.float64], idx: NDArray[np.intp], n: int) -> NDArray[np.float64]:
        a, b = grid[max(int(idx.min()) - 3, 0)], grid[min(int(idx.max()) + 3, grid.size - 1)]
        if a == 0.0:  # white noise: keep 0 and refine from the first positive level
            return np.concatenate([[0.0], np.geomspace(grid[1], b, n - 1)])
        return np.geomspace(a, b, n)

    fine = _region(y, s2, f_pts, dt_s, around(taus, ti, 41), around(steps, vi, 61),
                   around(whites, wi, 41), threshold, coarse["chi2_min"])  # fmt: skip
    best, c_min, dispersion = fine["best"], fine["chi2_min"], fine["dispersion"]
    tau_r, gm_r, wn_r = fine["taus"], fine["sigma_gm"], fine["sigma_wn"]
    out = ModelSet(
        best=best,
        tau_interval_s=(float(tau_r.min()), float(tau_r.max())),
        sigma_gm_interval_m=(float(gm_r.min()), float(gm_r.max())),
        sigma_wn_interval_m=(float(wn_r.min()), float(wn_r.max())),
        open_ends=open_ends,
        confidence_level=float(confidence_level),
        chi2_min=c_min,
        n_bands=n_b,
        dispersion=float(dispersion),
    )
    return out, ""
