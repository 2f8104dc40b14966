"""Dual-antenna (DA) isolation: between-receiver, between-satellite double differences.

Two receivers on a short baseline track the same signal. For satellite ``s``
and receiver ``k`` the carrier phase in metres is::

    phi_k^s = rho_k^s + c dt_k - c dT^s + lambda N_k^s + m_k^s + e_k^s

(``rho`` the geometric range at the true receive time, ``dt_k`` the receiver
clock, ``dT^s`` the satellite clock, ``N`` the ambiguity, ``m`` multipath,
``e`` noise; ionosphere and troposphere are common to both antennas of a short
baseline and cancel). The single difference across receivers,
``SD^s = phi_1^s - phi_2^s - (rho_1^s - rho_2^s)``, cancels the satellite
clock; the double difference with a reference satellite ``r``,
``DD^{s,r} = SD^s - SD^r``, cancels the receiver clocks. What is left is the
ambiguity (constant over an arc, removed with the arc's mean) and four
independent per-signal multipath terms, hence the scaling by 1/2.

Receiver clocks and the geometric term
--------------------------------------
Although ``c dt_k`` cancels in the double difference, ``rho_k`` must be
evaluated at the *true* receive time ``t - dt_k``: receiver clocks can be off
by milliseconds, and a range rate of 800 m/s turns 1 ms into 0.8 m, different
for every satellite. Each receiver's clock offset is estimated per epoch as
the median over satellites of ``(P - rho + c dT) / c`` with ``P`` a
pseudorange of the same band (else C1/C1C, else P1/C1W, else any code), ``rho``
computed at the nominal epoch, ``dT`` the broadcast satellite clock when the
orbit source gives one. The estimate is good to about 1e-7 s (ionosphere,
troposphere, code multipath), far better than needed: only the
*between-receiver* difference of the clock errors matters, and 1e-7 s times a
range-rate difference of 1 km/s is 0.1 mm. Without satellite clocks (SP3
orbits) the estimate is biased by the median satellite clock (below 1 ms),
nearly the same for both receivers, so the bias cancels to first order.

Antenna positions
-----------------
Positions come from the RINEX headers (``APPROX POSITION XYZ`` plus the
``ANTENNA: DELTA H/E/N`` eccentricity rotated to ECEF) or are given by the
user (taken as the antenna positions as they are). The double difference is
only as good as the baseline: an error ``db`` in the baseline vector leaves
``db . (u^s - u^r)`` (unit line-of-sight vectors) in the result, i.e. up to
about ``|db|``. Antenna phase-centre offsets and variations are not modelled;
they cancel for identical, identically oriented antennas.

Short-baseline DA partly cancels multipath common to both antennas (e.g. from
distant reflectors); the result can under-represent multipath, which is why
the dual-frequency method is preferred. ``meta["note"]`` says so.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.arcs.find import ArcSet, find_arcs
from psdbound.errors import InputError, NoDataError
from psdbound.io.geometry import (
    OrbitSource,
)
from psdbound.io.obs import Observations
from psdbound.io.signals import RINEX2_TO_RINEX3, wavelength_m
from psdbound.isolation._dd_support import (
    SDArc,
    antenna_position,
    any_above,
    check_not_same,
    common_satellites,
    estimate_receiver_clock,
    geometric_range_m,
    geometry_all,
    match_epochs,
    reference_periods,
    resolve_pair,
)
from psdbound.isolation.baseline import estimate_baseline_correction
from psdbound.isolation.names import BASELINE_MODES, BASELINE_TOLERANCE_M
from psdbound.isolation.series import MultipathSeries

__all__ = ["isolate_dual_antenna"]

#: Scaling of the double difference to one signal (four independent terms).
DA_SCALING = 0.5
#: A double-difference jump between consecutive epochs larger than this
#: fraction of the wavelength is an undetected cycle slip: the arc is split.
DD_JUMP_FRACTION = 0.4
MIN_ANTENNA_SEPARATION_M = 1e-3
#: With ``baseline="auto"`` the correction must also exceed this many sigmas.
SIGNIFICANCE = 3.0
_NOTE = (
    "short-baseline dual-antenna double differences partly cancel multipath that is "
    "common to both antennas; the dual-frequency method is preferred"
)
_CLOCK_NOTE = (
    "receiver clock offset per epoch = median over satellites of (P - rho + c*dT)/c "
    "(P pseudorange, rho geometric range at the nominal epoch, dT broadcast satellite "
    "clock); geometric ranges evaluated at the clock-corrected receive time"
)


def isolate_dual_antenna(
    obs1: Observations,
    obs2: Observations,
    orbit: OrbitSource,
    *,
    signal: str = "L1C",
    slip_signal: str | None = "L2W",
    system: str = "G",
    receiver1_xyz_m: ArrayLike | None = None,
    receiver2_xyz_m: ArrayLike | None = None,
    min_length_s: float = 600.0,
    elevation_mask_deg: float = 10.0,
    max_baseline_m: float = 20000.0,
    baseline: str = "auto",
    baseline_tolerance_m: float = BASELINE_TOLERANCE_M,
) -> MultipathSeries:
    """Isolate carrier-phase multipath with double differences of two antennas.

    Parameters
    ----------
    obs1, obs2 : Observations
        Observations of the two receivers (:func:`psdbound.io.read_obs`), of
        the same period, sampled on common epochs (matched to 1 ms).
    orbit : OrbitSource
        Satellite orbits (:func:`psdbound.io.read_orbit`); its
        ``satellite_clock_s`` is used for the receiver-clock estimate when
        present.
    signal : str, default "L1C"
        Carrier-phase signal to difference (RINEX 3 code; RINEX 2 files also
        accept their own codes, e.g. ``"L1"``).
    slip_signal : str or None, default "L2W"
        Second phase signal of each receiver used only to find cycle slips
        (geometry-free test, see :func:`psdbound.arcs.find_arcs`). With None,
        arcs are broken on gaps, loss-of-lock flags and power failures only
        (plus the double-difference jump test below).
    system : str, default "G"
        Satellite system letter.
    receiver1_xyz_m, receiver2_xyz_m : array_like of shape (3,), optional
        Antenna ECEF positions, metres. Default: the header's
        ``APPROX POSITION XYZ`` plus ``ANTENNA: DELTA H/E/N``.
    min_length_s : float, default 600
        Minimum duration of a tracking arc and of a double-difference arc,
        seconds; shorter double-difference arcs are dropped and counted.
    elevation_mask_deg : float, default 10
        Epochs with a satellite below this elevation (degrees) are excluded.
    max_baseline_m : float, default 20000
        Longest accepted distance between the antennas, metres: beyond it the
        ionosphere and troposphere no longer cancel.
    baseline : {"auto", "estimate", "given"}, default "auto"
        What to do with the baseline estimated from the double differences
        (:mod:`psdbound.isolation.baseline`): ``"auto"`` moves antenna 2 to
        the estimate when the correction is longer than
        ``baseline_tolerance_m`` and than three standard errors;
        ``"estimate"`` always does; ``"given"`` keeps the positions (header
        or ``receiver*_xyz_m``) and only reports the estimate.
    baseline_tolerance_m : float, default 0.005
        Correction length above which ``"auto"`` uses the estimate, metres.

    Returns
    -------
    MultipathSeries
        ``method="DA"``, ``scaling=0.5``, ``signals=(signal,)``; one arc per
        satellite pair and reference period, named ``"G05-G12"`` (satellite
        minus reference), with the arc mean removed (ambiguity) and values in
        metres scaled by 1/2; ``elevation_deg`` is the lower elevation of the
        pair. ``meta`` holds the files, markers, baseline length, positions
        and their source (antenna 2 corrected when the estimate is used),
        ``baseline_estimate`` (mode, whether used, correction in ECEF and
        ENU with standard errors, double-difference RMS before and after),
        reference periods, receiver-clock estimate, counts of dropped arcs
        and the elevation mask.

    Raises
    ------
    InputError
        The same file twice or identical positions, files with no common
        epochs (e.g. different days), stations more than ``max_baseline_m``
        apart, no common satellites, a signal or system missing from a file,
        no pseudorange for the clock estimate, or no antenna position.
    NoDataError
        No double-difference arc of at least ``min_length_s``.

    See Also
    --------
    isolate_dual_frequency : The one-antenna method (preferred).
    estimate_baseline_correction : The baseline check used here.

    Notes
    -----
    Reference satellite: the highest satellite with a single-difference arc
    at the first epoch; it is kept until its single-difference arc ends, then
    the highest satellite with a single-difference arc at the next epoch
    becomes the reference, and so on. A double-difference arc is the
    intersection of a satellite's single-difference arc, the reference's
    single-difference arc and the reference period; it is split where it
    jumps by more than 0.4 wavelength between epochs (a slip the per-receiver
    tests missed).

    References
    ----------
    .. [1] Teunissen, P. J. G., & Montenbruck, O. (Eds.) (2017). *Springer
       Handbook of Global Navigation Satellite Systems*, ch. 21 (double
       differences). Springer.
    .. [2] docs/method/isolation.rst.

    Examples
    --------
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()                        # two antennas 5 m apart
    >>> a, b = (read_obs(p, systems="G") for p in d.obs_paths)
    >>> da = isolate_dual_antenna(a, b, read_orbit(d.nav_path))
    >>> da.method, da.scaling, round(da.meta["baseline_m"], 1)
    ('DA', 0.5, 5.0)
    >>> da.meta["baseline_estimate"]["used"]   # the header positions agree with the phases
    False
    """
    files = f"{obs1.path} and {obs2.path}"
    inp = _check_inputs(
        obs1,
        obs2,
        files,
        receiver1_xyz_m,
        receiver2_xyz_m,
        system=system,
        signal=signal,
        slip_signal=slip_signal,
        max_baseline_m=max_baseline_m,
        baseline=baseline,
        baseline_tolerance_m=baseline_tolerance_m,
    )
    i1, i2 = match_epochs(obs1, obs2, files)
    sats = common_satellites(obs1, obs2, system, inp.code1, inp.code2, i1, i2, files)

    # geometry at the nominal epochs: receiver clocks and the find_arcs pre-filter
    trk1, trk2 = _track_both(
        obs1,
        obs2,
        inp,
        orbit,
        sats,
        system=system,
        min_length_s=min_length_s,
        elevation_mask_deg=elevation_mask_deg,
    )
    common = _Common.of(obs1, obs2, i1, i2, trk1, trk2, inp)
    sd = _single_difference_arcs(trk1, trk2, common, orbit, files, min_length_s, elevation_mask_deg)
    lam = wavelength_m(
        sats[0], RINEX2_TO_RINEX3.get(inp.code1, inp.code1), obs1.header.glonass_channels
    )
    dd = _double_difference_arcs(sd, common, DD_JUMP_FRACTION * lam, files, min_length_s)
    choice = _choose_baseline(dd.pieces, inp, baseline, baseline_tolerance_m)
    n_common = int(i1.size)
    interval_s = float(np.median(np.diff(common.t_s))) if n_common > 1 else obs1.interval_s
    meta: dict[str, Any] = {
        **_station_meta(obs1, obs2, inp, choice),
        "slip_detection": _slip_detection_text(slip_signal),
        "reference_periods": _reference_meta(dd.periods, common.t_s),
        "receiver_clock": _clock_meta(orbit, trk1, trk2, i1, i2),
        **_count_meta(n_common, trk1, trk2, sd, dd, len(choice.arcs)),
        "min_length_s": float(min_length_s),
        "elevation_mask_deg": float(elevation_mask_deg),
        "max_baseline_m": float(max_baseline_m),
        "note": _NOTE,
    }
    return MultipathSeries.from_arcs(
        "DA",
        choice.arcs,
        signals=(signal,),
        scaling=DA_SCALING,
        interval_s=interval_s,
        cutoff_hz=None,
        meta=meta,
    )


# --------------------------------------------------------------------------- checks


@dataclass(frozen=True)
class _Inputs:
    """The checked antenna positions (ECEF, m), their sources and the resolved codes."""

    pos1: NDArray[np.float64]
    pos2: NDArray[np.float64]
    src1: str
    src2: str
    baseline_m: float
    code1: str
    code2: str
    slip1: str | None
    slip2: str | None


def _check_inputs(
    obs1: Observations,
    obs2: Observations,
    files: str,
    receiver1_xyz_m: ArrayLike | None,
    receiver2_xyz_m: ArrayLike | None,
    *,
    system: str,
    signal: str,
    slip_signal: str | None,
    max_baseline_m: float,
    baseline: str,
    baseline_tolerance_m: float,
) -> _Inputs:
    """Check the options, the two files and the baseline; resolve positions and codes."""
    if baseline not in BASELINE_MODES:
        raise InputError(f"baseline must be one of {', '.join(BASELINE_MODES)}, got {baseline!r}")
    if not baseline_tolerance_m >= 0.0:
        raise InputError(f"baseline_tolerance_m must be >= 0 m, got {baseline_tolerance_m!r}")
    check_not_same(obs1, obs2, files)
    pos1, src1 = antenna_position(obs1, receiver1_xyz_m, "receiver1_xyz_m")
    pos2, src2 = antenna_position(obs2, receiver2_xyz_m, "receiver2_xyz_m")
    baseline_m = float(np.linalg.norm(pos1 - pos2))
    if baseline_m < MIN_ANTENNA_SEPARATION_M:
        raise InputError(
            f"identical antenna positions for {files} ({src1}, {src2}): "
            "the same station twice? dual-antenna isolation needs two antennas"
        )
    if not baseline_m <= max_baseline_m:
        raise InputError(
            f"not a short baseline: {files} are {baseline_m / 1e3:.3f} km apart "
            f"(max_baseline_m = {max_baseline_m:g} m)"
        )
    code1, code2, slip1, slip2 = _resolve_codes(obs1, obs2, files, system, signal, slip_signal)
    return _Inputs(pos1, pos2, src1, src2, baseline_m, code1, code2, slip1, slip2)


def _resolve_codes(
    obs1: Observations,
    obs2: Observations,
    files: str,
    system: str,
    signal: str,
    slip_signal: str | None,
) -> tuple[str, str, str | None, str | None]:
    """Return both files' phase codes and slip-test codes (None without a slip signal)."""
    for obs in (obs1, obs2):
        if system not in obs.blocks:
            raise InputError(
                f"no {system} observations in {obs.path} (systems: {' '.join(obs.blocks)}); "
                f"dual-antenna inputs {files}"
            )
    code1, code2 = resolve_pair(obs1, obs2, system, signal, "signal")
    if not code1.startswith("L"):
        raise InputError(f"signal {signal!r} is not a carrier phase (L..) in {files}")
    slip1 = slip2 = None
    if slip_signal is not None:
        slip1, slip2 = resolve_pair(obs1, obs2, system, slip_signal, "slip_signal")
    return code1, code2, slip1, slip2


