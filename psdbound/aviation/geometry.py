"""The VPL of a satellite geometry over time (seed 004 section 4).

:func:`sky_over` evaluates an orbit (a file read by :func:`psdbound.io.read_orbit`, or
:func:`nominal_orbit`) at a receiver and epochs, keeping the satellites above an elevation
mask (:class:`Sky`); :func:`vpl_series` applies :func:`~psdbound.aviation.budget.error_budget`
and :func:`~psdbound.aviation.budget.vpl` (seed 004 eqs. 10-13) at every epoch
(:class:`VplSeries`). Epochs with fewer than 4 satellites above the mask, or a geometry that
does not fix position and clock, get a NaN VPL and count as unavailable, never dropped.
"""

from __future__ import annotations

import contextlib
import inspect
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.aviation.budget import error_budget, los_from_az_el, multipliers, vpl
from psdbound.aviation.standards import P_EPH
from psdbound.common.atomic import atomic_write_bytes
from psdbound.errors import InputError
from psdbound.io.geometry import OrbitSource, satellite_azel
from psdbound.io.navigation import Navigation
from psdbound.io.nominal import nominal_elements, nominal_navigation
from psdbound.io.timescales import calendar_to_gps_s, gps_s_to_datetime64
from psdbound.results import write_json

__all__ = [
    "SEED004_START_GPS_S",
    "Sky",
    "VplSeries",
    "nominal_orbit",
    "sky_over",
    "vpl_series",
    "write_vpl_series",
]

#: 2009-01-01 00:00:00 (GPS time label), the first epoch of seed 004's simulations, GPS seconds.
SEED004_START_GPS_S = float(calendar_to_gps_s(2009, 1, 1, 0, 0, 0.0))
_BUDGET_OPTIONS = {
    name: p.default
    for name, p in inspect.signature(error_budget).parameters.items()
    if p.kind is inspect.Parameter.KEYWORD_ONLY and name not in ("n_receivers", "x_air_m")
}


def _label(t_gps_s: float) -> str:
    return str(gps_s_to_datetime64(t_gps_s).astype("datetime64[s]")).replace("T", " ")


def nominal_orbit(
    systems: str = "GE", *, start_gps_s: float = SEED004_START_GPS_S, duration_s: float = 86400.0
) -> Navigation:
    """Broadcast records of the nominal GPS / Galileo constellations over a span.

    The constellations of :mod:`psdbound.io.nominal` (GPS 24-slot, Galileo Walker 24/3/1)
    as :func:`~psdbound.io.nominal.nominal_navigation` records, zero satellite clocks.

    Parameters
    ----------
    systems : {"G", "E", "GE"}, default "GE"
    start_gps_s : float, default :data:`SEED004_START_GPS_S`
        Start of the span, GPS seconds.
    duration_s : float, default 86400
        Length of the span, seconds (> 0).

    Returns
    -------
    Navigation
        Accepted by :func:`sky_over`.
    """
    if not systems or set(systems) - set("GE") or duration_s <= 0:
        raise InputError(f"systems must be 'G', 'E' or 'GE' (got {systems!r}), duration > 0 s")
    stop = start_gps_s + duration_s
    return nominal_navigation(start_gps_s, stop, systems=systems, clock_seed=None)


@dataclass(frozen=True, eq=False)
class Sky:
    """Azimuths and elevations of the satellites above a mask, per epoch.

    Attributes
    ----------
    t_gps_s : ndarray, shape (n_epoch,)
        Epochs, GPS seconds.
    sats : tuple of str
        Satellite ids, the columns.
    azimuth_deg, elevation_deg : ndarray, shape (n_epoch, n_sat)
        Degrees; NaN below the mask or without an orbit position.
    receiver_xyz_m : ndarray, shape (3,)
        Receiver ECEF position, metres.
    elevation_mask_deg : float
        Degrees.
    source : str
        The orbit: file name or description of the nominal constellations.
    """

    t_gps_s: NDArray[np.float64]
    sats: tuple[str, ...]
    azimuth_deg: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    receiver_xyz_m: NDArray[np.float64]
    elevation_mask_deg: float
    source: str

    @property
    def n_sats(self) -> NDArray[np.int64]:
        """Satellites above the mask per epoch, count."""
        return np.isfinite(self.elevation_deg).sum(axis=1)


