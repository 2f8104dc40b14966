"""Slant ionospheric delay of every satellite in view (docs/method/cutoff.rst, step 1).

For a static station, a date and an orbit source, :func:`simulate_slant_delay`
gives the first-order ionospheric group delay (m) of every satellite above an
elevation mask, every ``sampling_s`` (12 s) over one sidereal day starting at
00:00 UTC::

    delay = 40.3 * STEC / f^2,   STEC = integral of n_e along the line of sight

The electron density is PyIRI's, evaluated once per day on a grid and
interpolated (:mod:`psdbound.ionosphere.iri`, with the model decisions).
Integration (decisions, with the evidence in the tests and the closing note
of issue #4):

* **Line of sight** (``method="line-of-sight"``, default): spherical Earth of
  the station's geocentric radius; the point of the ray at altitude ``h``
  lies at central angle ``psi = 90 deg - e - asin(R cos e / (R + h))`` along
  the azimuth, and ``ds/dh = (R + h) / sqrt((R + h)^2 - R^2 cos^2 e)``; the
  TEC integral is a trapezoid over the altitude nodes. Nodes fixed in
  altitude make the quadrature error a smooth function of the geometry (no
  spurious high-frequency content).
* **Thin shell** (``method="thin-shell"``): vertical TEC at the pierce point
  on a shell at :data:`DEFAULT_SHELL_HEIGHT_KM` (350 km) times the obliquity
  factor ``1 / sqrt(1 - (R cos e / (R + H))^2)``.
* **Ray sampling**: rays are integrated every ``ray_stride`` (5) epochs,
  i.e. every 60 s, and at each arc's last epoch; a cubic spline in time
  along the arc fills the 12 s epochs (differences below 1 mm against
  integrating every epoch).
* **Time**: epochs are GPS seconds; UT is taken as ``t - t(00:00 UTC)``.

:func:`slant_tec_direct` integrates one ray with PyIRI evaluated at every
ray point, the reference the gridded interpolation is checked against.
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.constants import SIDEREAL_DAY_S
from psdbound.errors import InputError, NoDataError
from psdbound.io.geometry import OrbitSource, geodetic_to_ecef, satellite_azel
from psdbound.io.timescales import calendar_to_gps_s, utc_to_gps_s
from psdbound.ionosphere.constellation import nominal_constellation
from psdbound.ionosphere.iri import (
    DEFAULT_F107_SFU,
    DEFAULT_UT_STEP_H,
    GRID_MARGIN_DEG,
    IRI_MODELS,
    UT_PAD,
    HorizontalGrid,
    altitude_nodes_km,
    central_angle_rad,
    destination_point,
    interpolate_layer,
    parse_date,
    pyiri_density,
)
from psdbound.ionosphere.names import (
    DEFAULT_SHELL_HEIGHT_KM,
    FREQUENCIES_HZ,
    METHODS,
)
from psdbound.ionosphere.stations import validate_station

__all__ = [
    "DEFAULT_MARGIN_S",
    "DEFAULT_SHELL_HEIGHT_KM",
    "FREQUENCIES_HZ",
    "METHODS",
    "SlantDelay",
    "delay_factor",
    "simulate_slant_delay",
    "slant_tec_direct",
]

#: Simulated time beyond one sidereal day, s (room for gap-aligned day windows).
DEFAULT_MARGIN_S = 12 * 3600.0

_K_IONO = 40.3  # m^3 s^-2: first-order delay = K * TEC / f^2
_TECU = 1e16


@dataclass(frozen=True, eq=False)
class SlantDelay:
    """Simulated slant ionospheric delays of one station and day.

    Attributes
    ----------
    lat_deg, lon_deg, height_m : float
        Station position (geodetic).
    date : str
        Day simulated, ``YYYY-MM-DD`` (UTC).
    t_gps_s : ndarray of float64, shape (n_epoch,)
        Epochs, GPS seconds, every ``sampling_s`` from 00:00 UTC over one
        sidereal day plus a margin (``info["duration_s"]``).
    sats : tuple of str
        Satellites above the mask at least once.
    delay_m : ndarray of float64, shape (n_sat, n_epoch)
        Ionospheric group delay, m, at the chosen frequency (or of the
        frequency difference); NaN where the satellite is below the mask.
    elevation_deg, azimuth_deg : ndarray of float64, shape (n_sat, n_epoch)
        Satellite elevation and azimuth, degrees (all epochs).
    info : dict
        Settings and provenance: F10.7, IRI model, method, orbit source,
        frequencies, mask, altitude range, shell height.
    """

    lat_deg: float
    lon_deg: float
    height_m: float
    date: str
    t_gps_s: NDArray[np.float64]
    sats: tuple[str, ...]
    delay_m: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    azimuth_deg: NDArray[np.float64]
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def sampling_s(self) -> float:
        """Sampling interval, s."""
        return float(self.info["sampling_s"])

    def series(self, sat: str) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Epochs and delays of one satellite where it is above the mask.

        Parameters
        ----------
        sat : str
            Satellite id.

        Returns
        -------
        t_gps_s, delay_m : ndarray of float64
            Times (GPS seconds) and delays (m).
        """
        j = self.sats.index(sat)
        ok = np.isfinite(self.delay_m[j])
        return self.t_gps_s[ok], self.delay_m[j, ok]