# --------------------------------------------------------------------------- tracking


@dataclass(frozen=True)
class _Tracking:
    """One receiver's clock estimate (s, per epoch of its file) and tracking arcs."""

    dt_s: NDArray[np.float64]
    clock_code: str
    n_interpolated: int
    arcs: ArcSet


def _track(
    obs: Observations,
    pos: NDArray[np.float64],
    code: str,
    slip: str | None,
    orbit: OrbitSource,
    sats: list[str],
    *,
    system: str,
    min_length_s: float,
    elevation_mask_deg: float,
) -> _Tracking:
    """Estimate one receiver's clock and find its tracking arcs of the visible satellites."""
    rho, tau, el = geometry_all(orbit, sats, obs.t_gps_s, pos)
    dt, code_c, n_interp = estimate_receiver_clock(obs, orbit, sats, code, rho, tau)
    visible = [
        s for k, s in enumerate(sats) if any_above(obs, s, code, slip, el[:, k], elevation_mask_deg)
    ]
    pair = (code, code if slip is None else slip)
    arcs = find_arcs(
        obs,
        pair,
        system=system,
        orbit=orbit,
        receiver_xyz_m=pos,
        min_length_s=min_length_s,
        elevation_mask_deg=elevation_mask_deg,
        satellites=visible,
    )
    return _Tracking(dt, code_c, n_interp, arcs)


