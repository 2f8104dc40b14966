"""One station-day of a campaign: the fit stages up to the window spectra, as a Dask task.

A task item is a plain dict (picklable, hashable into a cache key):
``{"station", "day", "obs": [paths], "nav": path, "sha256": {path: digest},
"options": {...}}``. The result is a plain dict of numbers and arrays that
:class:`psdbound.compute.DiskCache` stores as JSON + NPZ: the day's own
pooled bound and every window's PSD estimate (to pool days later).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["day_config", "pooled_days_bound", "psds_from_result", "station_day_task"]


def day_config(item: dict[str, Any]) -> Any:
    """Return the :class:`~psdbound.pipeline.FitConfig` of one station-day task item.

    The item's ``options`` (FitConfig sections) with its observation files,
    its navigation file and the dual-frequency method: exactly what
    ``psdbound fit OBS... --nav NAV --method df`` with the same options uses.
    """
    from psdbound.pipeline.config import FitConfig

    cfg = FitConfig()
    for section, values in (item.get("options") or {}).items():
        cfg = cfg.updated(section, **values)
    return cfg.updated("inputs", obs=tuple(item["obs"]), nav=(item["nav"],), method="df")


def station_day_task(item: dict[str, Any]) -> dict[str, Any]:
    """Fit one station-day as ``psdbound fit`` does and keep what pooling needs.

    The day is fitted by :func:`psdbound.fit` (every stage, the result
    document and its verdict by :func:`psdbound.pipeline.verdict.judge`), so
    the day's verdict and reasons are the ones ``fit`` gives for it.

    Parameters
    ----------
    item : dict
        ``station``, ``day`` (``YYYY-MM-DD``), ``obs`` (paths of the day's
        files of the station), ``nav`` (path), ``options`` (a dict of
        :class:`~psdbound.pipeline.FitConfig` sections).

    Returns
    -------
    dict
        ``station``, ``day``, ``fitted`` (a bound was computed),
        ``verdict`` (``"bounded"``, ``"not-bounded"`` or ``"failed"``: ``fit``
        would stop with exit code 2) and ``verdict_reasons``; when failed,
        ``error`` (a one-line reason); when fitted, the bound
        (``sigma_gm_m``, ``tau_s``, ``sigma_wn_m``, ``dt_s``), ``f_min_hz``,
        ``f_c_hz``, ``covered_fraction``, ``covered_s`` (time in stationary
        windows, s), ``n_windows`` and the window PSDs as flat arrays
        ``psd_f_hz``, ``psd_m2_hz`` (divided by the high-pass's power response
        where it passes at least half the power, as the pooled bound does),
        ``psd_dof``, ``psd_n`` (samples) and ``psd_len`` (frequencies per window),
        the station's position from the header (``position_xyz_m``, ECEF m;
        ``lat_deg``, ``lon_deg``, WGS84 deg; None without one) and the day's
        result document (``document``, for its report).
    """
    from psdbound.errors import InputError, NoDataError
    from psdbound.pipeline.front import fit
    from psdbound.results import to_jsonable

    out: dict[str, Any] = {"station": item["station"], "day": item["day"], "fitted": False}
    try:
        res = fit(config=day_config(item))
    except (InputError, NoDataError) as exc:
        error = " ".join(str(exc).split())
        out.update(
            verdict="failed", verdict_reasons=[f"no bound (fit exits 2): {error}"], error=error
        )
        return out
    out.update(verdict=res.verdict, verdict_reasons=res.verdict_reasons)
    out.update(_position(res.inputs))
    out.update(_day_bound(res))
    out["document"] = to_jsonable(res.document)
    return out


def _position(inputs: Any) -> dict[str, Any]:
    """Return the station's position from its header (APPROX POSITION XYZ): ECEF and geodetic."""
    xyz = inputs.receiver_xyz_m[0] if inputs.receiver_xyz_m else None
    return {
        "position_xyz_m": None if xyz is None else [float(v) for v in xyz],
        "lat_deg": inputs.lat_deg,
        "lon_deg": inputs.lon_deg,
    }


def _psd_values(res: Any) -> list[np.ndarray]:
    """Window PSDs divided by the high-pass's power response where it passes >= half the power."""
    psds, cutoff, b = res.bounded.psds, res.cutoff, res.bounded.bound
    values = [p.psd_m2_hz for p in psds]
    if cutoff is None:
        return values
    from psdbound.spectra.bands import smoothed_responses

    def gain(f: np.ndarray) -> np.ndarray:
        return res.config.filter.response(f, b.dt_s, cutoff.f_c_hz) ** 2

    gains = smoothed_responses(
        gain, [p.f_hz for p in psds], [float(p.params.get("bandwidth_hz", 0.0)) for p in psds]
    )
    return [
        np.where(g >= 0.5, v / np.maximum(g, 0.5), v) for v, g in zip(values, gains, strict=True)
    ]


