"""Ground-reflector heights and amplitude ratios of a station from its SNR data (GNSS-IR).

:func:`reflector_heights` reads the SNR of one signal (RINEX 2 or 3 code)
from an observation file, computes each satellite's elevations from an
orbit, splits the tracks into rising and setting arcs inside the
elevation range (at data gaps and turning points) and analyses every arc
with :func:`psdbound.validation.snr_arc.analyse_arc`: the
reflector height, the reflected/direct amplitude ratio ``alpha`` and a
quality-control verdict. :class:`ReflectorHeights` holds every arc with
robust summaries (median height, 1.4826 MAD spread, median ``alpha``),
a text summary and a JSON-ready dictionary.

The method (Lomb-Scargle periodogram of the detrended SNR against
``sin(e)``, peak refinement, amplitude ratio, quality control) and its
references are in :mod:`psdbound.validation.snr_arc`.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import asdict, dataclass, replace
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.io.geometry import OrbitSource, satellite_azel
from psdbound.io.obs import Observations
from psdbound.io.signals import RINEX2_TO_RINEX3, wavelength_m
from psdbound.validation.snr_arc import (
    DEFAULT_ELEVATION_RANGE_DEG,
    DEFAULT_HEIGHT_RANGE_M,
    MAD_TO_SIGMA,
    ArcOptions,
    analyse_arc,
)

__all__ = ["ReflectorHeights", "reflector_heights"]


def _nan_median(a: NDArray[np.float64]) -> float:
    return float(np.median(a)) if a.size else float("nan")


def _category(reason: str) -> str:
    """Return the first test an arc failed, without its numbers ("peak amplitude")."""
    return re.split(r"[\d(]", reason.split(";")[0])[0].strip() or reason


def _json(v: Any) -> Any:
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, float) and not np.isfinite(v):
        return None
    return v


@dataclass(frozen=True, eq=False)
class ReflectorHeights:
    """Reflector heights of every rising and setting arc of one signal.

    Per-arc arrays (one element per arc, in satellite then time order):

    Attributes
    ----------
    path : str
        Observation file.
    signal : str
        Signal requested (``"S1C"``).
    elevation_range_deg, height_range_m : tuple of float
        Elevations analysed and heights searched.
    sat : ndarray of str
        Satellite of each arc.
    code : ndarray of str
        SNR code as stored in the file (``S1C``; RINEX 2 ``S1``).
    wavelength_m : ndarray of float64
        Carrier wavelength, m.
    rising : ndarray of bool
        True for a rising arc, False for a setting one.
    t_start_gps_s, t_end_gps_s : ndarray of float64
        First and last epoch of the arc, GPS seconds.
    azimuth_deg : ndarray of float64
        Circular mean azimuth, degrees in [0, 360).
    elevation_min_deg, elevation_max_deg : ndarray of float64
        Elevations covered, degrees.
    n_points : ndarray of int64
        Observations in the arc.
    n_outliers : ndarray of int64
        Of those, the points left out as outliers.
    height_m : ndarray of float64
        Reflector height, m (also for rejected arcs, NaN without a periodogram).
    peak_amplitude : ndarray of float64
        Periodogram peak amplitude, volts/volt.
    peak_to_noise : ndarray of float64
        Peak-to-noise ratio.
    alpha : ndarray of float64
        Reflected/direct amplitude ratio.
    accepted : ndarray of bool
        Passed quality control.
    reason : ndarray of str
        Why rejected; empty when accepted.
    skipped : tuple of str
        Satellites not analysed and why (no orbit, unknown GLONASS channel).
    """

    path: str
    signal: str
    elevation_range_deg: tuple[float, float]
    height_range_m: tuple[float, float]
    sat: NDArray[np.str_]
    code: NDArray[np.str_]
    wavelength_m: NDArray[np.float64]
    rising: NDArray[np.bool_]
    t_start_gps_s: NDArray[np.float64]
    t_end_gps_s: NDArray[np.float64]
    azimuth_deg: NDArray[np.float64]
    elevation_min_deg: NDArray[np.float64]
    elevation_max_deg: NDArray[np.float64]
    n_points: NDArray[np.int64]
    n_outliers: NDArray[np.int64]
    height_m: NDArray[np.float64]
    peak_amplitude: NDArray[np.float64]
    peak_to_noise: NDArray[np.float64]
    alpha: NDArray[np.float64]
    accepted: NDArray[np.bool_]
    reason: NDArray[np.str_]
    skipped: tuple[str, ...] = ()

    @property
    def n_arcs(self) -> int:
        """Number of arcs analysed."""
        return int(self.sat.size)

    @property
    def n_accepted(self) -> int:
        """Number of arcs that passed quality control."""
        return int(np.count_nonzero(self.accepted))

    @property
    def median_height_m(self) -> float:
        """Median reflector height of the accepted arcs, m (NaN if none)."""
        return _nan_median(self.height_m[self.accepted])

    @property
    def height_spread_m(self) -> float:
        """Robust spread of the accepted heights: 1.4826 x median absolute deviation, m."""
        h = self.height_m[self.accepted]
        return MAD_TO_SIGMA * _nan_median(np.abs(h - _nan_median(h)))

    @property
    def median_alpha(self) -> float:
        """Median amplitude ratio of the accepted arcs (NaN if none)."""
        return _nan_median(self.alpha[self.accepted])

    @property
    def no_result_reason(self) -> str:
        """Why the summary values are NaN; empty when some arc was accepted."""
        if self.n_accepted:
            return ""
        if not self.n_arcs:
            return f"no {self.signal} arc inside {self._range_text()}" + (
                f" ({len(self.skipped)} satellites skipped)" if self.skipped else ""
            )
        counts = Counter(_category(r) for r in self.reason)
        top = ", ".join(f"{n} {why}" for why, n in counts.most_common(3))
        return f"no arc passed quality control ({self.n_arcs} arcs: {top})"

    def _range_text(self) -> str:
        e1, e2 = self.elevation_range_deg
        return f"{e1:g}-{e2:g} deg elevation"

    def select(self, mask: ArrayLike) -> ReflectorHeights:
        """Return the arcs where ``mask`` is true (e.g. ``r.select(r.rising)``).

        Parameters
        ----------
        mask : array_like of bool, shape (n_arcs,)
            Arcs to keep.

        Returns
        -------
        ReflectorHeights
            Same metadata, the selected arcs.
        """
        m = np.asarray(mask, dtype=bool)
        if m.shape != self.sat.shape:
            raise InputError(f"mask of shape {m.shape}: expected ({self.n_arcs},)")
        return replace(self, **{k: getattr(self, k)[m] for k in _ARC_FIELDS})

    def summary(self) -> str:
        """Describe the result in a few lines of text."""
        h1, h2 = self.height_range_m
        lines = [
            f"reflector heights from {self.signal} ({self._range_text()}, heights "
            f"{h1:g}-{h2:g} m): {self.n_accepted} of {self.n_arcs} arcs accepted",
        ]
        if self.n_accepted:
            acc = self.select(self.accepted)
            n_rise = int(np.count_nonzero(acc.rising))
            lines.append(
                f"  median height {self.median_height_m:.3f} m, spread (1.4826 MAD) "
                f"{self.height_spread_m:.3f} m, median alpha {self.median_alpha:.3f}; "
                f"{n_rise} rising, {acc.n_arcs - n_rise} setting"
            )
        else:
            lines.append(f"  no height: {self.no_result_reason}")
        lines += [f"  skipped {s}" for s in self.skipped]
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: settings, summary values (NaN as None) and every arc."""
        arcs = [{k: _json(getattr(self, k)[i]) for k in _ARC_FIELDS} for i in range(self.n_arcs)]
        return {
            "path": self.path,
            "signal": self.signal,
            "elevation_range_deg": list(self.elevation_range_deg),
            "height_range_m": list(self.height_range_m),
            "n_arcs": self.n_arcs,
            "n_accepted": self.n_accepted,
            "median_height_m": _json(self.median_height_m),
            "height_spread_m": _json(self.height_spread_m),
            "median_alpha": _json(self.median_alpha),
            "no_result_reason": self.no_result_reason,
            "skipped": list(self.skipped),
            "arcs": arcs,
        }


