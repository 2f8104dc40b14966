"""A bound with a stated confidence: pooled limits of window spectra, grouped by shape.

The thesis bounds the envelope of every window's PSD estimate. The maximum
of many noisy estimates grows with their number, so that bound gets looser
as data grow, and it states no confidence. The pooled rule states instead
(docs/method/bound.rst):

    with confidence ``confidence_level`` the bound lies above the true PSD
    of at least a fraction ``coverage`` of the windows, in every band from
    ``f_min`` to the Nyquist frequency.

1. **Bands** (:mod:`psdbound.spectra.bands`): each window's PSD estimate is
   averaged over log-spaced bands, with equivalent degrees of freedom.
2. **Groups by shape**: within a group the windows share a spectral shape
   up to a deviation each, a level (and a tilt in log frequency where it is
   significant; :func:`psdbound.spectra.limits.window_deviations`), fitted on
   bands at least the estimator's smoothing wide; a window whose band
   values lie above its group's shape (one-sided tests at
   ``shape_alpha / M``) is moved to the next group, treated the same way.
3. **Limits**: per group and band, the exact chi-square upper limit of the
   group's common level given the windows' deviations
   (:func:`psdbound.spectra.limits.mean_upper_limit`, at ``a_mean / (G B_g)``
   for ``G`` groups and the group's ``B_g`` bands; a small group's bands are
   merged until it has :data:`MIN_GROUP_DOF` in each, :func:`group_bands`),
   times the largest simultaneous upper deviation of the windows that must be
   covered (all but ``floor((1 - coverage) M)`` of them, at ``a_window /
   M``). The two error
   probabilities add up to ``1 - confidence_level`` (Bonferroni), so the
   statement holds whatever the windows' levels and however they are
   distributed. Below a short window's data its deviation is extrapolated,
   and capped by the ``f^-2`` rule (:func:`capped_below_data`).
4. **Bound**: the tightest GM + white-noise PSD above every limit
   (:func:`psdbound.spectra.fit_bound`). A limit holds for the band's
   *mean* PSD, but the PSD exceeds its band mean near the lower edge when
   it is steep there (up to ``r = f_hi / f_lo`` for an ``f^-2`` slope over
   the whole band) and near the upper edge when it is flat while the bound
   still falls: the bound is held above ``U sqrt(r)`` at each band's lower
   edge and above ``U`` at its centre and upper edge.

The previous rule (a DerSimonian-Laird random-effects limit on the log
scale, the spread added only when Cochran's test rejected, groups by mean
excess) covered the windows' 99th percentile in 47-79 % of runs with a
lognormal spread of sigma and missed minorities of slow reflectors; the
measured coverage of this rule is in ``benchmarks/bound_coverage.py``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray
from scipy import stats

from psdbound.errors import InputError
from psdbound.spectra.bands import BandSpectra, band_spectra, merge_bands
from psdbound.spectra.bound import BoundFit, ExtraRows, Floor, fit_bound
from psdbound.spectra.estimators import PSDEstimate
from psdbound.spectra.groups import log_frequency, shape_groups, tilted
from psdbound.spectra.limits import (
    SHAPE_MODELS,
    WindowDeviations,
    design_effect_dof,
    mean_upper_limit,
    simultaneous_factor,
    spread_upper_limit,
    tolerance_factor,
    window_deviations,
)
from psdbound.spectra.models import below_band_ceiling
from psdbound.spectra.ordinates import LowestOrdinates

__all__ = [
    "MIN_GROUP_DOF",
    "PooledLimits",
    "band_spans",
    "capped_below_data",
    "excess_statistic",
    "fit_limits",
    "fit_pooled_bound",
    "group_bands",
    "lowest_limit",
    "pool_bands",
    "random_effects_mean",
]

#: Share of ``1 - confidence_level`` spent on the group levels (the rest on the windows).
MEAN_SHARE = 0.5
#: Deviation of a window from its group's shape: a level, and a tilt in log frequency for
#: the windows whose tilt is significant at TILT_ALPHA ("auto"); "level", "tilt" for all.
DEVIATION_MODEL = "auto"
#: Window looseness above which a band limit is explained: limit over the largest window, dB.
LOOSE_DB = 10.0
#: Least pooled degrees of freedom of a group's band: a small group's bands are merged until
#: its windows together have this many in each. One window of 14 degrees of freedom in a band
#: has an exact upper limit 4.6 times its estimate at the Bonferroni level of 24 bands; merged
#: to 40, 2.0 times (the in-band slope costs at most sqrt(f_hi / f_lo) instead).
MIN_GROUP_DOF = 40.0


def random_effects_mean(z: NDArray, v: NDArray, tau2: float) -> tuple[float, float, float]:
    """Return the generalised Cochran Q, the weighted mean and its variance at ``tau2``.

    Parameters
    ----------
    z, v : ndarray
        Values and their sampling variances.
    tau2 : float
        Between-value variance (random effects).

    Returns
    -------
    q, mean, variance_of_mean : float
    """
    w = 1.0 / (v + tau2)
    mu = float(np.sum(w * z) / np.sum(w))
    return float(np.sum(w * (z - mu) ** 2)), mu, float(1.0 / np.sum(w))


@dataclass(frozen=True)
class PooledLimits:
    """Pooled upper limits of the window spectra: groups of windows, band by band.

    Attributes
    ----------
    f_hz : ndarray, shape (B,)
        Geometric band centres, Hz.
    groups : ndarray of int, shape (M,)
        Group of each window (0 = the main shape; higher groups hold the
        windows whose shape departed from the groups before them).
    upper_m2_hz : ndarray, shape (G, B)
        Upper limit of each group and band, m^2/Hz: above the true band PSD
        of every covered window of the group (NaN where the group has no
        data in the band).
    tau2 : ndarray, shape (G, B)
        Between-window variance of the true log band PSDs (moment estimate
        from the deviations, 0 when the sampling noise explains them).
    p_homogeneous : ndarray, shape (G, B)
        Cochran's p-value of a common PSD across the group's windows.
    confidence_level : float
        Level of the whole statement.
    coverage : float
        Fraction of the windows whose true PSD the limits cover.
    mean_upper_m2_hz : ndarray, shape (G, B)
        Exact upper limit of each group's common level (the windows' mean
        log level), m^2/Hz.
    window_psd_max_m2_hz : ndarray, shape (G, B)
        Largest band average of the group's windows, m^2/Hz (for the
        looseness check).
    shape_p : ndarray, shape (M,)
        Shape-test p-value of each window in its final group.
    level_log, level_se_log : ndarray, shape (M,)
        Each window's log level relative to its group and its standard error.
    spread_upper_log_sd : ndarray, shape (G,)
        Upper confidence limit of the sd of the windows' true log levels.
    tolerance_factor : ndarray, shape (G,)
        Normal quantile ``z*`` multiplying it (:func:`~psdbound.spectra.limits.tolerance_factor`).
    window_term_log : ndarray, shape (G, B)
        Log factor from the group level to the limit in each band: the
        largest upper deviation (level and tilt) over the covered windows.
    effective_dof : ndarray, shape (G, B)
        Degrees of freedom of each group level (reduced by the design
        effect of dependent windows).
    notes : tuple of str
        Bands whose limit lies more than :data:`LOOSE_DB` above the largest
        window, with the reason.
    shape_alpha : float
        Level of the shape tests that formed the groups.
    band_span_hz : ndarray, shape (G, B, 2), optional
        The band each limit holds for, Hz (lower and upper edge): the common
        band, or for a small group the merged band it lies in
        (:func:`group_bands`); NaN where the group has no data.
    """

    f_hz: NDArray[np.float64]
    groups: NDArray[np.int64]
    upper_m2_hz: NDArray[np.float64]
    tau2: NDArray[np.float64]
    p_homogeneous: NDArray[np.float64]
    confidence_level: float
    coverage: float
    mean_upper_m2_hz: NDArray[np.float64] | None = None
    window_psd_max_m2_hz: NDArray[np.float64] | None = None
    shape_p: NDArray[np.float64] | None = None
    level_log: NDArray[np.float64] | None = None
    level_se_log: NDArray[np.float64] | None = None
    spread_upper_log_sd: NDArray[np.float64] | None = None
    tolerance_factor: NDArray[np.float64] | None = None
    window_term_log: NDArray[np.float64] | None = None
    effective_dof: NDArray[np.float64] | None = None
    notes: tuple[str, ...] = ()
    shape_alpha: float = 0.05
    band_span_hz: NDArray[np.float64] | None = None

    @property
    def n_groups(self) -> int:
        """Number of groups."""
        return int(self.upper_m2_hz.shape[0])

    def sizes(self) -> NDArray[np.int64]:
        """Windows per group."""
        return np.bincount(self.groups[self.groups >= 0], minlength=self.n_groups)

    def heterogeneous_fraction(self) -> float:
        """Fraction of (group, band) cells whose homogeneity test rejects at 5 %."""
        p = self.p_homogeneous[np.isfinite(self.p_homogeneous)]
        return float(np.mean(p < 0.05)) if p.size else 0.0

    def looseness_db(self) -> NDArray[np.float64]:
        """Per group and band, the limit over the largest window's band average, dB."""
        if self.window_psd_max_m2_hz is None:
            return np.full(self.upper_m2_hz.shape, np.nan)
        with np.errstate(invalid="ignore", divide="ignore"):
            return 10.0 * np.log10(self.upper_m2_hz / self.window_psd_max_m2_hz)