def _day_bound(res: Any) -> dict[str, Any]:
    """Return the bound, coverage and window spectra of a fitted day (numbers and arrays)."""
    b, win, psds = res.bounded.bound, res.windowed, res.bounded.psds
    w = win.windows
    data_s = res.screened.series.data_s
    return {
        "fitted": True,
        "sigma_gm_m": b.sigma_gm_m,
        "tau_s": b.tau_s,
        "sigma_wn_m": b.sigma_wn_m,
        "dt_s": b.dt_s,
        "f_min_hz": b.f_min_hz,
        "f_c_hz": None if res.cutoff is None else res.cutoff.f_c_hz,
        "mapping": [win.mapping.a, win.mapping.b, win.mapping.c_deg],
        "n_windows": len(w),
        "covered_fraction": min(w.covered_s / data_s, 1.0) if data_s > 0 else 0.0,
        "covered_s": w.covered_s,
        "psd_f_hz": np.concatenate([p.f_hz for p in psds]),
        "psd_m2_hz": np.concatenate(_psd_values(res)),
        "psd_dof": np.concatenate([np.broadcast_to(p.dof, p.f_hz.shape) for p in psds]),
        "psd_n": np.array([p.n_samples for p in psds]),
        "psd_len": np.array([p.f_hz.size for p in psds]),
        "psd_bandwidth_hz": np.array([p.params.get("bandwidth_hz", 0.0) for p in psds]),
        "win_sats": [x.sats for x in w.windows],
        "win_t_start_gps_s": np.array([x.t_start_gps_s for x in w.windows]),
        "estimator": res.bounded.estimator,
    }


def psds_from_result(result: dict[str, Any]) -> list[Any]:
    """Rebuild the window PSD estimates of a station-day result.

    Parameters
    ----------
    result : dict
        A successful :func:`station_day_task` result (possibly read back
        from the cache).

    Returns
    -------
    list of PSDEstimate
    """
    from psdbound.spectra import PSDEstimate

    edges = np.r_[0, np.cumsum(np.asarray(result["psd_len"], dtype=int))]
    f, s, d = (np.asarray(result[k], dtype=float) for k in ("psd_f_hz", "psd_m2_hz", "psd_dof"))
    width = result.get("psd_bandwidth_hz", np.zeros(len(result["psd_n"])))
    return [
        PSDEstimate(
            f[a:b],
            s[a:b],
            d[a:b],
            str(result.get("estimator", "multitaper")),
            params={"bandwidth_hz": float(w)} if w else {},
            dt_s=float(result["dt_s"]),
            n_samples=int(n),
        )
        for a, b, n, w in zip(edges[:-1], edges[1:], result["psd_n"], width, strict=True)
    ]


def pooled_days_bound(days: list[dict[str, Any]], *, f_min_hz: float, options: Any = None) -> Any:
    """Pool the windows of several days of one station; a sidereal repeat is not independent.

    Windows of one satellite a whole number of sidereal days apart repeat
    the same multipath (:func:`psdbound.spectra.dependence.repeat_clusters`):
    they form one cluster with intra-cluster correlation 1, i.e. count as
    one window in the pooled degrees of freedom (conservative: the repeat is
    close, not exact). When the days were high-pass filtered, the model set
    and the low-frequency statement are identified on the statement's bands
    (from ``f_min_hz``), as in ``fit``: below them the filter, not the data,
    set the spectra.

    Parameters
    ----------
    days : list of dict
        Fitted station-day results of one sampling interval.
    f_min_hz : float
        Lowest band edge, Hz.
    options : BoundOptions, optional
        The pooled rule's options of the days' fits (confidence level,
        coverage, shape test level, bands per decade, objective, prior
        ``tau_max_s`` in s); default :class:`~psdbound.spectra.BoundOptions`.

    Returns
    -------
    StatedBound
        As :func:`psdbound.spectra.stated.fit_stated_bound` (with the
        low-frequency statement).
    """
    from psdbound.spectra.dependence import repeat_clusters
    from psdbound.spectra.options import BoundOptions
    from psdbound.spectra.stated import fit_stated_bound

    opt = options or BoundOptions()
    psds = [p for r in days for p in psds_from_result(r)]
    dt = float(days[0]["dt_s"])
    clusters = None
    if all("win_sats" in r for r in days):
        sats = [s for r in days for s in r["win_sats"]]
        t0 = np.concatenate([np.asarray(r["win_t_start_gps_s"], dtype=float) for r in days])
        dur = np.array([p.n_samples * dt for p in psds])
        clusters = repeat_clusters(sats, t0, dur)
    # the days' spectra are already divided by their own high-pass's response (each day has
    # its own cutoff): a filter shaped everything below f_min, so the model set is identified
    # on the statement's bands, as fit does (below them the filtered lowest frequencies looked
    # like data with no low-frequency power)
    filtered = any(r.get("f_c_hz") for r in days)
    return fit_stated_bound(
        psds,
        dt,
        f_min_hz=f_min_hz,
        confidence_level=opt.confidence_level,
        filtered=filtered,
        tau_max_s=opt.tau_max_s,
        objective=opt.objective,
        coverage=opt.coverage,
        shape_alpha=opt.shape_alpha,
        bands_per_decade=opt.bands_per_decade,
        clusters=clusters,
        cluster_correlation=1.0 if clusters is not None else 0.0,
    )