def _track_both(
    obs1: Observations,
    obs2: Observations,
    inp: _Inputs,
    orbit: OrbitSource,
    sats: list[str],
    *,
    system: str,
    min_length_s: float,
    elevation_mask_deg: float,
) -> tuple[_Tracking, _Tracking]:
    """Estimate both receivers' clocks and find their tracking arcs (:func:`_track`)."""
    trk1 = _track(
        obs1,
        inp.pos1,
        inp.code1,
        inp.slip1,
        orbit,
        sats,
        system=system,
        min_length_s=min_length_s,
        elevation_mask_deg=elevation_mask_deg,
    )
    trk2 = _track(
        obs2,
        inp.pos2,
        inp.code2,
        inp.slip2,
        orbit,
        sats,
        system=system,
        min_length_s=min_length_s,
        elevation_mask_deg=elevation_mask_deg,
    )
    return trk1, trk2


@dataclass(frozen=True)
class _Common:
    """Both receivers on the common epochs: times and clock-corrected receive times (GPS s)."""

    t_s: NDArray[np.float64]
    where1: NDArray[np.intp]
    where2: NDArray[np.intp]
    t_rx1: NDArray[np.float64]
    t_rx2: NDArray[np.float64]
    pos1: NDArray[np.float64]
    pos2: NDArray[np.float64]

    @classmethod
    def of(
        cls,
        obs1: Observations,
        obs2: Observations,
        i1: NDArray[np.intp],
        i2: NDArray[np.intp],
        trk1: _Tracking,
        trk2: _Tracking,
        inp: _Inputs,
    ) -> _Common:
        """Map each file's epochs to the common ones (-1: not common)."""
        n_common = int(i1.size)
        where1 = np.full(obs1.t_gps_s.size, -1, dtype=np.intp)
        where1[i1] = np.arange(n_common)
        where2 = np.full(obs2.t_gps_s.size, -1, dtype=np.intp)
        where2[i2] = np.arange(n_common)
        t1c, t2c = obs1.t_gps_s[i1], obs2.t_gps_s[i2]
        t_rx1 = t1c - trk1.dt_s[i1]
        t_rx2 = t2c - trk2.dt_s[i2]
        return cls(t1c, where1, where2, t_rx1, t_rx2, inp.pos1, inp.pos2)

    def too_short(self, ci: NDArray[np.intp], min_length_s: float) -> bool:
        """Whether common epochs ``ci`` are fewer than two or span less than ``min_length_s``."""
        return bool(ci.size < 2 or self.t_s[ci[-1]] - self.t_s[ci[0]] < min_length_s)