_ARC_FIELDS = (
    "sat",
    "code",
    "wavelength_m",
    "rising",
    "t_start_gps_s",
    "t_end_gps_s",
    "azimuth_deg",
    "elevation_min_deg",
    "elevation_max_deg",
    "n_points",
    "n_outliers",
    "height_m",
    "peak_amplitude",
    "peak_to_noise",
    "alpha",
    "accepted",
    "reason",
)


def _snr_codes(obs: Observations) -> str:
    parts = [
        f"{s}: {' '.join(c for c in b.codes if c.startswith('S')) or 'none'}"
        for s, b in obs.blocks.items()
    ]
    return "; ".join(parts) or "no systems"


def _code_in_block(codes: tuple[str, ...], signal: str) -> str | None:
    """Return the file's code for a requested SNR signal (RINEX 2 or 3 name), or None."""
    if signal in codes:
        return signal
    v3 = RINEX2_TO_RINEX3.get(signal)
    if v3 is not None and v3 in codes:
        return v3
    alias = [v2 for v2, c in RINEX2_TO_RINEX3.items() if c == signal and v2 in codes]
    return alias[0] if alias else None


def _resolve_signal(
    obs: Observations, signal: str, systems: str | Iterable[str] | None
) -> dict[str, str]:
    """Map each system to the SNR code it is analysed with."""
    if not any(c.startswith("S") for b in obs.blocks.values() for c in b.codes):
        raise InputError(
            f"signal {signal!r}: the file has no SNR observations (codes {_snr_codes(obs)})",
            path=obs.path,
        )
    if len(signal) not in (2, 3) or signal[0] != "S" or not signal[1].isdigit():
        raise InputError(
            f"signal {signal!r} is not an SNR code such as 'S1C' or 'S1'; the file "
            f"has {_snr_codes(obs)}",
            path=obs.path,
        )
    wanted = list(obs.blocks) if systems is None else list(dict.fromkeys(systems))
    out = {}
    for s in wanted:
        code = _code_in_block(obs.blocks[s].codes, signal) if s in obs.blocks else None
        if code is not None:
            out[s] = code
        elif systems is not None:
            raise InputError(
                f"signal {signal!r} is not in the file for system {s!r}; SNR codes: "
                f"{_snr_codes(obs)}",
                path=obs.path,
            )
    if not out:
        raise InputError(
            f"signal {signal!r} is not in the file; SNR codes: {_snr_codes(obs)}", path=obs.path
        )
    return out