def excess_statistic(
    z: NDArray[np.float64],
    v: NDArray[np.float64],
    ok: NDArray[np.bool_],
    log_u: NDArray[np.float64],
) -> NDArray[np.float64]:
    """Return each window's standardised mean excess of its log band values over a limit.

    ``T_w = sum_b (Z_wb - log U_b) / v_wb / sqrt(sum_b 1 / v_wb)``: standard
    normal when the window's PSD equals ``U``, stochastically smaller when it
    lies below.

    Parameters
    ----------
    z, v : ndarray, shape (M, B)
        Unbiased log band values and their variances (:meth:`BandSpectra.log_unbiased`).
    ok : ndarray of bool, shape (M, B)
        Cells with an estimate.
    log_u : ndarray, shape (B,)
        Log of the limit in each band.

    Returns
    -------
    ndarray, shape (M,)
    """
    use = ok & np.isfinite(log_u)[None, :]
    w = np.where(use, 1.0 / v, 0.0)
    d = np.where(use, z - np.nan_to_num(log_u)[None, :], 0.0)
    return np.sum(w * d, axis=1) / np.sqrt(np.maximum(np.sum(w, axis=1), 1e-300))


def _check_levels(confidence_level: float, coverage: float, shape_alpha: float) -> None:
    if not 0.0 < confidence_level < 1.0:
        raise InputError(f"confidence level must lie in (0, 1), got {confidence_level!r}")
    if not 0.5 < coverage <= 1.0:
        raise InputError(f"coverage must lie in (0.5, 1], got {coverage!r}")
    if not 0.0 < shape_alpha < 1.0:
        raise InputError(f"shape alpha must lie in (0, 1), got {shape_alpha!r}")