# --------------------------------------------------------------------------- differences


@dataclass
class _SingleDifferences:
    """Single-difference arcs and the count of common stretches too short."""

    arcs: list[SDArc]
    n_short: int


def _single_differences(
    arcs1: ArcSet, arcs2: ArcSet, common: _Common, orbit: OrbitSource, min_length_s: float
) -> _SingleDifferences:
    """Difference the two receivers' arcs of each satellite on their common epochs."""
    out = _SingleDifferences([], 0)
    by_sat2: dict[str, list] = {}
    for a in arcs2:
        by_sat2.setdefault(a.sat, []).append(a)
    for a1 in arcs1:
        c1 = common.where1[a1.epoch_index]
        k1 = np.flatnonzero(c1 >= 0)
        for a2 in by_sat2.get(a1.sat, []):
            arc, n_short = _single_difference(a1, c1, k1, a2, common, orbit, min_length_s)
            out.n_short += n_short
            if arc is not None:
                out.arcs.append(arc)
    return out


def _single_difference_arcs(
    trk1: _Tracking,
    trk2: _Tracking,
    common: _Common,
    orbit: OrbitSource,
    files: str,
    min_length_s: float,
    elevation_mask_deg: float,
) -> _SingleDifferences:
    """Single-difference arcs sorted by first common epoch and satellite; none is an error."""
    sd = _single_differences(trk1.arcs, trk2.arcs, common, orbit, min_length_s)
    if not sd.arcs:
        raise NoDataError(
            f"no single-difference arc of at least {min_length_s:g} s above "
            f"{elevation_mask_deg:g} deg in {files} ({len(trk1.arcs)} and "
            f"{len(trk2.arcs)} tracking arcs, {sd.n_short} common stretches too short)"
        )
    sd.arcs.sort(key=lambda a: (int(a.ci[0]), a.sat))
    return sd


