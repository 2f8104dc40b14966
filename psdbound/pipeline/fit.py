"""The ``fit`` pipeline: observations -> arcs -> multipath -> windows -> PSDs -> bound.

:func:`run_fit` runs every stage from a :class:`~psdbound.pipeline.config.FitConfig`
and returns a :class:`~psdbound.pipeline.result.FitResult` (the future
``result.json``), including the decimated data of every report figure.
It only calls the stage packages' public functions.
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import platform
import time
from collections.abc import Callable
from importlib import metadata
from pathlib import Path
from typing import Any

import numpy as np

from psdbound import __version__
from psdbound.errors import InputError, NoDataError
from psdbound.io import Observations, find_arcs, read_obs, read_orbit
from psdbound.isolation import (
    HighPass,
    MultipathSeries,
    filter_safety_check,
    isolate_dual_antenna,
    isolate_dual_frequency,
)
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.result import SCHEMA_VERSION, FitResult, _jsonable
from psdbound.spectra import BoundModel
from psdbound.stationarity import (
    THESIS_MAPPING,
    ElevationMapping,
    find_stationary_windows,
    fit_mapping,
)

__all__ = ["run_fit", "THESIS_CUTOFF_HZ", "cutoff_from_map", "cutoff_computed"]

#: The thesis's recommended cutoff for Chicago 2020 (maximum over the year).
THESIS_CUTOFF_HZ = 9.55e-4

_VERSIONED = (
    "numpy", "scipy", "astropy", "statsmodels", "hatanaka", "PyIRI", "matplotlib", "jinja2",
    "dask",
)  # fmt: skip
_MAX_POINTS = 1500  # per arc in the figure data
_MAX_PSD_POINTS = 300  # per window PSD in the figure data

Progress = Callable[[str], None]


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for chunk in iter(lambda: fh.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def _versions() -> dict[str, str]:
    out = {"psdbound": __version__, "python": platform.python_version()}
    for name in _VERSIONED:
        try:
            out[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            out[name] = "not installed"
    return out


def _decimate(n: int, limit: int = _MAX_POINTS) -> slice:
    return slice(None, None, max(1, int(np.ceil(n / limit))))


def _psd_for_figure(f: np.ndarray, s: np.ndarray) -> tuple[list, list]:
    """Log-binned maxima (a faithful upper outline for plotting)."""
    if f.size <= _MAX_PSD_POINTS:
        return f.tolist(), s.tolist()
    edges = np.geomspace(f[0], f[-1] * (1 + 1e-12), _MAX_PSD_POINTS + 1)
    idx = np.clip(np.searchsorted(edges, f, side="right") - 1, 0, _MAX_PSD_POINTS - 1)
    ff, ss = [], []
    for k in np.unique(idx):
        sel = idx == k
        j = np.argmax(s[sel])
        ff.append(float(f[sel][j]))
        ss.append(float(s[sel][j]))
    return ff, ss


def _method(config: FitConfig, n_obs: int) -> str:
    m = config.inputs.method.lower()
    if m == "auto":
        return "da" if n_obs == 2 else "df"
    if m not in ("df", "da"):
        raise InputError(f"--method must be df, da or auto, got {config.inputs.method!r}")
    if m == "da" and n_obs != 2:
        raise InputError(f"--method da needs two observation files (two antennas), got {n_obs}")
    if m == "df" and n_obs not in (1, 2):
        raise InputError(f"--method df needs one observation file, got {n_obs}")
    return m


def cutoff_from_map(lat_deg: float, lon_deg: float) -> tuple[float, dict[str, Any]]:
    """Recommended cutoff of the nearest station of the shipped 2020 cutoff map.

    Parameters
    ----------
    lat_deg, lon_deg : float
        Receiver position, degrees.

    Returns
    -------
    f_c_hz : float
        The nearest station's recommended (maximum) cutoff, Hz.
    info : dict
        Station, its distance (deg of arc), the map's days and settings.
    """
    import json
    from importlib import resources

    from psdbound.ionosphere import MAP_STATIONS, nearest_station

    text = resources.files("psdbound.ionosphere").joinpath("data/cutoff_map_2020.json")
    table = json.loads(text.read_text())
    station, dist_deg = nearest_station(lat_deg, lon_deg, MAP_STATIONS)
    row = next(r for r in table["stations"] if r["name"] == station.name)
    return float(row["recommended_f_c_hz"]), {
        "station": station.name,
        "station_distance_deg": float(dist_deg),
        "map": "psdbound/ionosphere/data/cutoff_map_2020.json",
        "map_days": table["days"],
        "map_note": table["note"],
    }


def cutoff_computed(lat_deg: float, lon_deg: float, year: int) -> tuple[float, dict[str, Any]]:
    """Compute the cutoff for a position (PyIRI, nominal GPS, first Monday of each month).

    Returns the recommended (maximum) f_c in Hz and the station summary.
    """
    from psdbound.ionosphere import select_days, station_cutoffs

    res = station_cutoffs(lat_deg, lon_deg, select_days(year), name="receiver", workers=2)
    summ = res.summary()
    return float(summ["recommended_f_c_hz"]), {"computed": summ}


def _cutoff(config: FitConfig, lat_lon: tuple[float, float] | None, year: int,
            warnings: list[str]):  # fmt: skip
    c = config.cutoff
    src = c.source
    if src == "auto":
        src = "given" if c.f_c_hz is not None else "default"
    if src == "given":
        if c.f_c_hz is None:
            raise InputError("cutoff source 'given' needs --cutoff-hz")
        return float(c.f_c_hz), "given", {}
    if src in ("map", "computed", "default") and lat_lon is None:
        if src != "default":
            raise InputError(f"cutoff source {src!r} needs a receiver position")
    if src == "map":
        f_c, info = cutoff_from_map(*lat_lon)
        return f_c, f"map (nearest station {info['station']})", info
    if src == "computed":
        f_c, info = cutoff_computed(*lat_lon, year)
        return f_c, f"computed (PyIRI, {year})", info
    if src == "default":
        note = ""
        if lat_lon is not None:
            f_map, info = cutoff_from_map(*lat_lon)
            note = (
                f"; the 2020 cutoff map gives {f_map:.3g} Hz (nearest station {info['station']}), "
                "about 10x higher because Lomb-Scargle leakage of the satellite passes sets its "
                "40 dB point - use --cutoff-source map to apply it"
            )
        warnings.append(
            f"no cutoff given: used the thesis's Chicago 2020 value {THESIS_CUTOFF_HZ:g} Hz{note}"
        )
        return THESIS_CUTOFF_HZ, "default (thesis Chicago 2020 maximum)", {}
    raise InputError(f"unknown cutoff source {c.source!r}; use auto, given, map or computed")


def _mapping(config: FitConfig, series: MultipathSeries) -> ElevationMapping:
    m = config.mapping
    if m.kind == "thesis":
        return THESIS_MAPPING
    if m.kind == "fixed":
        return ElevationMapping(m.a, m.b, m.c_deg, "fixed")
    if m.kind == "fit":
        return fit_mapping(series.value_m, series.elevation_deg)
    raise InputError(f"unknown mapping kind {m.kind!r}; use thesis, fixed or fit")


def _validation(config: FitConfig, f_c_hz: float | None, method: str) -> dict[str, Any]:
    if method == "da" or f_c_hz is None:
        return {
            "applicable": False,
            "verdict": "not applicable",
            "reason": "dual-antenna isolation applies no high-pass filter",
        }
    try:
        from psdbound.validation import validate_cutoff  # type: ignore[attr-defined]
    except ImportError:
        return {
            "applicable": False,
            "verdict": "not available",
            "reason": "validation stage absent",
        }
    v = config.validation
    report = validate_cutoff(
        list(v.geometries), cutoff_hz=f_c_hz, rate=v.rate, alpha=v.alpha, threshold=v.threshold
    )
    out = report.to_dict()
    out["applicable"] = True
    out["summary"] = (
        f"{'pass' if report.passed else 'fail'}: largest fraction of multipath power below "
        f"f_c over {', '.join(v.geometries)} (physical convention) vs threshold "
        f"{100 * v.threshold:g} %"
    )
    cases: dict[str, dict[str, Any]] = {}
    for chk in report.expansion:
        h = chk.second
        f_hz = np.asarray(h.orders, dtype=float) * chk.rate.frequency_hz
        keep = slice(0, 2000)
        case = cases.setdefault(
            chk.geometry.label,
            {"label": f"{chk.geometry.label}, rate {chk.rate.name} "
                      f"({chk.rate.frequency_hz:.3g} Hz), alpha {chk.alpha:g}"},
        )  # fmt: skip
        case[chk.convention] = {
            "f_hz": f_hz[keep],
            "power": np.asarray(h.power_rad2)[keep],
            "fraction_below": chk.fraction_below_cutoff,
            "z": chk.z,
        }
    out["figure"] = {"cases": list(cases.values())}
    return out


def run_fit(config: FitConfig, *, progress: Progress | None = None) -> FitResult:
    """Run the whole fit pipeline.

    Parameters
    ----------
    config : FitConfig
        All options (inputs, arcs, cutoff, filter, mapping, stationarity,
        spectra, bound, validation, output).
    progress : callable, optional
        Called with a short message at the start of each stage.

    Returns
    -------
    FitResult
        The result document (bound, cutoff, sampling, mapping, windows,
        validation, warnings, provenance, figure data).

    Raises
    ------
    InputError
        Bad input (files, options); :class:`~psdbound.errors.NoDataError`
        when the data hold no usable arc or window.
    """
    say = progress or (lambda msg: None)
    t_start = time.perf_counter()
    warnings: list[str] = []
    demo = None
    obs_paths = [Path(p) for p in config.inputs.obs]
    nav_path = Path(config.inputs.nav) if config.inputs.nav else None
    if not obs_paths:
        from psdbound.simulate import demo_data

        say("demo data (simulated on first use)")
        demo = demo_data()
        obs_paths = [demo.obs_paths[0]]
        nav_path = demo.nav_path
        config = config.updated("inputs", method="df")
    method = _method(config, len(obs_paths))
    for p in obs_paths:
        if not p.is_file():
            raise InputError("observation file not found", path=p)
    if nav_path is None:
        raise InputError("a navigation (or SP3) file is needed for elevations: give --nav")
    say(f"reading {len(obs_paths)} observation file(s) and {nav_path.name}")
    system = config.inputs.system
    obs: list[Observations] = [read_obs(p, systems=system) for p in obs_paths]
    orbit = read_orbit(nav_path)
    rx = [tuple(x) for x in config.inputs.receiver_xyz_m] or [None] * len(obs)
    interval_s = obs[0].interval_s
    figures: dict[str, Any] = {}
    iso: dict[str, Any] = {}

    if method == "df":
        sig = tuple(config.inputs.signals) or None
        say("arcs (gaps, loss of lock, cycle slips, elevations)")
        arcs = find_arcs(
            obs[0],
            sig,
            system=system,
            orbit=orbit,
            receiver_xyz_m=None if rx[0] is None else np.asarray(rx[0]),
            min_length_s=config.arcs.min_length_s,
            slip_threshold_m=config.arcs.slip_threshold_m,
            elevation_mask_deg=config.arcs.elevation_mask_deg,
        )
        from psdbound.io.geometry import ecef_to_geodetic

        pos = obs[0].header.approx_position_m if rx[0] is None else np.asarray(rx[0])
        lat_lon = None
        if pos is not None:
            lat, lon, _ = ecef_to_geodetic(np.asarray(pos))
            lat_lon = (float(lat), float(lon))
        year = int(str(obs[0].times[0])[:4])
        f_c, f_c_source, f_c_info = _cutoff(config, lat_lon, year, warnings)
        say(f"dual-frequency isolation (high-pass {f_c:.4g} Hz)")
        hp = HighPass(kind=config.filter.kind, order=config.filter.order, edge=config.filter.edge)
        series = isolate_dual_frequency(arcs, f_c, highpass=hp)
        safety = filter_safety_check(series)
        iso = {
            "signals": list(series.signals),
            "scaling": series.scaling,
            "scaling_note": "DF difference / sqrt(2): two independent per-carrier terms",
            "filter": series.meta["filter"],
            "n_arcs": series.n_arcs,
            "arc_breaks": dict(arcs.breaks),
            "short_stretches_dropped": int(sum(arcs.dropped.values())),
            "short_stretches_dropped_s": arcs.dropped_s,
            "arcs_dropped_after_trim": series.meta["arcs_dropped_after_trim"],
            "safety": {
                "removed_below_fc_median": float(np.nanmedian(safety.removed_below)),
                "removed_below_fc_min": float(np.nanmin(safety.removed_below)),
                "removed_above_fc_median": float(np.nanmedian(safety.removed_above)),
                "removed_above_fc_max": float(np.nanmax(safety.removed_above)),
            },
        }
        arcs_fig = [
            {"sat": a.sat, "t0": float(a.t_gps_s[0]), "t1": float(a.t_gps_s[-1]),
             "kept": True, "start_reason": a.start_reason}
            for a in arcs
        ]  # fmt: skip
        # the DF difference before/after filtering, for the longest arc
        k = int(np.argmax([a.duration_s for a in series.arcs()]))
        av = series.arc(k)
        sl = _decimate(av.t_gps_s.size)
        figures["df_filter"] = {
            "sat": av.sats,
            "t_gps_s": av.t_gps_s[sl],
            "unfiltered_m": av.unfiltered_m[sl],
            "filtered_m": (av.value_m / series.scaling)[sl],
        }
    else:
        say("dual-antenna double differences (receiver clocks, geometry, re-referencing)")
        f_c, f_c_source, f_c_info = None, "not applicable (dual-antenna)", {}
        series = isolate_dual_antenna(
            obs[0],
            obs[1],
            orbit,
            signal=config.inputs.da_signal,
            system=system,
            receiver1_xyz_m=None if rx[0] is None else np.asarray(rx[0]),
            receiver2_xyz_m=None if len(rx) < 2 or rx[1] is None else np.asarray(rx[1]),
            min_length_s=min(config.arcs.min_length_s, 600.0),
            elevation_mask_deg=config.arcs.elevation_mask_deg,
        )
        m = series.meta
        iso = {
            "signals": list(series.signals),
            "scaling": series.scaling,
            "scaling_note": "double difference / 2: four independent per-signal terms",
            "n_arcs": series.n_arcs,
            "baseline_m": m.get("baseline_m"),
            "reference_periods": m.get("reference_periods"),
            "receiver_clock": m.get("receiver_clock"),
        }
        warnings.append(
            "dual-antenna differences cancel the multipath common to both antennas "
            f"({m.get('baseline_m', float('nan')):.1f} m baseline): the bound may be "
            "optimistic for a single antenna; the dual-frequency method is preferred"
        )
        arcs_fig = [
            {"sat": a.sats, "t0": float(a.t_gps_s[0]), "t1": float(a.t_gps_s[-1]),
             "kept": True, "start_reason": ""}
            for a in series.arcs()
        ]  # fmt: skip
    figures["arcs"] = arcs_fig
    figures["t_ref_gps_s"] = float(obs[0].t_gps_s[0])

    say("elevation mapping and stationarity windows (Levene, then K-S)")
    mapping = _mapping(config, series)
    st = config.stationarity
    windows = find_stationary_windows(
        series,
        mapping=mapping,
        alpha=st.alpha,
        p_slide=st.p_slide,
        p_trim=st.p_trim,
        min_length_s=st.min_window_s,
        center=st.levene_center,
    )
    if len(windows) == 0:
        raise NoDataError(
            f"no stationary window of at least {st.min_window_s:g} s in {series.n_arcs} arcs "
            f"({windows.n_tests} tests)"
        )
    say(f"{len(windows)} windows: PSDs ({config.spectra.estimator}) and bound")
    res = BoundModel(windows, estimator=config.spectra.estimator, **config.spectra.options).fit(
        objective=config.bound.objective, target=config.bound.target, level=config.bound.level
    )
    b = res.bound

    say("cutoff validation")
    validation = _validation(config, f_c, method)
    if validation.get("verdict") == "fail":
        warnings.append(
            "cutoff validation failed: the filter removes more multipath power than the "
            f"threshold {100 * config.validation.threshold:g} % for some geometry"
        )
    if windows.uncovered_s > 0:
        warnings.append(
            f"{windows.uncovered_s / 60:.1f} min of data never tested stationary "
            f"({len(windows.uncovered)} stretches) and are not covered by the bound"
        )
    if method == "df" and iso["short_stretches_dropped"]:
        warnings.append(
            f"{iso['short_stretches_dropped']} tracking stretches shorter than "
            f"{config.arcs.min_length_s / 60:g} min dropped "
            f"({iso['short_stretches_dropped_s'] / 3600:.2f} h)"
        )
    if b.sigma_wn_m == 0.0:
        warnings.append(
            f"no white-noise floor resolved at {interval_s:g} s sampling (Nyquist "
            f"{0.5 / interval_s:.4g} Hz): sigma_WN = 0; the bound says nothing above Nyquist"
        )

    # figure data: mapped series with windows, every window PSD under the bound
    mapped = []
    for k, (lo, hi) in enumerate(series._bounds()):
        sl = _decimate(hi - lo)
        mapped.append(
            {"arc": k, "sats": series.arc_sats[k],
             "t_gps_s": series.t_gps_s[lo:hi][sl], "mapped_m": windows.mapped_m[lo:hi][sl],
             "elevation_deg": series.elevation_deg[lo:hi][sl]}
        )  # fmt: skip
    figures["mapped"] = mapped
    psd_fig = []
    for p in res.psds:
        ff, ss = _psd_for_figure(np.asarray(p.f_hz), np.asarray(p.psd_m2_hz))
        psd_fig.append({"f_hz": ff, "psd_m2_hz": ss})
    figures["psds"] = psd_fig
    f_grid = np.geomspace(b.f_min_hz, 0.5 / interval_s, 400)
    figures["bound_curve"] = {"f_hz": f_grid, "psd_m2_hz": b.psd(f_grid)}
    if "figure" in f_c_info:
        figures["cutoff_envelope"] = f_c_info["figure"]
    if "figure" in validation:
        figures["jacobi_anger"] = validation.pop("figure")

    per_window = [
        {"arc": w.arc_id, "sats": w.sats, "t_start_gps_s": w.t_start_gps_s,
         "t_stop_gps_s": w.t_stop_gps_s, "n": w.n, "margin": float(mg),
         "levene_p": w.levene_p, "ks_p": w.ks_p}
        for w, mg in zip(windows.windows, b.margins, strict=True)
    ]  # fmt: skip
    inputs = [
        {"role": role, "name": p.name, "path": str(p), "sha256": _sha256(p)}
        for role, p in [*(("obs", q) for q in obs_paths), ("nav", nav_path)]
    ]
    t_all = series.t_gps_s
    data = {
        "schema_version": SCHEMA_VERSION,
        "method": method.upper(),
        "bound": {
            "sigma_gm_m": b.sigma_gm_m,
            "tau_s": b.tau_s,
            "sigma_wn_m": b.sigma_wn_m,
            "n_wn_two_sided_m2_hz": b.n_wn_two_sided_m2_hz,
            "white_noise_convention": (
                "sigma_wn_m is the per-sample standard deviation at dt_s; the one-sided "
                "white PSD level is 2 sigma_wn^2 dt (m^2/Hz); the thesis's two-sided N_WN = "
                "sigma_wn^2 dt"
            ),
            "psd_convention": "one-sided, per hertz, sampled (aliased) AR(1) + white noise",
            "dt_s": b.dt_s,
            "total_variance_m2": b.total_variance_m2,
            "applies_to": "elevation-mapped error: multiply sigma by m(el) for elevation el",
            "objective": b.objective,
            "objective_value_m2": b.objective_value,
            "target": b.target,
            "level": b.level,
            "estimator": res.estimator,
            "estimator_options": res.estimator_options,
            "min_margin": float(b.margins.min()),
            "median_margin": float(np.median(b.margins)),
            "gap_db_median": b.gap_db_median,
            "gap_db_p05": b.gap_db_p05,
            "band_hz": [b.f_min_hz, b.f_max_hz],
            "tau_grid_s": b.tau_grid_s,
            "objective_grid_m2": b.objective_grid,
        },
        "cutoff": {
            "f_c_hz": f_c,
            "source": f_c_source,
            "tau_c_min": None if f_c is None else 1.0 / f_c / 60.0,
            **{k: v for k, v in f_c_info.items() if k != "figure"},
        },
        "sampling": {"interval_s": interval_s, "nyquist_hz": 0.5 / interval_s},
        "mapping": mapping.as_dict(),
        "isolation": iso,
        "data_span": {
            "start_gps_s": float(t_all.min()),
            "stop_gps_s": float(t_all.max()),
            "n_samples": int(t_all.size),
            "n_arcs": series.n_arcs,
        },
        "windows": {
            "count": len(windows),
            "total_duration_s": windows.total_duration_s,
            "never_stationary_s": windows.uncovered_s,
            "never_stationary": [list(u) for u in windows.uncovered],
            "n_tests": windows.n_tests,
            "params": windows.params,
            "per_window": per_window,
        },
        "validation": validation,
        "warnings": warnings,
        "provenance": {
            "inputs": inputs,
            "versions": _versions(),
            "configuration": config.to_dict(),
            "created_utc": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
            "platform": platform.platform(),
            "run_time_s": time.perf_counter() - t_start,
        },
        "figures": figures,
    }
    if demo is not None:
        meta = demo.truth_meta()
        mp = meta["scenario"]["multipath"]
        data["demo"] = {
            "note": "simulated demo data (antenna A, dual-frequency); the truth model is "
            "known: compare the bound with the injected multipath",
            "injected": mp,
            "seed": meta["seed"],
            "digest": meta["digest"],
        }
    return FitResult(_jsonable(data))
