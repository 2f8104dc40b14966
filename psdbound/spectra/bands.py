"""Band averages of window PSD estimates: the data the pooled bound is stated for.

Each window's PSD estimate is averaged over log-spaced frequency bands from
``f_min_hz`` to the Nyquist frequency (:func:`band_spectra`), with the
equivalent degrees of freedom of each band average, and adjacent bands are
merged until a typical window has enough degrees of freedom in each
(:func:`merge_bands`). See docs/method/bound.rst.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import special

from psdbound.errors import InputError
from psdbound.spectra.estimators import PSDEstimate
from psdbound.spectra.limits import log_chi2_bias

__all__ = [
    "BandSpectra",
    "band_spectra",
    "merge_bands",
    "over_data_db",
    "resolved_from_hz",
    "smoothed_response",
    "smoothed_responses",
]


@dataclass(frozen=True)
class BandSpectra:
    """Band-averaged PSDs of a set of windows.

    Attributes
    ----------
    edges_hz : ndarray, shape (B + 1,)
        Band edges, Hz (log-spaced).
    centres_hz : ndarray, shape (B,)
        Geometric band centres, Hz.
    psd_m2_hz : ndarray, shape (M, B)
        Band average of each window's PSD, m^2/Hz; NaN where the window has
        no frequency in the band.
    dof : ndarray, shape (M, B)
        Equivalent degrees of freedom of each band average (0 where NaN).
    duration_s : ndarray, shape (M,), optional
        Length ``N dt`` of each window, seconds.
    nu0 : ndarray, shape (M,), optional
        Each estimate's degrees of freedom at one frequency.
    """

    edges_hz: NDArray[np.float64]
    centres_hz: NDArray[np.float64]
    psd_m2_hz: NDArray[np.float64]
    dof: NDArray[np.float64]
    duration_s: NDArray[np.float64] | None = None
    nu0: NDArray[np.float64] | None = None

    def pooled(
        self, rows: NDArray[np.bool_] | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return the degrees-of-freedom weighted mean of the windows' band averages, and its dof.

        Parameters
        ----------
        rows : ndarray of bool, shape (M,), optional
            The windows pooled (default all).

        Returns
        -------
        mean_m2_hz, dof : ndarray, shape (B,)
            NaN and 0 where no window has data in the band.
        """
        s, nu = (
            (self.psd_m2_hz, self.dof) if rows is None else (self.psd_m2_hz[rows], self.dof[rows])
        )
        ok = np.isfinite(s) & (nu > 0)
        w = np.where(ok, nu, 0.0)
        den = w.sum(axis=0)
        with np.errstate(invalid="ignore", divide="ignore"):
            return (np.where(ok, s, 0.0) * w).sum(axis=0) / den, den

    def log_unbiased(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Return ``Z = log S_hat - E[log(chi2_nu / nu)]`` and its variance ``psi'(nu/2)``.

        Cells without an estimate (or with a non-positive Blackman-Tukey
        average) are NaN with infinite variance.
        """
        ok = (self.dof > 0) & (self.psd_m2_hz > 0)
        nu = np.where(ok, self.dof, 2.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            z = np.log(np.where(ok, self.psd_m2_hz, 1.0)) - log_chi2_bias(nu)
        var = special.polygamma(1, nu / 2.0)
        return np.where(ok, z, np.nan), np.where(ok, var, np.inf)


def band_spectra(
    psds: Sequence[PSDEstimate],
    *,
    f_min_hz: float,
    bands_per_decade: int = 10,
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]] | None = None,
    below_resolved: bool = False,
    edges_hz: NDArray[np.float64] | None = None,
) -> BandSpectra:
    """Average every PSD estimate over common log-spaced frequency bands.

    Parameters
    ----------
    psds : sequence of PSDEstimate
        One estimate per window (same sampling interval).
    f_min_hz : float
        Lower edge of the lowest band, Hz (> 0): e.g. where the high-pass
        filter's attenuation ends.
    bands_per_decade : int, default 10
        Number of bands per decade of frequency.
    power_response : callable, optional
        ``|H(f)|^2`` of a filter the data went through (e.g. the high-pass):
        each PSD value is divided by it before averaging, so the bands
        estimate the PSD before filtering. A multitaper estimate at ``f``
        averages the filtered PSD over ``f +- W``, so it is divided by the
        response averaged the same way (:func:`smoothed_response`), not by
        its value at ``f``: near the cutoff, where ``|H|^2`` rises steeply,
        the point value over-corrects the estimate. Values below 0.5 are refused
        (``f_min_hz`` should start where the filter passes most power).
    below_resolved : bool, default False
        Use the estimates below :func:`resolved_from_hz` too (down to
        ``f_min_hz``). Their band averages are then not averages of the PSD
        near the band: only a comparison with the estimator's exact
        expectation (:mod:`psdbound.spectra.expectation`) may use them.
    edges_hz : ndarray, optional
        Band edges, Hz, increasing from ``f_min_hz`` to the Nyquist frequency,
        in place of the log spacing (e.g. cells of the estimator's resolution,
        :mod:`psdbound.spectra.cells`).

    Returns
    -------
    BandSpectra

    Raises
    ------
    InputError
        No estimate, mixed sampling intervals, or ``f_min_hz`` not below the
        Nyquist frequency.
    """
    if not psds:
        raise InputError("no PSD estimate to pool")
    dts = {round(p.dt_s, 12) for p in psds}
    if len(dts) != 1:
        raise InputError(f"PSD estimates of different sampling intervals {sorted(dts)} s")
    nyq = psds[0].nyquist_hz
    if not 0.0 < f_min_hz < nyq:
        raise InputError(
            f"lowest band edge {f_min_hz:g} Hz must lie between 0 and the Nyquist frequency "
            f"{nyq:g} Hz"
        )
    if bands_per_decade < 1:
        raise InputError(f"bands_per_decade must be >= 1, got {bands_per_decade}")
    if edges_hz is None:
        n_bands = max(1, int(np.ceil(bands_per_decade * np.log10(nyq / f_min_hz))))
        edges = np.geomspace(f_min_hz, nyq, n_bands + 1)
    else:
        edges = np.array(edges_hz, dtype=float)
        n_bands = edges.size - 1
    edges[-1] = nyq * (1.0 + 1e-12)
    width = np.diff(edges)
    values = np.full((len(psds), n_bands), np.nan)
    dof = np.zeros((len(psds), n_bands))
    durations, nu0s = np.zeros(len(psds)), np.zeros(len(psds))
    picked = [_in_bands(p, edges, f_min_hz, below_resolved) for p in psds]
    if power_response is not None:
        gains = smoothed_responses(
            power_response,
            [f for f, _, _ in picked],
            [float(p.params.get("bandwidth_hz", 0.0)) for p in psds],
        )
        picked = [(f, s / _checked(g, f), i) for (f, s, i), g in zip(picked, gains, strict=True)]
    for k, (p, (_, s, idx)) in enumerate(zip(psds, picked, strict=True)):
        nu0 = float(np.median(np.atleast_1d(p.dof)))
        n = p.n_samples if p.n_samples > 0 else int(round(2 * p.f_hz.size))
        counts = np.bincount(idx, minlength=n_bands)
        sums = np.bincount(idx, weights=s, minlength=n_bands)
        have = counts > 0
        values[k, have] = sums[have] / counts[have]
        # in-band dof: 2 N dt df independent ordinates at most, never below one estimate's
        # nu_0 nor above what the band's own grid points can carry (bands narrower than the
        # estimator's smoothing share ordinates with their neighbours: an approximation the
        # coverage benchmark measures, benchmarks/bound_coverage.py)
        dof[k, have] = np.clip(2.0 * n * p.dt_s * width[have], nu0, nu0 * counts[have])
        durations[k], nu0s[k] = n * p.dt_s, nu0
    centres = np.sqrt(edges[:-1] * edges[1:])
    return BandSpectra(edges, centres, values, dof, durations, nu0s)


def _in_bands(
    p: PSDEstimate, edges: NDArray[np.float64], f_min_hz: float, below_resolved: bool
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    """One estimate's frequencies and values inside the bands, and each one's band index."""
    use = p.f_hz >= (f_min_hz if below_resolved else max(resolved_from_hz(p), f_min_hz))
    idx = np.searchsorted(edges, p.f_hz[use], side="right") - 1
    inside = (idx >= 0) & (idx < edges.size - 1)
    return p.f_hz[use][inside], p.psd_m2_hz[use][inside], idx[inside]


def _checked(gain: NDArray[np.float64], f_hz: NDArray[np.float64]) -> NDArray[np.float64]:
    """Return the filter's smoothed power response; refuse it where it passes under half."""
    if gain.size and gain.min() < 0.5:
        raise InputError(
            f"the filter passes only {gain.min():.2f} of the power at "
            f"{f_hz[np.argmin(gain)]:.3g} Hz; start the bands higher"
        )
    return gain


def merge_bands(
    bands: BandSpectra,
    *,
    min_window_dof: float = 4.0,
    min_width_hz: float = 0.0,
    dof_by_width: bool | None = None,
) -> BandSpectra:
    """Merge adjacent bands until a typical window has ``min_window_dof`` in each.

    Bands are merged from low to high frequency until the median, over the
    windows with data there, of the per-window degrees of freedom reaches
    ``min_window_dof`` (a short remainder joins the last band). Leading bands
    that no window reaches (below every window's resolution) are dropped, so
    the lowest band starts where the data do. Band
    averages combine with their degrees of freedom as weights.

    Parameters
    ----------
    bands : BandSpectra
    min_window_dof : float, default 4
        Target median per-window degrees of freedom of a band.
    min_width_hz : float, default 0
        Smallest band width, Hz. With the estimator's smoothing width (for
        multitaper ``2W``) the merged band averages of one window are nearly
        independent of each other.
    dof_by_width : bool, optional
        Each merged band's degrees of freedom, and those ``min_window_dof``
        is judged on, come from its width (``2 T df``, at least ``nu_0``, at
        most the sum of its parts), not summed over parts that share
        ordinates. Default: when ``min_width_hz`` is given (> 0). Needs the
        windows' durations and ``nu_0``.

    Returns
    -------
    BandSpectra
    """
    groups: list[list[int]] = []
    cur: list[int] = []
    if dof_by_width is None:
        dof_by_width = min_width_hz > 0
    by_width = dof_by_width and bands.duration_s is not None and bands.nu0 is not None
    for j in range(bands.centres_hz.size):
        if not cur and not (bands.dof[:, j] > 0).any():
            continue  # no window reaches this band: drop it rather than widen the next one
        cur.append(j)
        width = bands.edges_hz[cur[-1] + 1] - bands.edges_hz[cur[0]]
        d = bands.dof[:, cur].sum(axis=1)
        if by_width:  # adjacent narrow bands share ordinates: their dof do not add up
            d = np.minimum(d, np.maximum(2.0 * bands.duration_s * width, bands.nu0))
        wide = width >= min_width_hz
        if wide and (np.median(d[d > 0]) >= min_window_dof if (d > 0).any() else False):
            groups.append(cur)
            cur = []
    if cur:
        if groups:
            groups[-1] += cur
        else:
            groups.append(cur)
    edges = np.array([bands.edges_hz[g[0]] for g in groups] + [bands.edges_hz[-1]])
    dof = np.stack([bands.dof[:, g].sum(axis=1) for g in groups], axis=1)
    num = np.stack(
        [np.nansum(bands.dof[:, g] * np.nan_to_num(bands.psd_m2_hz[:, g]), axis=1) for g in groups],
        axis=1,
    )
    with np.errstate(invalid="ignore", divide="ignore"):
        psd = np.where(dof > 0, num / dof, np.nan)
    if by_width:
        width = np.diff(edges)[None, :]
        by_width = np.maximum(2.0 * bands.duration_s[:, None] * width, bands.nu0[:, None])
        dof = np.where(dof > 0, np.minimum(dof, by_width), 0.0)
    return BandSpectra(
        edges, np.sqrt(edges[:-1] * edges[1:]), psd, dof, bands.duration_s, bands.nu0
    )


def resolved_from_hz(psd: PSDEstimate) -> float:
    """Lowest frequency an estimate resolves, Hz.

    Multitaper: ``W + 1 / T`` (``W = NW / T`` the smoothing half-width, ``T``
    the window length): the estimate there averages the PSD over ``[1/T,
    2W + 1/T]``, clear of the zero frequency the window's mean removal
    empties. Other estimators: their equivalent bandwidth ``B = nu_0 / (2 T)``
    (Percival and Walden 1993, eq. 255a), and never below ``1 / T + B / 2``,
    the same clearance: the Blackman-Tukey estimate with the thesis's
    full-length lags (``nu_0`` about 1.14) would otherwise be stated from
    ``0.57 / T``, inside the emptied zero frequency.
    """
    n = psd.n_samples if psd.n_samples > 0 else int(round(2 * psd.f_hz.size))
    t = n * psd.dt_s
    if psd.method == "multitaper" and "bandwidth_hz" in psd.params:
        return float(psd.params["bandwidth_hz"]) + 1.0 / t
    bandwidth_hz = float(np.median(np.atleast_1d(psd.dof))) / (2.0 * t)
    return max(bandwidth_hz, 1.0 / t + 0.5 * bandwidth_hz)


#: Points of the average over ``f +- W`` in :func:`smoothed_response`.
_SMOOTH_POINTS = 17
#: Most frequencies per call of a filter's response in :func:`smoothed_responses`: the
#: windows of a 24 h, 1 Hz day are 7 million points, whose evaluation in one call held
#: 0.5 GB (the fit's peak memory 448 -> 726 MB); in calls of this size, about 40 MB.
_RESPONSE_POINTS = 1 << 18


def smoothed_response(
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    f_hz: NDArray[np.float64],
    half_width_hz: float,
) -> NDArray[np.float64]:
    """Power response averaged over ``f +- W``: what a smoothing estimator sees.

    Parameters
    ----------
    power_response : callable
        ``|H(f)|^2``.
    f_hz : ndarray
        Frequencies, Hz.
    half_width_hz : float
        The estimator's smoothing half-width ``W``, Hz (multitaper
        ``NW / T``; 0: the point value).

    Returns
    -------
    ndarray
        Mean of ``|H|^2`` over ``[f - W, f + W]`` (folded at 0), the
        boxcar approximation of the multitaper spectral window (flat within
        ``W``, small outside; Percival and Walden 1993, chapter 7).
    """
    return smoothed_responses(power_response, [f_hz], [half_width_hz])[0]


def smoothed_responses(
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    f_hz: Sequence[NDArray[np.float64]],
    half_width_hz: Sequence[float],
) -> list[NDArray[np.float64]]:
    """:func:`smoothed_response` of several estimates, with few calls of ``power_response``.

    A filter's response costs a fixed overhead per call (its design and
    evaluation set-up): the windows of a fit ask it together, not once each,
    in calls of about :data:`_RESPONSE_POINTS` frequencies (memory).

    Parameters
    ----------
    power_response : callable
        ``|H(f)|^2``.
    f_hz : sequence of ndarray
        Frequencies of each estimate, Hz.
    half_width_hz : sequence of float
        Smoothing half-width ``W`` of each estimate, Hz (0: the point value).

    Returns
    -------
    list of ndarray
        The smoothed response of each estimate at its frequencies.
    """
    out: list[NDArray[np.float64]] = []
    grids: list[NDArray[np.float64]] = []
    points = 0
    for f, w in zip(f_hz, half_width_hz, strict=True):
        f = np.asarray(f, dtype=float)
        offsets = np.linspace(-w, w, _SMOOTH_POINTS) if w > 0.0 else np.zeros(1)
        grids.append(np.abs(f[:, None] + offsets[None, :]))
        points += grids[-1].size
        if points >= _RESPONSE_POINTS:
            out += _averaged(power_response, grids)
            grids, points = [], 0
    return out + (_averaged(power_response, grids) if grids else [])


def _averaged(
    power_response: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    grids: list[NDArray[np.float64]],
) -> list[NDArray[np.float64]]:
    """Evaluate the response once on every grid (rows: frequencies) and average each row."""
    values = np.asarray(power_response(np.concatenate([g.ravel() for g in grids])), dtype=float)
    out, start = [], 0
    for g in grids:
        out.append(values[start : start + g.size].reshape(g.shape).mean(axis=1))
        start += g.size
    return out


def over_data_db(
    psd: Callable[[NDArray[np.float64]], NDArray[np.float64]], bands: BandSpectra
) -> dict[str, float]:
    """How far a PSD lies above the pooled data, band by band, dB (the bound's looseness).

    The pooled data of a band is the degrees-of-freedom weighted mean of every
    window's band average; the PSD's band value its mean over 16 log-spaced
    frequencies of the band.

    Parameters
    ----------
    psd : callable
        The PSD (e.g. the bound's ``psd``), m^2/Hz at frequencies in Hz.
    bands : BandSpectra
        The windows' band averages.

    Returns
    -------
    dict
        ``median_db`` and ``max_db`` over the bands with data, ``f_max_hz``
        (centre of the band where it is largest), ``over_highest_median_db``
        (the median over the bands of the PSD over the highest window's band
        average: what covering every window costs, apart from the spread of
        the windows) and ``n_bands``; NaN and 0 without data.
    """
    s, nu = bands.psd_m2_hz, bands.dof
    ok = np.isfinite(s) & (nu > 0)
    pooled, _ = bands.pooled()
    have = np.isfinite(pooled) & (pooled > 0)
    if not have.any():
        return {
            "median_db": float("nan"),
            "max_db": float("nan"),
            "f_max_hz": float("nan"),
            "over_highest_median_db": float("nan"),
            "n_bands": 0,
        }
    lo, hi = bands.edges_hz[:-1][have], bands.edges_hz[1:][have]
    model = np.array([np.mean(psd(np.geomspace(a, b, 16))) for a, b in zip(lo, hi, strict=True)])
    db = 10.0 * np.log10(model / pooled[have])
    highest = np.nanmax(np.where(ok, s, np.nan)[:, have], axis=0)
    k = int(np.argmax(db))
    return {
        "median_db": float(np.median(db)),
        "max_db": float(db[k]),
        "f_max_hz": float(bands.centres_hz[have][k]),
        "over_highest_median_db": float(np.median(10.0 * np.log10(model / highest))),
        "n_bands": int(have.sum()),
    }