def _single_difference(
    a1: Any,
    c1: NDArray[np.intp],
    k1: NDArray[np.intp],
    a2: Any,
    common: _Common,
    orbit: OrbitSource,
    min_length_s: float,
) -> tuple[SDArc | None, int]:
    """Single difference of one pair of tracking arcs (m), or None with 1 if too short."""
    c2 = common.where2[a2.epoch_index]
    k2 = np.flatnonzero(c2 >= 0)
    ci, j1, j2 = np.intersect1d(c1[k1], c2[k2], assume_unique=True, return_indices=True)
    j1, j2 = k1[j1], k2[j2]
    if common.too_short(ci, min_length_s):
        return None, int(ci.size > 0)
    rho1, _, sv = geometric_range_m(orbit, a1.sat, common.t_rx1[ci], common.pos1)
    rho2 = geometric_range_m(orbit, a1.sat, common.t_rx2[ci], common.pos2)[0]
    sd = a1.phase_m[j1, 0] - a2.phase_m[j2, 0] - (rho1 - rho2)
    el = np.minimum(a1.elevation_deg[j1], a2.elevation_deg[j2])
    los = (sv - common.pos1) / rho1[:, None]
    ok = np.isfinite(sd) & np.isfinite(el)
    if not ok.all():
        ci, sd, el, los = ci[ok], sd[ok], el[ok], los[ok]
        if common.too_short(ci, min_length_s):
            return None, 1
    return SDArc(a1.sat, ci, sd, el, los), 0