def sky_over(
    orbit: OrbitSource,
    receiver_xyz_m: ArrayLike,
    t_gps_s: ArrayLike,
    *,
    systems: str = "GE",
    elevation_mask_deg: float = 5.0,
) -> Sky:
    """Satellites of ``systems`` above the mask at each epoch.

    Parameters
    ----------
    orbit : OrbitSource
        Anything :func:`psdbound.io.satellite_azel` accepts that also has
        ``satellites`` (a read navigation/SP3 file, :func:`nominal_orbit`).
    receiver_xyz_m : array_like, shape (3,)
        Receiver ECEF position, metres.
    t_gps_s : array_like, shape (n_epoch,)
        Epochs, GPS seconds.
    systems : str, default "GE"
        System letters to keep.
    elevation_mask_deg : float, default 5
        Satellites below this elevation (degrees, in [0, 90)) are NaN.

    Returns
    -------
    Sky
    """
    rx = np.asarray(receiver_xyz_m, dtype=float).reshape(-1)
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=float))
    if rx.size != 3 or not np.isfinite(rx).all() or not 6.0e6 < np.linalg.norm(rx) < 6.5e6:
        raise InputError("receiver_xyz_m must be an ECEF position near the Earth's surface, m")
    if t.ndim != 1 or t.size == 0 or not np.isfinite(t).all():
        raise InputError("t_gps_s must be a non-empty 1-D array of finite GPS seconds")
    if not 0.0 <= elevation_mask_deg < 90.0:
        raise InputError(f"elevation mask must be in [0, 90) deg, got {elevation_mask_deg}")
    sats = tuple(s for s in getattr(orbit, "satellites", ()) if s[0] in systems)
    if not sats:
        raise InputError(f"the orbit has no satellite of systems {systems!r}")
    az, el = np.full((2, t.size, len(sats)), np.nan)
    for j, sat in enumerate(sats):
        az[:, j], el[:, j] = satellite_azel(orbit, sat, t, rx)
    below = ~((el >= elevation_mask_deg) & (el > 0.0))  # NaN (no orbit) is below
    az[below], el[below] = np.nan, np.nan
    path = getattr(orbit, "path", None)
    if str(path) == "<nominal>":
        letters = sorted({s[0] for s in sats}, reverse=True)  # G before E
        src = "nominal: " + "; ".join(nominal_elements(c).description for c in letters)
    else:
        src = str(path) if path is not None else type(orbit).__name__
    return Sky(t, sats, az, el, rx, float(elevation_mask_deg), src)