def delay_factor(frequency_hz: float, second_frequency_hz: float | None = None) -> float:
    """Return the metres of delay per electron/m^2 of slant TEC (of the pair's difference).

    Parameters
    ----------
    frequency_hz : float
        Carrier frequency, Hz.
    second_frequency_hz : float, optional
        A second carrier, Hz: the factor of the two carriers' difference,
        ``40.3 |1/f_1^2 - 1/f_2^2|`` (what a dual-frequency series holds).

    Returns
    -------
    float
        m^3 (metres per electron/m^2).

    Raises
    ------
    InputError
        A frequency that is not positive.
    """
    if frequency_hz <= 0 or (second_frequency_hz is not None and second_frequency_hz <= 0):
        raise InputError("carrier frequencies must be positive (Hz)")
    k = _K_IONO / frequency_hz**2
    if second_frequency_hz is not None:
        k = abs(k - _K_IONO / second_frequency_hz**2)
    return k


def _check_options(
    method: str, iri_model: str, f107_sfu: float, mask_deg: float, sampling_s: float
) -> None:
    if method not in METHODS:
        raise InputError(f"unknown slant method {method!r}; expected one of {', '.join(METHODS)}")
    if iri_model not in IRI_MODELS:
        raise InputError(
            f"unknown IRI model {iri_model!r}; expected one of {', '.join(IRI_MODELS)}"
        )
    if not np.isfinite(f107_sfu) or not 50.0 <= f107_sfu <= 400.0:
        raise InputError(f"F10.7 = {f107_sfu} sfu is outside the plausible range 50-400 sfu")
    if not np.isfinite(mask_deg) or not 0.0 <= mask_deg < 90.0:
        raise InputError(f"elevation mask {mask_deg} deg is out of range: expected 0 <= mask < 90")
    if not np.isfinite(sampling_s) or sampling_s <= 0:
        raise InputError(f"sampling interval {sampling_s} s must be positive")


def _check_altitudes(alt_range_km: tuple[float, float]) -> None:
    """Refuse an altitude range (km) that is not increasing and non-negative."""
    if not alt_range_km[0] < alt_range_km[1] or alt_range_km[0] < 0:
        raise InputError(f"altitude range {alt_range_km} km must be increasing and non-negative")


def _n_ut(ut_step_h: float) -> int:
    """Return the number of UT nodes a day of ``ut_step_h`` hours holds (it must divide 24)."""
    n_ut = int(round(24.0 / ut_step_h))
    if abs(n_ut * ut_step_h - 24.0) > 1e-9:
        raise InputError(f"ut_step_h = {ut_step_h} h must divide 24 h")
    return n_ut


def _day_epochs(
    day: _dt.date, sampling_s: float, duration_s: float
) -> tuple[float, NDArray[np.float64]]:
    """Return 00:00 UTC of ``day`` and the epochs from it, GPS seconds."""
    t0 = float(utc_to_gps_s(calendar_to_gps_s(day.year, day.month, day.day, 0, 0, 0.0))[0])
    n_ep = int(np.ceil(duration_s / sampling_s - 1e-9))
    return t0, t0 + sampling_s * np.arange(n_ep)