def _split_arcs(
    t: NDArray[np.float64], el: NDArray[np.float64], e_range: tuple[float, float], max_gap_s: float
) -> list[tuple[NDArray[np.intp], bool]]:
    """Index arrays of the rising and setting arcs inside the elevation range.

    ``t`` and ``el`` are one satellite's valid samples. The direction comes
    from the neighbouring samples' elevation change (forward difference,
    backward at the end of a stretch); arcs end at gaps over ``max_gap_s``,
    where the direction changes, and where the elevation leaves the range.
    """
    gap_after = np.append(np.diff(t) > max_gap_s, True)
    d = np.diff(el)
    fwd = np.append(d, np.nan)
    bwd = np.insert(d, 0, np.nan)
    gap_before = np.insert(gap_after[:-1], 0, True)
    rate = np.where(gap_after, np.where(gap_before, 0.0, bwd), fwd)
    rising = rate > 0.0
    idx = np.flatnonzero((el >= e_range[0]) & (el <= e_range[1]))
    if idx.size == 0:
        return []
    new = np.ones(idx.size, dtype=bool)
    new[1:] = (np.diff(idx) > 1) | gap_after[idx[:-1]] | (rising[idx[1:]] != rising[idx[:-1]])
    starts = np.flatnonzero(new)
    bounds = np.append(starts, idx.size)
    return [(idx[a:b], bool(rising[idx[a]])) for a, b in zip(bounds[:-1], bounds[1:], strict=True)]


def _circular_mean_deg(az_deg: NDArray[np.float64]) -> float:
    a = np.radians(az_deg)
    return float(np.degrees(np.arctan2(np.mean(np.sin(a)), np.mean(np.cos(a)))) % 360.0)


def _satellite_arcs(
    obs: Observations,
    orbit: OrbitSource,
    sat: str,
    code: str,
    lam: float,
    rx: NDArray[np.float64],
    qc: ArcOptions,
    max_gap_s: float,
) -> tuple[list[dict[str, Any]], str]:
    """Arc rows of one satellite, and why it is skipped (empty if it is not)."""
    snr = obs.get(sat, code)
    ok = np.isfinite(snr) & (snr > 0.0)
    if not np.any(ok):
        return [], ""
    t = obs.t_gps_s[ok]
    az, el = satellite_azel(orbit, sat, t, rx)
    fin = np.isfinite(el)
    if not np.any(fin):
        return [], f"{sat}: no orbit positions at the observed epochs"
    t, az, el, s = t[fin], az[fin], el[fin], snr[ok][fin]
    rows = []
    for ix, rising in _split_arcs(t, el, qc.elevation_range_deg, max_gap_s):
        arc = {"sat": sat, "code": code, "wavelength_m": lam, "rising": rising}
        arc |= {"t_start_gps_s": t[ix[0]], "t_end_gps_s": t[ix[-1]]}
        arc["azimuth_deg"] = _circular_mean_deg(az[ix])
        rows.append(arc | asdict(analyse_arc(el[ix], s[ix], lam, qc)))
    return rows, ""


def _receiver_position(obs: Observations, receiver_xyz_m: ArrayLike | None) -> NDArray[np.float64]:
    rx = obs.header.approx_position_m if receiver_xyz_m is None else receiver_xyz_m
    if rx is None:
        raise InputError(
            "the header has no usable APPROX POSITION XYZ: pass receiver_xyz_m "
            "(ECEF metres) to compute elevations",
            path=obs.path,
        )
    out = np.asarray(rx, dtype=np.float64)
    if out.shape != (3,) or not np.all(np.isfinite(out)):
        raise InputError(f"receiver position {rx!r}: expected three finite ECEF metres")
    return out