@dataclass(frozen=True, eq=False)
class VplSeries:
    """Fault-free and ephemeris VPLs of a geometry over time (seed 004 eqs. 10-12).

    Attributes
    ----------
    t_gps_s : ndarray, shape (n_epoch,)
        Epochs, GPS seconds.
    n_sats : ndarray of int, shape (n_epoch,)
        Satellites above the mask, count.
    vpl_h0_m, vpl_eph_m, vpl_m : ndarray, shape (n_epoch,)
        ``VPL_H0``, ``VPL_eph`` and their maximum, metres; NaN where unavailable.
    elevation_mask_deg, source, receiver_xyz_m
        Those of the :class:`Sky`: degrees, the orbit, ECEF metres.
    options : dict
        Every budget and VPL option used (names carry their units), with
        ``multipliers``: the value and source of ``K_ffmd`` and ``K_md_e``.
    """

    t_gps_s: NDArray[np.float64]
    n_sats: NDArray[np.int64]
    vpl_h0_m: NDArray[np.float64]
    vpl_eph_m: NDArray[np.float64]
    vpl_m: NDArray[np.float64]
    elevation_mask_deg: float
    source: str
    receiver_xyz_m: NDArray[np.float64]
    options: dict[str, Any] = field(default_factory=dict)

    @property
    def unavailable(self) -> NDArray[np.bool_]:
        """Epochs without a VPL (< 4 satellites or singular geometry)."""
        return ~np.isfinite(self.vpl_m)

    @property
    def singular(self) -> NDArray[np.bool_]:
        """Epochs with >= 4 satellites whose geometry does not fix position and clock."""
        return self.unavailable & (self.n_sats >= 4)

    def availability(self, val_m: float) -> float:
        """Fraction of all epochs (unavailable ones count as not) with VPL <= ``val_m`` (m, > 0)."""
        if not val_m > 0:
            raise InputError(f"the alert limit must be > 0 m, got {val_m}")
        return float(np.mean(self.vpl_m <= val_m))  # NaN compares False

    def _stats(self, x: NDArray[np.float64]) -> dict[str, float | None]:
        f = x[np.isfinite(x)]
        if f.size == 0:
            return dict.fromkeys(("min", "median", "p95", "max"))
        q = np.percentile(f, [0, 50, 95, 100]).tolist()
        return dict(zip(("min", "median", "p95", "max"), q, strict=True))

    def summary(self, val_m: float | None = None) -> str:
        """Text: epochs, satellites, VPL statistics, unavailable epochs, availability at val_m m."""
        t, n = self.t_gps_s, self.n_sats
        step = f", step {np.median(np.diff(t)):g} s" if t.size > 1 else ""
        lines = [
            f"VPL over {t.size} epochs, {_label(t[0])} to {_label(t[-1])} GPS time{step}",
            f"orbit: {self.source}",
            f"satellites above {self.elevation_mask_deg:g} deg: min {n.min()}, "
            f"median {np.median(n):g}, max {n.max()}",
        ]
        curves = (("VPL", self.vpl_m), ("VPL_H0", self.vpl_h0_m), ("VPL_eph", self.vpl_eph_m))
        for name, x in curves:
            s = self._stats(x)
            text = ", ".join(f"{k} {v:.3f}" for k, v in s.items()) if s["min"] is not None else ""
            lines.append(f"{name + ' m:':<12} {text or 'no epoch with a VPL'}")
        bad = np.flatnonzero(self.unavailable)
        lines.append(f"unavailable (< 4 satellites or singular geometry): {bad.size} epoch(s)")
        for i in bad[:10]:
            why = "singular geometry" if self.singular[i] else f"{n[i]} satellite(s)"
            lines.append(f"  {_label(t[i])}: {why}")
        if bad.size > 10:
            lines.append(f"  ... and {bad.size - 10} more")
        if val_m is not None:
            a = 100.0 * self.availability(val_m)
            lines.append(f"availability at VAL = {val_m:g} m: {a:.2f} % of epochs")
        return "\n".join(lines)

    def to_dict(self, val_m: float | None = None) -> dict[str, Any]:
        """JSON-ready content, NaN as null, units in the key names (``val_m`` as in summary)."""

        def lst(x: NDArray[np.float64]) -> list[float | None]:
            return [float(v) if np.isfinite(v) else None for v in x]  # NaN is not JSON

        stats = {f"vpl_{k}_m": v for k, v in self._stats(self.vpl_m).items()}
        out: dict[str, Any] = {
            "orbit": self.source,
            "receiver_xyz_m": [float(v) for v in self.receiver_xyz_m],
            "elevation_mask_deg": self.elevation_mask_deg,
            "options": dict(self.options),
            "n_epochs": int(self.t_gps_s.size),
            "n_unavailable": int(self.unavailable.sum()),
            **stats,
            "t_gps_s": [float(v) for v in self.t_gps_s],
            "time_gps": [_label(v).replace(" ", "T") for v in self.t_gps_s],
            "n_sats": [int(v) for v in self.n_sats],
            **{k: lst(getattr(self, k)) for k in ("vpl_h0_m", "vpl_eph_m", "vpl_m")},
            "singular": [bool(v) for v in self.singular],
        }
        if val_m is not None:
            out["val_m"] = float(val_m)
            out["availability"] = self.availability(val_m)
        return out