def _cochran_p(z: NDArray, v: NDArray, ok: NDArray) -> NDArray[np.float64]:
    out = np.full(z.shape[1], np.nan)
    for b in range(z.shape[1]):
        use = ok[:, b]
        if use.sum() > 1:
            q, _, _ = random_effects_mean(z[use, b], v[use, b], 0.0)
            out[b] = float(stats.chi2.sf(q, use.sum() - 1))
    return out


@dataclass(frozen=True)
class _GroupLimits:
    """One group's limits on the common bands (a merged band's values repeated on its parts)."""

    mean_upper: NDArray[np.float64]
    tau2: NDArray[np.float64]
    p_hom: NDArray[np.float64]
    eff_dof: NDArray[np.float64]
    dev: WindowDeviations
    spread_upper: float
    z_star: float
    max_term: NDArray[np.float64]
    span_hz: NDArray[np.float64]


def group_bands(bands: BandSpectra, rows: NDArray[np.intp]) -> tuple[BandSpectra, NDArray[np.intp]]:
    """Return a group's band averages, merged until its windows have :data:`MIN_GROUP_DOF`.

    Parameters
    ----------
    bands : BandSpectra
        The common bands of every window.
    rows : ndarray of int
        The group's windows.

    Returns
    -------
    group_bands : BandSpectra
        The group's windows on its own bands: the common ones where the group's
        pooled degrees of freedom reach :data:`MIN_GROUP_DOF`, adjacent ones merged
        from the lowest up where they do not
        (:func:`~psdbound.spectra.bands.merge_bands`).
    index : ndarray of int, shape (B,)
        The group band of each common band (-1: the group has no data there).
    """
    sub = BandSpectra(
        bands.edges_hz,
        bands.centres_hz,
        bands.psd_m2_hz[rows],
        bands.dof[rows],
        None if bands.duration_s is None else bands.duration_s[rows],
        None if bands.nu0 is None else bands.nu0[rows],
    )
    pooled = sub.dof.sum(axis=0)
    if np.all(pooled[pooled > 0] >= MIN_GROUP_DOF):
        return sub, np.where(pooled > 0, np.arange(pooled.size), -1)
    # degrees of freedom from the merged width: narrow bands share multitaper ordinates
    merged = merge_bands(sub, min_window_dof=MIN_GROUP_DOF / rows.size, dof_by_width=True)
    lo = bands.edges_hz[:-1]
    index = np.searchsorted(merged.edges_hz, lo * (1.0 + 1e-12), side="right") - 1
    index[(index < 0) | (index >= merged.centres_hz.size)] = -1
    have = merged.dof.sum(axis=0) > 0
    index[index >= 0] = np.where(have[index[index >= 0]], index[index >= 0], -1)
    return merged, index


def _deviations(
    test_bands: BandSpectra,
    rows: NDArray[np.intp],
    model: str,
) -> tuple[WindowDeviations, WindowDeviations | None, NDArray[np.bool_]]:
    """Return the windows' levels, their levels and tilts, and which windows take the tilt."""
    zt, vt = test_bands.log_unbiased()
    okt = np.isfinite(zt[rows])
    x_test = log_frequency(test_bands.centres_hz)
    dof = test_bands.dof[rows]
    dev = window_deviations(zt[rows], vt[rows], okt, x_test, model="level", dof=dof)
    if model == "level":
        return dev, None, np.zeros(rows.size, dtype=bool)
    tilt = window_deviations(zt[rows], vt[rows], okt, x_test, model="tilt", dof=dof)
    use = np.ones(rows.size, dtype=bool) if model == "tilt" else tilted(tilt)
    return dev, tilt, use