#: A double-difference arc: satellite pair name, times (GPS s), values (m),
#: elevations (deg) and line-of-sight differences.
_Piece = tuple[str, NDArray, NDArray, NDArray, NDArray]


@dataclass
class _DoubleDifferences:
    """Double-difference arcs, the reference periods and the counts of dropped/split arcs."""

    pieces: list[_Piece]
    periods: list[tuple[SDArc, int, int]]
    n_short: int = 0
    n_jump_splits: int = 0


def _double_difference_arcs(
    sd: _SingleDifferences,
    common: _Common,
    jump_m: float,
    files: str,
    min_length_s: float,
) -> _DoubleDifferences:
    """Double-difference arcs of the single-difference arcs; none is an error."""
    dd = _double_differences(sd.arcs, common.t_s, jump_m, min_length_s)
    if not dd.pieces:
        raise NoDataError(
            f"no double-difference arc of at least {min_length_s:g} s in {files} "
            f"({len(sd.arcs)} single-difference arcs, {dd.n_short} double-difference "
            "arcs too short)"
        )
    return dd


def _double_differences(
    sd_arcs: list[SDArc], t_s: NDArray[np.float64], jump_m: float, min_length_s: float
) -> _DoubleDifferences:
    """Choose the reference periods and difference every other arc with the reference."""
    out = _DoubleDifferences([], reference_periods(sd_arcs))
    for ref, k0, k1 in out.periods:
        in_period = (ref.ci >= k0) & (ref.ci <= k1)
        window = SDArc(
            ref.sat,
            ref.ci[in_period],
            ref.sd_m[in_period],
            ref.el_deg[in_period],
            ref.los[in_period],
        )
        for other in sd_arcs:
            if other.sat == ref.sat or other.ci[-1] < k0 or other.ci[0] > k1:
                continue
            _difference_with_reference(other, window, t_s, jump_m, min_length_s, out)
    return out