def _in_view(
    orbit: OrbitSource,
    satellites: tuple[str, ...] | list[str] | None,
    t: NDArray[np.float64],
    rx: NDArray[np.float64],
    elevation_mask_deg: float,
    day: _dt.date,
    lat_lon: tuple[float, float],
    source: str,
) -> tuple[list[str], NDArray[np.float64], NDArray[np.float64]]:
    """Return the satellites above the mask at some epoch, their elevations and azimuths, deg."""
    where = f"{lat_lon[0]:.2f} {lat_lon[1]:.2f} on {day.isoformat()} (orbit: {source})"
    sats_all = tuple(satellites) if satellites is not None else tuple(orbit.satellites)
    kept, els, azs, any_position = [], [], [], False
    for sat in sats_all:
        az, el = satellite_azel(orbit, sat, t, rx)
        any_position |= bool(np.any(np.isfinite(el)))
        if np.any(el >= elevation_mask_deg):
            kept.append(sat)
            els.append(el)
            azs.append(az)
    if not any_position:
        raise NoDataError(
            f"the orbit source gives no satellite position on {day.isoformat()}; "
            f"does it cover that day? ({source})"
        )
    if not kept:
        raise NoDataError(
            f"no satellite rises above the {elevation_mask_deg:g} deg elevation mask at {where}"
        )
    return kept, np.array(els), np.array(azs)


@dataclass(frozen=True)
class _Model:
    """The ionosphere model of a run: profile, altitude nodes (km), grid, UT nodes (h)."""

    method: str
    iri_model: str
    f107_sfu: float
    alt_km: NDArray[np.float64]
    shell_height_km: float
    grid_size: int
    ut_step_h: float
    n_ut: int


def _layer_fields(
    day: _dt.date,
    lat: float,
    lon: float,
    min_el_deg: float,
    radius_m: float,
    m: _Model,
) -> tuple[NDArray[np.float64], NDArray[np.float64], HorizontalGrid]:
    """Return the density (el/m^3) or vertical TEC (el/m^2) fields, layer heights (km), grid."""
    mask_eff = np.radians(max(min_el_deg, 0.0))
    h_top = m.alt_km[-1] if m.method == "line-of-sight" else m.shell_height_km
    psi_max = np.degrees(central_angle_rad(radius_m, np.array(h_top * 1e3), np.array(mask_eff)))
    grid = HorizontalGrid(lat, lon, float(psi_max) + GRID_MARGIN_DEG, m.grid_size)
    ut_nodes = m.ut_step_h * np.arange(m.n_ut)
    lon_g, lat_g = grid.lon_deg.ravel(), grid.lat_deg.ravel()
    edp = pyiri_density(
        day, ut_nodes, lon_g, lat_g, m.alt_km, m.f107_sfu, m.iri_model
    )  # (n_ut, n_alt, n_grid), el/m^3
    if m.method == "thin-shell":
        vtec = np.trapezoid(edp, m.alt_km * 1e3, axis=1)  # (n_ut, n_grid), el/m^2
        fields = vtec.reshape(m.n_ut, 1, m.grid_size, m.grid_size)
        layer_h_km = np.array([m.shell_height_km])
    else:
        fields = edp.reshape(m.n_ut, m.alt_km.size, m.grid_size, m.grid_size)
        layer_h_km = m.alt_km
    return fields, layer_h_km, grid


def _slant_tec(
    fields: NDArray[np.float64],
    layer_h_km: NDArray[np.float64],
    grid: HorizontalGrid,
    ut_idx: NDArray[np.float64],
    radius_m: float,
    el_r: NDArray[np.float64],
    az_r: NDArray[np.float64],
    m: _Model,
) -> NDArray[np.float64]:
    """Return the slant TEC (el/m^2) of rays at elevations and azimuths ``el_r``, ``az_r`` (rad)."""
    values = np.empty((layer_h_km.size, el_r.size))
    for i, h in enumerate(layer_h_km):
        values[i] = interpolate_layer(fields[:, i], grid, ut_idx, radius_m, h * 1e3, el_r, az_r)
    if m.method == "thin-shell":
        h = m.shell_height_km * 1e3
        obliq = 1.0 / np.sqrt(1.0 - (radius_m * np.cos(el_r) / (radius_m + h)) ** 2)
        return values[0] * obliq
    r_h = radius_m + m.alt_km[:, None] * 1e3
    ds_dh = r_h / np.sqrt(r_h**2 - (radius_m * np.cos(el_r)[None, :]) ** 2)
    return np.trapezoid(values * ds_dh, m.alt_km * 1e3, axis=0)