def _at(
    dev: WindowDeviations, tilt: WindowDeviations | None, use: NDArray[np.bool_], x: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Each window's deviation and its standard error at ``x`` (its tilt where it takes one)."""
    d, se = dev.at(x)
    if tilt is not None and use.any():
        d_t, se_t = tilt.at(x)
        d[use], se[use] = d_t[use], se_t[use]
    return d, se


def capped_below_data(
    own: NDArray[np.float64], gb: BandSpectra, mean_up: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Cap each window's upper deviation in the bands below its data by the ``f^-2`` rule.

    A window shorter than the group's longest has no value in the group's lowest bands;
    its deviation there is its level (and tilt) model extrapolated, whose standard error
    grows with the distance (a steep short window's tilt put a limit 26 dB above every
    window of its group). For any sum of Gauss-Markov and white terms ``f^2 S(f)`` rises
    with ``f``, so below the window's lowest band ``j`` (lower edge ``l_j``, edge ratio
    ``r_j``) its PSD is at most ``r_j`` times its band mean there times ``(l_j / f)^2``
    (``S(l_j) <= r_j`` times the band mean, for the same reason). With its band mean at
    most ``U_j exp(u_j)`` (its upper deviation ``u_j`` over the group's level limit
    ``U_j``) and the bound held ``sqrt(r_b)`` above ``U_b exp(t_b)`` at band ``b``'s lower
    edge, the deviation ``u_b`` needed there is at most
    ``u_j + ln(U_j / U_b) + ln r_j + 2 ln(l_j / l_b) - ln(r_b) / 2``; each window takes
    the smaller of that and its extrapolated deviation.

    Parameters
    ----------
    own : ndarray, shape (M, B)
        Each window's upper deviation (log) at the group's bands.
    gb : BandSpectra
        The group's bands (which windows have a value in which band).
    mean_up : ndarray, shape (B,)
        The group's level limits, m^2/Hz.

    Returns
    -------
    ndarray, shape (M, B)
    """
    have = np.isfinite(gb.psd_m2_hz) & (gb.dof > 0)
    lo = gb.edges_hz[:-1]
    half_r = 0.5 * np.log(gb.edges_hz[1:] / lo)  # the bound is held sqrt(r_b) above at l_b
    out = own.copy()
    for i in range(own.shape[0]):
        first = np.flatnonzero(have[i])
        j = int(first[0]) if first.size else 0
        if j == 0 or not np.isfinite(mean_up[j]) or mean_up[j] <= 0:
            continue
        b = np.arange(j)
        with np.errstate(invalid="ignore", divide="ignore"):
            ceiling = below_band_ceiling(mean_up[j], lo[j], gb.edges_hz[j + 1], lo[b])
            cap = own[i, j] + np.log(ceiling / mean_up[b]) - half_r[b]
        usable = np.isfinite(cap)
        out[i, b] = np.where(usable, np.minimum(own[i, b], cap), own[i, b])
    return out


def _window_term(own: NDArray[np.float64], allowed: int) -> NDArray[np.float64]:
    """Return the largest own upper deviation of the windows kept (all but ``allowed``)."""
    m = own.shape[0]
    if m == 1:
        return np.zeros(own.shape[1])
    keep = np.argsort(np.max(own, axis=1))[: m - allowed]
    return np.max(own[keep], axis=0)


def _level_limits(
    gb: BandSpectra,
    d: NDArray[np.float64],
    a_mean: float,
    clusters: NDArray[np.int64] | None,
    rho: float,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Exact upper limits of the group's common level per band, and their degrees of freedom."""
    s, nu = gb.psd_m2_hz, gb.dof
    ok = np.isfinite(s) & (nu > 0)
    n_b = s.shape[1]
    a_band = a_mean / max(int(ok.any(axis=0).sum()), 1)  # Bonferroni over the group's bands
    mean_up, eff = np.full(n_b, np.nan), np.full(n_b, np.nan)
    for b in np.flatnonzero(ok.any(axis=0)):
        use = ok[:, b]
        cl = clusters[use] if clusters is not None else None
        eff[b] = design_effect_dof(nu[use, b], cl, rho)
        mean_up[b] = mean_upper_limit(
            s[use, b] * np.exp(-d[use, b]), nu[use, b], a_band, effective_dof=eff[b]
        )
    return mean_up, eff


def _group_limits(
    bands: BandSpectra,
    test_bands: BandSpectra,
    rows: NDArray[np.intp],
    levels: tuple[float, float],
    coverage: float,
    clusters: NDArray[np.int64] | None,
    rho: float,
    model: str,
) -> _GroupLimits:
    """Exact group levels per band, the windows' spread limit and its quantile factor.

    The windows' levels come from ``test_bands`` (bands at least the estimator's smoothing
    wide, whose averages are nearly independent); the limits are stated on the group's
    bands (:func:`group_bands`) and returned on the common ``bands``.
    """
    a_mean, a_window = levels
    a_spread = a_count = a_window / 2.0  # the tolerance diagnostics (no share of their own)
    gb, index = group_bands(bands, rows)
    dev, tilt, use = _deviations(test_bands, rows, model)
    m = rows.size
    allowed = int(np.floor((1.0 - coverage) * m + 1e-9))
    k = np.where(
        use, simultaneous_factor(a_window, m, n_params=2), simultaneous_factor(a_window, m)
    )[:, None]
    ref = test_bands.centres_hz
    d_c, se_c = _at(dev, tilt, use, log_frequency(gb.centres_hz, ref))
    cl = clusters[rows] if clusters is not None else None
    mean_up, eff = _level_limits(gb, d_c, a_mean, cl, rho)
    term = _window_term(capped_below_data(d_c + k * se_c, gb, mean_up), allowed)
    level, level_se = dev.coef[:, 0], np.sqrt(dev.cov[:, 0, 0])
    tau2 = np.where(
        np.isfinite(mean_up), max(0.0, float(np.var(level)) - float(np.mean(level_se**2))), np.nan
    )
    z, v = gb.log_unbiased()
    p_hom = _cochran_p(z, v, np.isfinite(z))
    span = np.column_stack([gb.edges_hz[:-1], gb.edges_hz[1:]])
    return _GroupLimits(
        _on_common(mean_up, index),
        _on_common(tau2, index),
        _on_common(p_hom, index),
        _on_common(eff, index),
        dev,
        spread_upper_limit(level, level_se, a_spread),
        tolerance_factor(m, allowed, a_count),
        _on_common(term, index, fill=0.0),
        _on_common(span, index),
    )


def _on_common(
    x: NDArray[np.float64], index: NDArray[np.intp], fill: float = np.nan
) -> NDArray[np.float64]:
    """Spread per-group-band values ``x`` (first axis) over the common bands (``fill``: none)."""
    have = (index >= 0).reshape(-1, *([1] * (x.ndim - 1)))
    return np.where(have, x[np.maximum(index, 0)], fill)


def _loose_notes(
    pl_upper: NDArray, win_max: NDArray, f_hz: NDArray, sizes: NDArray, eff: NDArray
) -> tuple[str, ...]:
    notes = []
    with np.errstate(invalid="ignore", divide="ignore"):
        db = 10.0 * np.log10(pl_upper / win_max)
    for g, b in zip(*np.nonzero(db > LOOSE_DB), strict=True):
        notes.append(
            f"group {g}, band at {f_hz[b]:.3g} Hz: the limit lies {db[g, b]:.1f} dB above the "
            f"largest window ({sizes[g]} window(s), {eff[g, b]:.0f} degrees of freedom in the "
            "band): few degrees of freedom, or windows whose levels differ"
        )
    return tuple(notes)


def _check_pool_options(
    confidence_level: float,
    coverage: float,
    shape_alpha: float,
    deviation_model: str,
    cluster_correlation: float,
) -> None:
    """Raise :class:`InputError` for a level, deviation model or correlation out of range."""
    _check_levels(confidence_level, coverage, shape_alpha)
    if deviation_model not in (*SHAPE_MODELS, "auto"):
        raise InputError(
            f"unknown deviation model {deviation_model!r}; choose from auto, "
            f"{', '.join(SHAPE_MODELS)}"
        )
    if not 0.0 <= cluster_correlation <= 1.0:
        raise InputError(f"cluster correlation must lie in [0, 1], got {cluster_correlation!r}")


def _check_pool_data(ok: NDArray[np.bool_], clusters: NDArray[np.int64] | None, n_w: int) -> None:
    """Raise :class:`InputError` when no window has data or the cluster labels do not fit."""
    if not ok.any():
        raise InputError("no window has a positive PSD in any band")
    if clusters is not None and np.shape(clusters) != (n_w,):
        raise InputError(
            f"clusters must give one label per window ({n_w}), got {np.shape(clusters)}"
        )


def _shape_groups(
    bands: BandSpectra,
    smoothing_hz: float,
    shape_alpha: float,
    max_groups: int,
    lowest: LowestOrdinates | None,
) -> tuple[BandSpectra, NDArray[np.int64]]:
    """Return the bands of the shape tests (at least ``2 W`` wide) and the windows' groups."""
    test_bands = (
        merge_bands(bands, min_window_dof=0.0, min_width_hz=2.0 * smoothing_hz)
        if smoothing_hz > 0
        else bands
    )
    zt, vt = test_bands.log_unbiased()
    labels = shape_groups(
        zt,
        vt,
        np.isfinite(zt),
        log_frequency(test_bands.centres_hz),
        test_bands.dof,
        shape_alpha,
        max_groups,
        lowest,
    )
    return test_bands, labels


def _error_levels(confidence_level: float, n_g: int) -> tuple[float, float]:
    """Split ``1 - confidence_level`` per group: its levels (over its bands), its windows."""
    alpha = 1.0 - confidence_level
    a_win = (1.0 - MEAN_SHARE) * alpha / n_g  # per group: the windows' own upper levels
    return (MEAN_SHARE * alpha / n_g, a_win)


@dataclass(frozen=True)
class _Pooled:
    """The limits of every group, stacked (rows: groups; per-window arrays: windows)."""

    mean_upper: NDArray[np.float64]
    tau2: NDArray[np.float64]
    p_hom: NDArray[np.float64]
    eff_dof: NDArray[np.float64]
    window_max: NDArray[np.float64]
    upper: NDArray[np.float64]
    level: NDArray[np.float64]
    level_se: NDArray[np.float64]
    shape_p: NDArray[np.float64]
    spread: NDArray[np.float64]
    z_star: NDArray[np.float64]
    window_term: NDArray[np.float64]
    span_hz: NDArray[np.float64]


def _pool_groups(
    bands: BandSpectra,
    test_bands: BandSpectra,
    labels: NDArray[np.int64],
    ok: NDArray[np.bool_],
    levels: tuple[float, float],
    coverage: float,
    clusters: NDArray[np.int64] | None,
    rho: float,
    model: str,
) -> _Pooled:
    """Return the limits of each shape group (:func:`_group_limits`) and its largest window."""
    n_w, n_b = ok.shape
    n_g = int(labels.max()) + 1
    keys = ("mean_upper", "tau2", "p_hom", "eff_dof", "window_max", "upper")
    out = {k: np.full((n_g, n_b), np.nan) for k in keys}
    level, level_se, shape_p = np.full(n_w, np.nan), np.full(n_w, np.nan), np.ones(n_w)
    spread, z_star, window_term = np.zeros(n_g), np.zeros(n_g), np.zeros((n_g, n_b))
    span = np.full((n_g, n_b, 2), np.nan)
    for g in range(n_g):
        rows = np.flatnonzero(labels == g)
        gl = _group_limits(bands, test_bands, rows, levels, coverage, clusters, rho, model)
        out["mean_upper"][g], out["tau2"][g], out["p_hom"][g], out["eff_dof"][g] = (
            gl.mean_upper,
            gl.tau2,
            gl.p_hom,
            gl.eff_dof,
        )
        spread[g], z_star[g] = np.sqrt(gl.spread_upper), gl.z_star
        window_term[g], span[g] = gl.max_term, gl.span_hz
        out["upper"][g] = gl.mean_upper * np.exp(window_term[g])
        out["window_max"][g] = np.where(ok[rows], bands.psd_m2_hz[rows], -np.inf).max(axis=0)
        out["window_max"][g][~np.isfinite(out["window_max"][g])] = np.nan
        level[rows], level_se[rows] = gl.dev.coef[:, 0], np.sqrt(gl.dev.cov[:, 0, 0])
        shape_p[rows] = gl.dev.shape_p
    return _Pooled(
        **out,
        level=level,
        level_se=level_se,
        shape_p=shape_p,
        spread=spread,
        z_star=z_star,
        window_term=window_term,
        span_hz=span,
    )


def pool_bands(
    bands: BandSpectra,
    *,
    confidence_level: float = 0.95,
    coverage: float = 0.99,
    shape_alpha: float = 0.05,
    clusters: NDArray[np.int64] | None = None,
    cluster_correlation: float = 0.0,
    max_groups: int = 8,
    smoothing_hz: float = 0.0,
    deviation_model: str = DEVIATION_MODEL,
    lowest: LowestOrdinates | None = None,
) -> PooledLimits:
    """Pool the windows' band spectra into limits that cover a fraction of the windows.

    Parameters
    ----------
    bands : BandSpectra
        Output of :func:`~psdbound.spectra.bands.band_spectra` /
        :func:`~psdbound.spectra.bands.merge_bands`.
    confidence_level : float, default 0.95
        Confidence of the whole statement, in (0, 1).
    coverage : float, default 0.99
        Fraction of the windows whose true PSD is covered, in (0.5, 1]: more
        than ``floor((1 - coverage) M)`` of a group's ``M`` windows above the
        limits has probability at most the share of ``1 - confidence_level``
        spent on it.
    shape_alpha : float, default 0.05
        Family-wise level of the tests that move a window of another shape
        to the next group.
    clusters : ndarray of int, optional
        Cluster of each window (windows sharing an error source); their
        pooled degrees of freedom are reduced by the design effect.
    cluster_correlation : float, default 0
        Intra-cluster correlation of the windows' estimates, in [0, 1].
    max_groups : int, default 8
        Most groups; the last one takes every remaining window.
    deviation_model : {"auto", "tilt", "level"}, default "auto"
        Each window's deviation from its group's shape: a level only, a
        level and a tilt in log frequency for every window, or ("auto") a
        tilt for the windows whose tilt is significant at
        :data:`~psdbound.spectra.groups.TILT_ALPHA` (family-wise) and a
        level for the others; a window with a significant tilt is also given
        a shape group of its own. Windows whose
        Gauss-Markov part differs while the white noise is shared differ
        most at the lowest frequencies, which a level averages away; a tilt
        for every window costs a wide margin at the band ends. Measured in
        ``benchmarks/bound_coverage.py``.
    smoothing_hz : float, default 0
        Half-width of the estimator's smoothing, Hz (multitaper ``W``). The
        windows' levels and the shape tests use bands merged to at least
        ``2 W`` width, whose averages are nearly independent (narrower bands
        share multitaper ordinates: treated as independent they understate
        a level's standard error and make the shape tests reject too often).
    lowest : LowestOrdinates, optional
        The windows' narrow estimates at their lowest Fourier frequencies
        (:func:`psdbound.spectra.ordinates.lowest_ordinates`, data that went
        through no filter), in the order of the bands' windows: a window whose
        estimate there exceeds its group's more than its level says is
        another shape too (:func:`psdbound.spectra.groups.shape_groups`).

    Returns
    -------
    PooledLimits

    Raises
    ------
    InputError
        A level outside its range, bad cluster labels, or no window with a
        positive PSD.

    References
    ----------
    Kish, L. (1965). Survey Sampling. Wiley.

    Viechtbauer, W. (2007). Confidence intervals for the amount of
    heterogeneity in meta-analysis. Statistics in Medicine 26(1), 37-52.
    """
    _check_pool_options(
        confidence_level, coverage, shape_alpha, deviation_model, cluster_correlation
    )
    z, var = bands.log_unbiased()
    ok = np.isfinite(z)
    n_w, n_b = z.shape
    _check_pool_data(ok, clusters, n_w)
    if lowest is not None and lowest.n.size != n_w:
        raise InputError(f"lowest has {lowest.n.size} windows, the bands {n_w}")
    test_bands, labels = _shape_groups(bands, smoothing_hz, shape_alpha, max_groups, lowest)
    n_g = int(labels.max()) + 1
    levels = _error_levels(confidence_level, n_g)
    pooled = _pool_groups(
        bands,
        test_bands,
        labels,
        ok,
        levels,
        coverage,
        clusters,
        cluster_correlation,
        deviation_model,
    )
    sizes = np.bincount(labels[labels >= 0], minlength=n_g)
    return PooledLimits(
        f_hz=bands.centres_hz,
        groups=labels,
        upper_m2_hz=pooled.upper,
        tau2=pooled.tau2,
        p_homogeneous=pooled.p_hom,
        confidence_level=confidence_level,
        coverage=coverage,
        mean_upper_m2_hz=pooled.mean_upper,
        window_psd_max_m2_hz=pooled.window_max,
        shape_p=pooled.shape_p,
        level_log=pooled.level,
        level_se_log=pooled.level_se,
        spread_upper_log_sd=pooled.spread,
        tolerance_factor=pooled.z_star,
        window_term_log=pooled.window_term,
        effective_dof=pooled.eff_dof,
        notes=_loose_notes(
            pooled.upper, pooled.window_max, bands.centres_hz, sizes, pooled.eff_dof
        ),
        shape_alpha=shape_alpha,
        band_span_hz=pooled.span_hz,
    )


def smoothing_hz(psds: Sequence[PSDEstimate]) -> float:
    """Median smoothing half-width of the estimates, Hz (multitaper ``W``; 0 for the others)."""
    return float(np.median([p.params.get("bandwidth_hz", 0.0) for p in psds]))


@dataclass(frozen=True, eq=False)
class _BandLimits:
    """The upper limits of one group as a PSD-like object for :func:`fit_bound`."""

    f_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]