def _difference_with_reference(
    other: SDArc,
    ref: SDArc,
    t_s: NDArray[np.float64],
    jump_m: float,
    min_length_s: float,
    out: _DoubleDifferences,
) -> None:
    """Append the pieces of ``other - ref`` to ``out``, split at jumps over ``jump_m`` metres."""
    ci, jo, jr = np.intersect1d(other.ci, ref.ci, assume_unique=True, return_indices=True)
    if ci.size < 2:
        return
    dd = other.sd_m[jo] - ref.sd_m[jr]
    el = np.minimum(other.el_deg[jo], ref.el_deg[jr])
    g = other.los[jo] - ref.los[jr]
    cuts = np.flatnonzero(np.abs(np.diff(dd)) > jump_m) + 1
    out.n_jump_splits += int(cuts.size)
    for piece in np.split(np.arange(ci.size), cuts):
        tp = t_s[ci[piece]]
        if piece.size < 2 or tp[-1] - tp[0] < min_length_s:
            out.n_short += 1
            continue
        out.pieces.append((f"{other.sat}-{ref.sat}", tp, dd[piece], el[piece], g[piece]))


# --------------------------------------------------------------------------- baseline


@dataclass(frozen=True)
class _BaselineChoice:
    """The levelled arcs and antenna 2's position (ECEF, m) after the baseline check."""

    arcs: list[dict[str, Any]]
    pos2: NDArray[np.float64]
    baseline_m: float
    src2: str
    info: dict[str, Any]


def _choose_baseline(
    pieces: list[_Piece], inp: _Inputs, baseline: str, baseline_tolerance_m: float
) -> _BaselineChoice:
    """Estimate the baseline correction, apply it when the mode says so, level the arcs."""
    pos1, pos2 = inp.pos1, inp.pos2
    est, why_not = estimate_baseline_correction(
        [p[2] for p in pieces], [p[4] for p in pieces], pos1
    )
    use = est is not None and (
        baseline == "estimate"
        or (
            baseline == "auto"
            and est.length_m > baseline_tolerance_m
            and est.length_m > SIGNIFICANCE * est.sigma_length_m
        )
    )
    arcs: list[dict[str, Any]] = []
    for sats_name, tp, v, el, g in pieces:
        if use:
            assert est is not None
            v = v - est.correct(g)
        arcs.append(
            {
                "sats": sats_name,
                "t_gps_s": tp,
                "value_m": DA_SCALING * (v - v.mean()),
                "elevation_deg": el,
            }
        )
    pos2_used = pos2 + est.correction_m if use and est is not None else pos2
    info: dict[str, Any] = {
        "mode": baseline,
        "tolerance_m": float(baseline_tolerance_m),
        "used": bool(use),
        "given_baseline_m": inp.baseline_m,
        "given_positions_m": (pos1.tolist(), pos2.tolist()),
        "estimate": None if est is None else est.to_dict(),
        "estimated_baseline_m": None
        if est is None
        else float(np.linalg.norm(pos2 + est.correction_m - pos1)),
        "reason": why_not,
    }
    if not use:
        return _BaselineChoice(arcs, pos2_used, inp.baseline_m, inp.src2, info)
    baseline_m = float(np.linalg.norm(pos2_used - pos1))
    src2 = f"{inp.src2} corrected by the double-difference baseline estimate"
    return _BaselineChoice(arcs, pos2_used, baseline_m, src2, info)