def _ray_tec(
    el_deg: NDArray[np.float64],
    az_deg: NDArray[np.float64],
    visible: NDArray[np.bool_],
    t_day_s: NDArray[np.float64],
    radius_m: float,
    layers: tuple[NDArray[np.float64], NDArray[np.float64], HorizontalGrid],
    ray_stride: int,
    m: _Model,
) -> tuple[NDArray[np.float64], NDArray[np.intp], list[tuple[int, int, int, int, int]]]:
    """Return the slant TEC (el/m^2) at the ray nodes, their epoch indices and the arcs."""
    fields, layer_h_km, grid = layers
    # ray integrals on the visible samples every `ray_stride` epochs (plus each
    # arc's last epoch), then a cubic spline in time along each arc
    (js, ks), arcs = _ray_nodes(visible, ray_stride)
    el_r = np.radians(el_deg[js, ks])
    az_r = np.radians(az_deg[js, ks])
    ut_idx = np.mod(t_day_s[ks] / 3600.0, 24.0) / m.ut_step_h + UT_PAD
    return _slant_tec(fields, layer_h_km, grid, ut_idx, radius_m, el_r, az_r, m), ks, arcs


def _along_arcs(
    stec: NDArray[np.float64],
    ks: NDArray[np.intp],
    arcs: list[tuple[int, int, int, int, int]],
    shape: tuple[int, ...],
    k_delay: float,
) -> NDArray[np.float64]:
    """Return the delay (m) at every epoch of each arc: a cubic spline through its ray nodes."""
    delay = np.full(shape, np.nan)
    for j, k0, k1, n0, n1 in arcs:
        kn, yn = ks[n0:n1], stec[n0:n1]
        if kn.size >= 4:
            from scipy.interpolate import CubicSpline

            delay[j, k0:k1] = k_delay * CubicSpline(kn, yn)(np.arange(k0, k1))
        else:
            delay[j, k0:k1] = k_delay * np.interp(np.arange(k0, k1), kn, yn)
    return delay