def fit_pooled_bound(
    psds: Sequence[PSDEstimate],
    dt_s: float,
    *,
    f_min_hz: float,
    confidence_level: float = 0.95,
    coverage: float = 0.99,
    shape_alpha: float = 0.05,
    bands_per_decade: int = 10,
    min_window_dof: float = 4.0,
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None = None,
    clusters: NDArray[np.int64] | None = None,
    cluster_correlation: float = 0.0,
    deviation_model: str = DEVIATION_MODEL,
    objective: str = "variance",
    n_grid: int = 64,
    lowest: LowestOrdinates | None = None,
) -> tuple[BoundFit, BandSpectra, PooledLimits]:
    """Fit the tightest GM + white-noise bound over the pooled limits of the windows.

    Parameters
    ----------
    psds : sequence of PSDEstimate
        One estimate per (disjoint) stationary window.
    dt_s : float
        Sampling interval, seconds.
    f_min_hz : float
        Lowest band edge, Hz (the bound is stated from here to Nyquist).
    confidence_level : float, default 0.95
        With this probability the bound lies above the true PSD of at least
        ``coverage`` of the windows in every band (:func:`pool_bands`).
    coverage : float, default 0.99
        Fraction of the windows covered, in (0.5, 1].
    shape_alpha : float, default 0.05
        Level of the tests that move a window of another spectral shape to
        a group of its own.
    bands_per_decade : int, default 10
        Frequency bands per decade.
    min_window_dof : float, default 4
        Bands are merged until a typical window has this many degrees of
        freedom in each (:func:`~psdbound.spectra.bands.merge_bands`).
    power_response : callable, optional
        Power response of a filter the data went through, undone in the
        band averages (:func:`~psdbound.spectra.bands.band_spectra`).
    clusters : ndarray of int, optional
        Cluster label of each window (dependent windows, :func:`pool_bands`).
    cluster_correlation : float, default 0
        Their intra-cluster correlation, in [0, 1].
    deviation_model : {"auto", "tilt", "level"}, default "auto"
        Each window's deviation from its group's shape (:func:`pool_bands`).
    objective : {"variance", "area"}, default "variance"
        Tightness objective (:func:`fit_bound`).
    n_grid : int, default 64
        ``tau`` grid size.
    lowest : LowestOrdinates, optional
        The windows' lowest-frequency estimates, for the shape groups
        (:func:`pool_bands`).

    Returns
    -------
    bound : BoundFit
        ``target="pooled"``, ``level=confidence_level``; ``margins`` are per
        group (bound / upper limit, >= 1).
    bands : BandSpectra
        The per-window band averages.
    limits : PooledLimits
        The pooled band limits.
    """
    bands = merge_bands(
        band_spectra(
            psds,
            f_min_hz=f_min_hz,
            bands_per_decade=bands_per_decade,
            power_response=power_response,
        ),
        min_window_dof=min_window_dof,
    )
    limits = pool_bands(
        bands,
        confidence_level=confidence_level,
        coverage=coverage,
        shape_alpha=shape_alpha,
        smoothing_hz=smoothing_hz(psds),
        deviation_model=deviation_model,
        clusters=clusters,
        cluster_correlation=cluster_correlation,
        lowest=lowest,
    )
    fit = fit_limits(limits, bands, dt_s, objective=objective, n_grid=n_grid)
    return fit, bands, limits


