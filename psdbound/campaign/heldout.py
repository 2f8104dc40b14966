"""Held-out days: each station-day tested against the bound of the station's other days.

For a station with at least two good days, for each day ``d``:

* the **held-out bound** is the pooled bound (:func:`psdbound.spectra.pooled.fit_pooled_bound`)
  of every window of the station's other days at the same sampling interval,
  over the band from the highest of the days' lowest frequencies to Nyquist;
* ``windows_covered_fraction``: the fraction of day ``d``'s windows whose
  band spectrum is not significantly above that bound (standardised mean
  excess ``T_w`` of :func:`~psdbound.spectra.pooled.excess_statistic`, one-sided
  at 5 %);
* ``worst_excess_db``: the largest ``10 log10(band PSD / bound)`` over day
  ``d``'s windows and bands (a point estimate: noisy, positive values of a
  few dB are expected from a single window's scatter);
* ``kf_max_generalized_eigenvalue``: the existing covariance analysis
  (:func:`psdbound.kalman.analyze_covariance`) of a 6-satellite static
  position + clock filter (1 mm of other phase noise per satellite, 200
  steps) designed with the held-out bound, against day ``d``'s own pooled
  bound taken as its true multipath (independent per satellite, zenith
  scale); above 1 the design under-predicts some direction of the position
  error covariance.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np

from psdbound.campaign.tasks import pooled_days_bound, psds_from_result

__all__ = ["held_out"]

_ALPHA = 0.05
_N_STEPS = 200
_R_OTHER_M = 0.001


def _geometry() -> tuple[np.ndarray, np.ndarray]:
    az = np.deg2rad([0.0, 60.0, 130.0, 200.0, 270.0, 320.0])
    el = np.deg2rad([75.0, 40.0, 25.0, 55.0, 15.0, 35.0])
    los = np.column_stack([np.cos(el) * np.sin(az), np.cos(el) * np.cos(az), np.sin(el)])
    return np.column_stack([-los, np.ones(6)]), np.diag([1.0, 1.0, 1.0, 100.0])


def _kf_eig(design: Any, truth: dict[str, Any]) -> float:
    from psdbound.kalman import ErrorProcess, GaussMarkovBound, analyze_covariance

    dt = float(truth["dt_s"])
    bound = GaussMarkovBound.from_params(design.sigma_gm_m, design.tau_s, design.sigma_wn_m, dt)
    proc = ErrorProcess.gauss_markov(float(truth["sigma_gm_m"]), float(truth["tau_s"]), dt)
    if truth["sigma_wn_m"] > 0:
        proc = proc + ErrorProcess.white(float(truth["sigma_wn_m"]), dt)
    h, p0 = _geometry()
    r_other = np.eye(6) * _R_OTHER_M**2  # receiver phase noise besides the multipath
    res = analyze_covariance(np.eye(4), np.diag([1e-6, 1e-6, 1e-6, 1e-2]), h, r_other, bound, proc,
                             dt_s=dt, n_steps=_N_STEPS, p0_base=p0, steady_state=False)  # fmt: skip
    return float(res.max_eig_ratio)


def held_out(results: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Test every station-day against the bound of the station's other days.

    Parameters
    ----------
    results : sequence of dict
        Station-day results of :func:`~psdbound.campaign.tasks.station_day_task`.

    Returns
    -------
    list of dict
        One row per tested station-day: ``station``, ``day``, ``n_other_days``,
        ``bound`` (``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``),
        ``windows_covered_fraction``, ``worst_excess_db``,
        ``kf_max_generalized_eigenvalue``, ``band_hz``. Stations with one
        good day get no row.
    """
    from scipy import stats

    from psdbound.spectra.bands import band_spectra
    from psdbound.spectra.pooled import excess_statistic

    rows = []
    good = [r for r in results if r.get("ok")]
    for station in sorted({r["station"] for r in good}):
        days = sorted((r for r in good if r["station"] == station), key=lambda r: r["day"])
        for d in days:
            others = [r for r in days if r is not d and np.isclose(r["dt_s"], d["dt_s"])]
            if not others:
                continue
            f_min = max(float(r["f_min_hz"]) for r in [*others, d])
            bound, _, _ = pooled_days_bound(others, f_min_hz=f_min)
            own = band_spectra(psds_from_result(d), f_min_hz=f_min)
            z, v = own.log_unbiased()
            ok = np.isfinite(z)
            log_u = np.log(bound.psd(own.centres_hz))
            t = excess_statistic(z, v, ok, log_u)
            has = ok.any(axis=1)
            covered = float(np.mean(t[has] <= stats.norm.isf(_ALPHA))) if has.any() else np.nan
            with np.errstate(divide="ignore", invalid="ignore"):
                excess = 10.0 * np.log10(own.psd_m2_hz / bound.psd(own.centres_hz)[None, :])
            rows.append({
                "station": station, "day": d["day"], "n_other_days": len(others),
                "bound": {"sigma_gm_m": bound.sigma_gm_m, "tau_s": bound.tau_s,
                          "sigma_wn_m": bound.sigma_wn_m},
                "band_hz": [bound.f_min_hz, bound.f_max_hz],
                "windows_covered_fraction": covered,
                "worst_excess_db": float(np.nanmax(excess[ok])) if ok.any() else None,
                "kf_max_generalized_eigenvalue": _kf_eig(bound, d),
            })  # fmt: skip
    return rows