def simulate_slant_delay(
    lat_deg: float,
    lon_deg: float,
    date: str | _dt.date,
    *,
    orbit: OrbitSource | None = None,
    height_m: float = 0.0,
    satellites: tuple[str, ...] | list[str] | None = None,
    f107_sfu: float = DEFAULT_F107_SFU,
    elevation_mask_deg: float = 10.0,
    method: str = "line-of-sight",
    frequency_hz: float = FREQUENCIES_HZ["L1"],
    second_frequency_hz: float | None = None,
    sampling_s: float = 12.0,
    duration_s: float = SIDEREAL_DAY_S + DEFAULT_MARGIN_S,
    iri_model: str = "ursi",
    alt_range_km: tuple[float, float] = (60.0, 2000.0),
    alt_resolution: str = "fine",
    shell_height_km: float = DEFAULT_SHELL_HEIGHT_KM,
    grid_size: int = 21,
    ut_step_h: float = DEFAULT_UT_STEP_H,
    ray_stride: int = 5,
) -> SlantDelay:
    """Simulate the slant ionospheric delay of every satellite in view.

    Parameters
    ----------
    lat_deg, lon_deg : float
        Station geodetic latitude and longitude, degrees.
    date : str or datetime.date
        Day (UTC), ``YYYY-MM-DD``.
    orbit : OrbitSource, optional
        Anything with ``positions_ecef_m(sat, t_gps_s)`` and ``satellites``
        (navigation, SP3, :class:`~psdbound.ionosphere.almanac.Almanac`).
        Default: the nominal GPS 24-slot constellation.
    height_m : float, default 0
        Station ellipsoidal height, m.
    satellites : sequence of str, optional
        Restrict to these satellites (default: all the orbit source has).
    f107_sfu : float, default 70
        F10.7 solar flux, sfu.
    elevation_mask_deg : float, default 10
        Elevation mask, degrees.
    method : {"line-of-sight", "thin-shell"}
        Slant TEC by integrating density along the ray, or vertical TEC at
        the pierce point times the thin-shell obliquity factor.
    frequency_hz : float, default GPS L1
        Carrier frequency of the delay, Hz.
    second_frequency_hz : float, optional
        If given, the delay is that of the difference of the two carriers
        (``40.3 TEC |1/f1^2 - 1/f2^2|``), the ionosphere left in a
        dual-frequency phase difference.
    sampling_s : float, default 12
        Sampling interval, s.
    duration_s : float, default one sidereal day + 12 h
        Span simulated from 00:00 UTC, s (epochs strictly before it). The
        12 h beyond the sidereal day let every satellite's one-day window
        start in a visibility gap (see
        :func:`psdbound.ionosphere.cutoff.one_day_series`); UT past 24 h
        reuses the day's diurnal cycle.
    iri_model : {"ursi", "ccir", "sh"}
        PyIRI model (see module notes).
    alt_range_km : (float, float), default (60, 2000)
        Altitude range of the density integral, km.
    alt_resolution : {"fine", "coarse"}
        Altitude nodes of the integral (see
        :func:`~psdbound.ionosphere.iri.altitude_nodes_km`).
    shell_height_km : float, default 350
        Thin-shell height, km (``method="thin-shell"`` only).
    grid_size : int, default 21
        Horizontal interpolation grid nodes per axis.
    ut_step_h : float, default 0.5
        UT step of the interpolation grid, hours (must divide 24).
    ray_stride : int, default 5
        Integrate the ray every ``ray_stride`` epochs (60 s at 12 s) and at
        each arc's last epoch, then interpolate along the arc with a cubic
        spline; 1 integrates every epoch.

    Returns
    -------
    SlantDelay

    Raises
    ------
    InputError
        For a latitude outside [-90, 90], an unsupported date, an unknown
        method or model, an implausible F10.7, a mask outside [0, 90).
    NoDataError
        If no satellite rises above the mask during the day, or the orbit
        source has no position on that day.
    """
    lat, lon = validate_station(lat_deg, lon_deg)
    day = parse_date(date)
    _check_options(method, iri_model, f107_sfu, elevation_mask_deg, sampling_s)
    _check_altitudes(alt_range_km)
    k_delay = delay_factor(frequency_hz, second_frequency_hz)
    if orbit is None:
        orbit = nominal_constellation("G")
    n_ut = _n_ut(ut_step_h)

    t0, t = _day_epochs(day, sampling_s, duration_s)
    rx = geodetic_to_ecef(lat, lon, height_m)
    radius_m = float(np.linalg.norm(rx))
    source = getattr(orbit, "source_id", None) or f"file:{getattr(orbit, 'path', '?')}"
    kept, el_deg, az_deg = _in_view(
        orbit, satellites, t, rx, elevation_mask_deg, day, (lat, lon), source
    )
    visible = el_deg >= elevation_mask_deg

    alt_km = altitude_nodes_km(*alt_range_km, resolution=alt_resolution)
    model = _Model(method, iri_model, f107_sfu, alt_km, shell_height_km, grid_size, ut_step_h, n_ut)
    min_el = min(elevation_mask_deg, float(np.nanmin(el_deg[visible])))
    layers = _layer_fields(day, lat, lon, min_el, radius_m, model)
    stec, ks, arcs = _ray_tec(el_deg, az_deg, visible, t - t0, radius_m, layers, ray_stride, model)
    delay = _along_arcs(stec, ks, arcs, el_deg.shape, k_delay)

    info = {
        "f107_sfu": float(f107_sfu),
        "iri_model": iri_model,
        "method": method,
        "orbit_source": source,
        "orbit_description": getattr(orbit, "description", source),
        "frequency_hz": float(frequency_hz),
        "second_frequency_hz": None if second_frequency_hz is None else float(second_frequency_hz),
        "elevation_mask_deg": float(elevation_mask_deg),
        "sampling_s": float(sampling_s),
        "duration_s": float(duration_s),
        "alt_range_km": [float(alt_range_km[0]), float(alt_range_km[1])],
        "alt_resolution": alt_resolution,
        "shell_height_km": float(shell_height_km) if method == "thin-shell" else None,
        "grid_size": int(grid_size),
        "ut_step_h": float(ut_step_h),
        "ray_stride": int(ray_stride),
    }
    return SlantDelay(
        lat_deg=lat,
        lon_deg=lon,
        height_m=float(height_m),
        date=day.isoformat(),
        t_gps_s=t,
        sats=tuple(kept),
        delay_m=delay,
        elevation_deg=el_deg,
        azimuth_deg=az_deg,
        info=info,
    )


