"""Held-out days: each station-day tested against the bound of the station's other days.

For a station with at least two bounded days (those in its pool), for each day ``d``:

* the **held-out bound** is the pooled bound of every window of the station's
  other days at the same sampling interval
  (:func:`~psdbound.campaign.tasks.pooled_days_bound`: a satellite repeating a
  sidereal day later is not counted as independent), over the band from the
  highest of the days' lowest frequencies to Nyquist;
* ``windows_covered_fraction``: the fraction of day ``d``'s windows that lie
  under that bound *in every band* within their own confidence: a window is
  not covered when, in some band, the lower limit of its band average
  (exact chi-square, one-sided at 5 % Bonferroni over the bands) lies above
  the bound;
* ``worst_excess_db``: the largest ``10 log10(band PSD / bound)`` over day
  ``d``'s windows and bands (a point estimate: positive values of a few dB
  are expected from a single window's scatter);
* ``kf_max_generalized_eigenvalue`` and ``kf_windows_bounded_fraction``: the
  covariance analysis (:func:`psdbound.kalman.analyze_covariance`) of a
  6-satellite static position + clock filter (1 mm of other phase noise per
  satellite, 200 steps) designed with the held-out bound, against each of
  day ``d``'s windows as the truth (the GM + white-noise model fitted to the
  window's own band spectrum: the held-out *data*, never a bound); the
  largest ratio over the windows, and the fraction of windows whose ratio is
  at most 1. Above 1 the design under-predicts some direction of the
  position-error covariance for that window's error.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.campaign.tasks import pooled_days_bound, psds_from_result

__all__ = ["held_out", "window_model"]

_ALPHA = 0.05
_N_STEPS = 200
_N_TAU_FIT = 40
_R_OTHER_M = 0.001


def _geometry() -> tuple[np.ndarray, np.ndarray]:
    az = np.deg2rad([0.0, 60.0, 130.0, 200.0, 270.0, 320.0])
    el = np.deg2rad([75.0, 40.0, 25.0, 55.0, 15.0, 35.0])
    los = np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])
    return np.column_stack([-los, np.ones(6)]), np.diag([1.0, 1.0, 1.0, 100.0])


def _kf_eig(design: Any, truth: tuple[float, float, float], dt: float) -> float:
    from psdbound.kalman import ErrorProcess, GaussMarkovBound, analyze_covariance

    bound = GaussMarkovBound.from_params(design.sigma_gm_m, design.tau_s, design.sigma_wn_m, dt)
    proc = ErrorProcess.gauss_markov(truth[0], truth[1], dt)
    if truth[2] > 0:
        proc = proc + ErrorProcess.white(truth[2], dt)
    h, p0 = _geometry()
    r_other = np.eye(6) * _R_OTHER_M**2  # receiver phase noise besides the multipath
    res = analyze_covariance(
        np.eye(4),
        np.diag([1e-6, 1e-6, 1e-6, 1e-2]),
        h,
        r_other,
        bound,
        proc,
        dt_s=dt,
        n_steps=_N_STEPS,
        p0_base=p0,
        steady_state=False,
    )
    return float(res.max_eig_ratio)


def window_model(bands: Any, row: int, dt_s: float) -> tuple[float, float, float]:
    """GM + white model fitted to one window's band spectrum: ``(sigma_gm_m, tau_s, sigma_wn_m)``.

    Least squares of the relative residuals, weighted by the band degrees of
    freedom, over a log grid of time constants (the variances by
    non-negative least squares at each). The time constant is capped at
    ``1 / (2 pi f_lo)``, the corner at the lowest band: below it the window
    shows nothing, and the model adds no power there that the data did not
    show (a longer time constant on the ridge of equal fit put ten to a
    hundred times the bound's power below the band into the truth).
    """
    from scipy import optimize

    from psdbound.spectra.models import gm_psd_sampled

    ok = np.isfinite(bands.psd_m2_hz[row]) & (bands.dof[row] > 0)
    s, nu = bands.psd_m2_hz[row][ok], bands.dof[row][ok]
    lo, hi = bands.edges_hz[:-1][ok], np.minimum(bands.edges_hz[1:][ok], 0.5 / dt_s)
    pts = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, 16)
    best, out = np.inf, (0.0, dt_s, 0.0)
    for tau in np.geomspace(dt_s / 2.0, 1.0 / (2.0 * np.pi * float(lo[0])), _N_TAU_FIT):
        a = (
            np.column_stack(
                [gm_psd_sampled(pts, 1.0, tau, dt_s).mean(axis=1), np.full(s.size, 2.0 * dt_s)]
            )
            / s[:, None]
        )
        x, _ = optimize.nnls(a * np.sqrt(nu)[:, None], np.sqrt(nu))
        misfit = float(np.sum((a @ x - 1.0) ** 2 * nu))
        if misfit < best:
            best, out = misfit, (float(np.sqrt(x[0])), float(tau), float(np.sqrt(x[1])))
    return out


def _covered(bands: Any, bound: Any) -> NDArray[np.bool_]:
    """Windows whose band averages' lower limits lie under the bound in every band."""
    from scipy import stats

    ok = np.isfinite(bands.psd_m2_hz) & (bands.dof > 0)
    a = _ALPHA / max(bands.centres_hz.size, 1)
    nu = np.where(ok, bands.dof, 1.0)
    lower = nu * np.where(ok, bands.psd_m2_hz, 0.0) / stats.chi2.isf(a, nu)
    above = ok & (lower > bound.psd(bands.centres_hz)[None, :])
    return ~above.any(axis=1)


def held_out(results: Sequence[dict[str, Any]], *, options: Any = None) -> list[dict[str, Any]]:
    """Test every station-day against the bound of the station's other days.

    Parameters
    ----------
    results : sequence of dict
        Station-day results of :func:`~psdbound.campaign.tasks.station_day_task`
        that entered their station's pool (bounded days).
    options : BoundOptions, optional
        The pooled rule's options (as :func:`~psdbound.campaign.tasks.pooled_days_bound`).

    Returns
    -------
    list of dict
        One row per tested station-day: ``station``, ``day``, ``n_other_days``,
        ``bound`` (``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``),
        ``windows_covered_fraction``, ``worst_excess_db``,
        ``kf_max_generalized_eigenvalue``, ``kf_windows_bounded_fraction``,
        ``band_hz``. Stations with one
        day get no row.
    """
    from psdbound.spectra.bands import band_spectra

    rows = []
    good = [r for r in results if r.get("fitted")]
    for station in sorted({r["station"] for r in good}):
        days = sorted((r for r in good if r["station"] == station), key=lambda r: r["day"])
        for d in days:
            others = [r for r in days if r is not d and np.isclose(r["dt_s"], d["dt_s"])]
            if not others:
                continue
            dt = float(d["dt_s"])
            f_min = max(float(r["f_min_hz"]) for r in [*others, d])
            bound = pooled_days_bound(others, f_min_hz=f_min, options=options).fit
            own = band_spectra(psds_from_result(d), f_min_hz=f_min)
            ok = np.isfinite(own.psd_m2_hz)
            has = ok.any(axis=1)
            covered = _covered(own, bound)[has]
            eigs = np.array(
                [_kf_eig(bound, window_model(own, i, dt), dt) for i in np.flatnonzero(has)]
            )
            with np.errstate(divide="ignore", invalid="ignore"):
                excess = 10.0 * np.log10(own.psd_m2_hz / bound.psd(own.centres_hz)[None, :])
            rows.append(
                {
                    "station": station,
                    "day": d["day"],
                    "n_other_days": len(others),
                    "bound": {
                        "sigma_gm_m": bound.sigma_gm_m,
                        "tau_s": bound.tau_s,
                        "sigma_wn_m": bound.sigma_wn_m,
                    },
                    "band_hz": [bound.f_min_hz, bound.f_max_hz],
                    "windows_covered_fraction": float(np.mean(covered)) if has.any() else np.nan,
                    "worst_excess_db": float(np.nanmax(excess[ok])) if ok.any() else None,
                    "kf_max_generalized_eigenvalue": float(eigs.max()) if eigs.size else np.nan,
                    "kf_windows_bounded_fraction": float(np.mean(eigs <= 1.0 + 1e-9))
                    if eigs.size
                    else np.nan,
                }
            )
    return rows