def vpl_series(
    sky: Sky,
    *,
    k_md_e: float | None,
    n_receivers: int = 3,
    x_air_m: float = 5000.0,
    p_eph: float = P_EPH.value,
    k_ffmd: float | None = None,
    **budget_options: Any,
) -> VplSeries:
    """VPL_H0, VPL_eph and VPL at every epoch of a :class:`Sky` (the budget of its satellites).

    Parameters
    ----------
    sky : Sky
    n_receivers : int, default 3
        Reference receivers ``M``.
    x_air_m : float, default 5000
        User to reference distance, metres.
    p_eph : float, default 0.00018
        Ephemeris decorrelation parameter, m/m.
    k_md_e : float
        Ephemeris missed-detection multiplier (required; see
        :func:`~psdbound.aviation.budget.vpl`).
    k_ffmd : float, optional
        Override the tabulated fault-free multiplier.
    **budget_options
        Other keyword options of :func:`~psdbound.aviation.budget.error_budget`
        (``process``, ``tau_gnd_s``, ``gad``, ``rho``, ...).

    Returns
    -------
    VplSeries
    """
    unknown = sorted(set(budget_options) - set(_BUDGET_OPTIONS))
    if unknown:
        raise InputError(f"unknown budget option(s) {unknown}; known: {sorted(_BUDGET_OPTIONS)}")
    used_k = multipliers(n_receivers=n_receivers, k_ffmd=k_ffmd, k_md_e=k_md_e)
    opts = {"n_receivers": n_receivers, "x_air_m": x_air_m, **budget_options}
    error_budget([45.0], **opts)  # validate the options once, whatever the geometry
    kw = dict(n_receivers=n_receivers, k_ffmd=k_ffmd, k_md_e=k_md_e, x_air_m=x_air_m, p_eph=p_eph)
    n = sky.n_sats
    h0, eph = np.full(n.size, np.nan), np.full(n.size, np.nan)
    for i in np.flatnonzero(n >= 4):
        vis = np.isfinite(sky.elevation_deg[i])
        el, az = sky.elevation_deg[i, vis], sky.azimuth_deg[i, vis]
        total = error_budget(el, **opts).total
        with contextlib.suppress(InputError):  # options checked above: a singular geometry
            h0[i], eph[i] = vpl(los_from_az_el(az, el), total, **kw)
    used = {**_BUDGET_OPTIONS, **opts, "p_eph": p_eph, "multipliers": used_k}
    t, rx, mask = sky.t_gps_s.copy(), sky.receiver_xyz_m.copy(), sky.elevation_mask_deg
    return VplSeries(t, n, h0, eph, np.maximum(h0, eph), mask, sky.source, rx, used)


def write_vpl_series(
    series: VplSeries, out: str | Path, *, val_m: float | None = None
) -> list[Path]:
    """Write ``vpl.json``, ``vpl.png`` and ``vpl.html`` into the folder ``out``, each atomically.

    The figure (:func:`psdbound.reports.figures_aviation.fig_vpl`, the
    report's style): VPL_H0, VPL_eph and VPL (m) against time (h) with
    ``val_m``, an optional vertical alert limit in metres (also adds the
    availability to the JSON), and below it, in a panel of its own, the
    satellites above the mask (count). Returns the three paths.
    """
    from psdbound.reports.figures_aviation import fig_vpl
    from psdbound.reports.render import rasterize

    doc = series.to_dict(val_m=val_m)
    png = rasterize("vertical protection level", fig_vpl(doc)).png
    from psdbound.reports.page import write_page

    folder = Path(out)
    png_path = atomic_write_bytes(folder / "vpl.png", png)
    json_path = write_json(folder / "vpl.json", {"vpl": doc})
    html = write_page(
        folder / "vpl.html",
        command="budget",
        title="vertical protection level over time",
        json_name="vpl.json",
        lines=series.summary(val_m=val_m).splitlines(),
        figures=[("VPL_H0, VPL_eph and VPL over time; satellites above the mask.", png, "vpl.png")],
    )
    return [json_path, png_path, html]