def _ray_nodes(
    visible: NDArray[np.bool_], stride: int
) -> tuple[tuple[NDArray[np.intp], NDArray[np.intp]], list[tuple[int, int, int, int, int]]]:
    """Epochs where rays are integrated, and the arcs they belong to.

    Returns ``((sat_index, epoch_index), arcs)`` with one arc per contiguous
    visible run: ``(sat_index, first_epoch, stop_epoch, first_node, stop_node)``.
    """
    if stride < 1:
        raise InputError(f"ray_stride = {stride} must be a positive integer")
    js: list[NDArray[np.intp]] = []
    ks: list[NDArray[np.intp]] = []
    arcs = []
    count = 0
    for j in range(visible.shape[0]):
        v = np.concatenate([[False], visible[j], [False]]).astype(np.int8)
        starts = np.flatnonzero(np.diff(v) == 1)
        stops = np.flatnonzero(np.diff(v) == -1)
        for k0, k1 in zip(starts, stops, strict=True):
            k = np.arange(k0, k1, stride)
            if k[-1] != k1 - 1:
                k = np.append(k, k1 - 1)
            js.append(np.full(k.size, j))
            ks.append(k)
            arcs.append((j, int(k0), int(k1), count, count + k.size))
            count += k.size
    return (np.concatenate(js), np.concatenate(ks)), arcs


def slant_tec_direct(
    lat_deg: float,
    lon_deg: float,
    date: str | _dt.date,
    t_gps_s: float,
    elevation_deg: float,
    azimuth_deg: float,
    *,
    height_m: float = 0.0,
    f107_sfu: float = DEFAULT_F107_SFU,
    iri_model: str = "ursi",
    alt_range_km: tuple[float, float] = (60.0, 2000.0),
) -> float:
    """Slant TEC of one ray with PyIRI evaluated at every ray point (no grid).

    The reference against which the gridded interpolation of
    :func:`simulate_slant_delay` is checked; slow (one PyIRI call per ray).

    Parameters
    ----------
    lat_deg, lon_deg : float
        Station position, degrees.
    date : str or datetime.date
        Day (UTC) of the epoch.
    t_gps_s : float
        Epoch, GPS seconds (within that day).
    elevation_deg, azimuth_deg : float
        Ray direction, degrees.
    height_m : float, default 0
        Station height, m.
    f107_sfu : float, default 70
        F10.7, sfu.
    iri_model : {"ursi", "ccir", "sh"}
        PyIRI model.
    alt_range_km : (float, float)
        Integration range, km.

    Returns
    -------
    float
        Slant TEC, TECU.
    """
    lat, lon = validate_station(lat_deg, lon_deg)
    day = parse_date(date)
    t0 = float(utc_to_gps_s(calendar_to_gps_s(day.year, day.month, day.day, 0, 0, 0.0))[0])
    radius_m = float(np.linalg.norm(geodetic_to_ecef(lat, lon, height_m)))
    alt_km = altitude_nodes_km(*alt_range_km)
    el = np.radians(elevation_deg)
    psi = central_angle_rad(radius_m, alt_km * 1e3, np.full(alt_km.shape, el))
    plat, plon = destination_point(lat, lon, psi, np.full(alt_km.shape, np.radians(azimuth_deg)))
    ut = np.array([np.mod((t_gps_s - t0) / 3600.0, 24.0)])
    edp = pyiri_density(day, ut, plon, plat, alt_km, f107_sfu, iri_model)[0]
    ne = np.diagonal(edp)  # density of point i at altitude i
    r_h = radius_m + alt_km * 1e3
    ds_dh = r_h / np.sqrt(r_h**2 - (radius_m * np.cos(el)) ** 2)
    return float(np.trapezoid(ne * ds_dh, alt_km * 1e3) / _TECU)