def band_spans(
    limits: PooledLimits, bands: BandSpectra, g: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return the lower and upper edges (Hz) of the band each of group ``g``'s limits holds for.

    Parameters
    ----------
    limits : PooledLimits
        The pooled limits.
    bands : BandSpectra
        Their common bands.
    g : int
        Group index.

    Returns
    -------
    lo_hz, hi_hz : ndarray, shape (B,)
        The common band, or for a small group the merged band it lies in.
    """
    if limits.band_span_hz is None:
        return bands.edges_hz[:-1].copy(), bands.edges_hz[1:].copy()
    return limits.band_span_hz[g, :, 0], limits.band_span_hz[g, :, 1]


def lowest_limit(
    limits: PooledLimits, bands: BandSpectra, g: int
) -> tuple[float, float, float] | None:
    """Return group ``g``'s lowest finite, positive upper limit and the band it holds for.

    Parameters
    ----------
    limits : PooledLimits
        The pooled limits.
    bands : BandSpectra
        Their common bands.
    g : int
        Group index.

    Returns
    -------
    (limit_m2_hz, lo_hz, hi_hz) or None
        None when the group has no such limit.
    """
    row = np.asarray(limits.upper_m2_hz[g], dtype=float)
    have = np.flatnonzero(np.isfinite(row) & (row > 0))
    if not have.size:
        return None
    k = int(have[0])
    lo, hi = band_spans(limits, bands, g)
    return float(row[k]), float(lo[k]), float(hi[k])


def fit_limits(
    limits: PooledLimits,
    bands: BandSpectra,
    dt_s: float,
    *,
    objective: str = "variance",
    n_grid: int = 64,
    floor: Floor | None = None,
    extra: ExtraRows | None = None,
) -> BoundFit:
    """Fit the tightest GM + white-noise bound above pooled band limits.

    A limit holds for the band's mean PSD; the PSD can exceed the mean near
    the lower edge (a steep in-band slope) and near the upper edge (flat
    in-band, bound still falling). The bound is held at ``U sqrt(r)`` at the
    lower edge (``r = f_hi / f_lo``) and at ``U`` at the centre and the upper
    edge.

    Parameters
    ----------
    limits : PooledLimits
        The limits (:func:`pool_bands`).
    bands : BandSpectra
        The bands they are stated on.
    dt_s : float
        Sampling interval, seconds.
    objective : {"variance", "area"}, default "variance"
        Tightness objective (:func:`fit_bound`).
    n_grid : int, default 64
        ``tau`` grid size.
    floor : (ndarray, ndarray), optional
        Further points (Hz, m^2/Hz) the bound must lie above, not data
        (:func:`fit_bound`).
    extra : callable, optional
        Further linear constraints of each time constant (:func:`fit_bound`).

    Returns
    -------
    BoundFit
        ``target="pooled"``, ``level`` the limits' confidence level, stated
        from the lowest band edge to Nyquist; ``margins`` per group.
    """
    target = []
    for g, row in enumerate(limits.upper_m2_hz):
        lo, hi = band_spans(limits, bands, g)
        hi = np.minimum(hi, 0.5 / dt_s)
        have = np.isfinite(row) & np.isfinite(lo)
        lo, hi, row = lo[have], hi[have], row[have]
        f = np.concatenate([lo, np.sqrt(lo * hi), hi])
        u = np.concatenate([row * np.sqrt(hi / lo), row, row])
        target.append(_BandLimits(f, u))
    fit = fit_bound(
        target,
        dt_s,
        objective=objective,
        target="point",
        n_grid=n_grid,
        tau_range_s=(0.5 * dt_s, 20.0 / float(bands.edges_hz[0])),
        floor=floor,
        extra=extra,
    )
    # the bound is stated over the bands' full span, lowest edge to Nyquist
    return replace(
        fit,
        target="pooled",
        level=limits.confidence_level,
        f_min_hz=float(bands.edges_hz[0]),
        f_max_hz=0.5 / dt_s,
        meta={
            "n_bands": int(limits.f_hz.size),
            "coverage": limits.coverage,
            "n_groups": limits.n_groups,
            "shape_alpha": limits.shape_alpha,
        },
    )