# --------------------------------------------------------------------------- meta


def _station_meta(
    obs1: Observations, obs2: Observations, inp: _Inputs, choice: _BaselineChoice
) -> dict[str, Any]:
    """Describe the two stations: files, markers, baseline, positions and codes used."""
    return {
        "files": (obs1.path, obs2.path),
        "markers": (obs1.header.marker_name, obs2.header.marker_name),
        "baseline_m": choice.baseline_m,
        "positions_m": (inp.pos1.tolist(), choice.pos2.tolist()),
        "baseline_estimate": choice.info,
        "position_sources": (inp.src1, choice.src2),
        "codes": (inp.code1, inp.code2),
        "slip_codes": (inp.slip1, inp.slip2),
    }


def _slip_detection_text(slip_signal: str | None) -> str:
    """Say how the arcs were broken at cycle slips."""
    return (
        "geometry-free test with the second signal, gaps, loss of lock, power failure"
        if slip_signal is not None
        else "gaps, loss of lock and power failure only (no second signal)"
    ) + f"; double-difference jumps > {DD_JUMP_FRACTION:g} wavelength split arcs"


def _reference_meta(
    periods: list[tuple[SDArc, int, int]], t_s: NDArray[np.float64]
) -> list[dict[str, Any]]:
    """Return the reference satellite and its period (GPS s) of each reference period."""
    return [
        {
            "sat": ref.sat,
            "start_gps_s": float(t_s[k0]),
            "stop_gps_s": float(t_s[k1]),
        }
        for ref, k0, k1 in periods
    ]


def _clock_meta(
    orbit: OrbitSource,
    trk1: _Tracking,
    trk2: _Tracking,
    i1: NDArray[np.intp],
    i2: NDArray[np.intp],
) -> dict[str, Any]:
    """Describe the receiver-clock estimates (offsets in s)."""
    dt1, dt2 = trk1.dt_s, trk2.dt_s
    return {
        "method": _CLOCK_NOTE,
        "codes": (trk1.clock_code, trk2.clock_code),
        "satellite_clock": hasattr(orbit, "satellite_clock_s"),
        "median_offset_s": (float(np.median(dt1[i1])), float(np.median(dt2[i2]))),
        "max_abs_offset_s": (float(np.max(np.abs(dt1))), float(np.max(np.abs(dt2)))),
        "epochs_interpolated": (trk1.n_interpolated, trk2.n_interpolated),
    }


def _count_meta(
    n_common: int,
    trk1: _Tracking,
    trk2: _Tracking,
    sd: _SingleDifferences,
    dd: _DoubleDifferences,
    n_dd_arcs: int,
) -> dict[str, Any]:
    """Count the common epochs and the arcs kept, dropped and split at each stage."""
    return {
        "n_common_epochs": n_common,
        "n_tracking_arcs": (len(trk1.arcs), len(trk2.arcs)),
        "tracking_breaks": (dict(trk1.arcs.breaks), dict(trk2.arcs.breaks)),
        "n_sd_arcs": len(sd.arcs),
        "n_sd_arcs_dropped": sd.n_short,
        "n_dd_arcs": n_dd_arcs,
        "n_dd_arcs_dropped": dd.n_short,
        "n_dd_jump_splits": dd.n_jump_splits,
    }