def _collect(rows: list[dict[str, Any]]) -> dict[str, NDArray[Any]]:
    dtypes: Mapping[str, Any] = {
        "sat": str,
        "code": str,
        "reason": str,
        "rising": bool,
        "accepted": bool,
        "n_points": np.int64,
        "n_outliers": np.int64,
    }
    return {k: np.array([r[k] for r in rows], dtype=dtypes.get(k, np.float64)) for k in _ARC_FIELDS}


def reflector_heights(
    obs: Observations,
    orbit: OrbitSource,
    *,
    signal: str = "S1C",
    systems: str | Iterable[str] | None = None,
    elevation_range_deg: tuple[float, float] = DEFAULT_ELEVATION_RANGE_DEG,
    height_range_m: tuple[float, float] = DEFAULT_HEIGHT_RANGE_M,
    min_points: int = 40,
    max_edge_gap_deg: float = 2.0,
    max_gap_s: float = 300.0,
    poly_order: int = 4,
    min_peak_amplitude: float = 6.0,
    min_peak_to_noise: float = 3.0,
    oversampling: float = 10.0,
    joint_refinement: bool = True,
    receiver_xyz_m: ArrayLike | None = None,
) -> ReflectorHeights:
    """Reflector height and amplitude ratio of every rising and setting arc (GNSS-IR).

    Method and quality control in :mod:`psdbound.validation.snr_arc`; one
    arc per satellite pass direction inside the elevation range, split at
    data gaps.

    Parameters
    ----------
    obs : Observations
        From :func:`psdbound.io.read_obs`.
    orbit : OrbitSource
        From :func:`psdbound.io.read_orbit` (broadcast or SP3).
    signal : str, optional
        SNR code, RINEX 3 (``"S1C"``, ``"S2W"``) or RINEX 2 (``"S1"``,
        ``"S2"``); mapped between versions with
        :data:`psdbound.io.signals.RINEX2_TO_RINEX3`.
    systems : str or iterable of str, optional
        System letters to analyse (``"G"``, ``"GE"``); by default every
        system whose observations have the signal. GLONASS FDMA satellites
        with no known frequency channel are skipped (listed in ``skipped``).
    elevation_range_deg : tuple of float, optional
        Elevations analysed, degrees.
    height_range_m : tuple of float, optional
        Reflector heights searched (and the noise region), m.
    min_points, max_edge_gap_deg, poly_order, min_peak_amplitude, min_peak_to_noise : optional
        Arc-level quality control, see :func:`arc_height`.
    oversampling, joint_refinement : optional
        Peak search, see :func:`arc_height`.
    max_gap_s : float, optional
        A gap in a satellite's SNR longer than this ends an arc, s.
    receiver_xyz_m : array_like of float, shape (3,), optional
        Receiver ECEF position, m; default the header's approximate position.

    Returns
    -------
    ReflectorHeights
        Every arc with its height, amplitude ratio and quality-control
        verdict; summary values are NaN (with ``no_result_reason``) when no
        arc passes.

    Raises
    ------
    InputError
        If the signal is not an SNR code or not in the file (the message
        lists the SNR codes the file has), a requested system lacks it, the
        receiver position is unknown, or a setting is inconsistent.

    See Also
    --------
    arc_height : The same analysis of one arc.
    """
    qc = ArcOptions.build(
        elevation_range_deg=elevation_range_deg,
        height_range_m=height_range_m,
        min_points=min_points,
        max_edge_gap_deg=max_edge_gap_deg,
        poly_order=poly_order,
        min_peak_amplitude=min_peak_amplitude,
        min_peak_to_noise=min_peak_to_noise,
        oversampling=oversampling,
        joint_refinement=joint_refinement,
    )
    codes = _resolve_signal(obs, signal, systems)
    rx = _receiver_position(obs, receiver_xyz_m)
    channels = {**getattr(orbit, "glonass_channels", {}), **obs.header.glonass_channels}
    rows: list[dict[str, Any]] = []
    skipped: list[str] = []
    for system, code in codes.items():
        for sat in obs.blocks[system].sats:
            try:
                lam = wavelength_m(sat, RINEX2_TO_RINEX3.get(code, code), channels)
            except InputError as exc:  # GLONASS FDMA without a known channel
                skipped.append(f"{sat}: {exc.reason}")
                continue
            arcs, note = _satellite_arcs(obs, orbit, sat, code, lam, rx, qc, float(max_gap_s))
            rows += arcs
            skipped += [note] if note else []
    return ReflectorHeights(
        obs.path,
        signal,
        qc.elevation_range_deg,
        qc.height_range_m,
        skipped=tuple(skipped),
        **_collect(rows),
    )
