"""Continuous carrier-phase tracking arcs.

An arc is a stretch of epochs over which one satellite is tracked on both
signals of a pair with no gap, no loss of lock and no cycle slip, so that
its carrier-phase ambiguities are constant. Arcs are broken

* on a gap longer than ``gap_factor`` (1.5) sampling intervals;
* on an epoch flagged by the receiver: loss-of-lock indicator bit 0 on either
  signal, or RINEX epoch flag 1 (power failure);
* on a cycle slip detected from the data: a jump of the geometry-free phase
  ``L_a - L_b`` (metres) between consecutive epochs that departs from the
  local (running-median) rate by more than ``slip_threshold_m`` and by more
  than six robust standard deviations of the local jumps. This test
  is blind to slip pairs that hardly move ``L_a - L_b`` (GPS L1/L2: 5 and 4
  cycles move it by 2.5 cm, 9 and 7 by 3 mm); such steps stay in the arc;
* where the satellite is below the elevation mask (when an orbit is given).

Stretches shorter than ``min_length_s`` are dropped and counted.

When an orbit is given, :func:`find_arcs` first checks that it covers the
observations (:func:`psdbound.io.coverage.orbit_coverage`): an orbit file of
another day or without the system raises an :class:`InputError` that says
so, and satellites or epochs it leaves without a position are reported as
warnings (in :attr:`ArcSet.warnings`). :meth:`ArcSet.empty_reason` tells
why an arc set is empty.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view
from numpy.typing import NDArray

from psdbound.common.notices import warn
from psdbound.errors import InputError, NoDataError
from psdbound.io.coverage import OrbitCoverage, orbit_coverage
from psdbound.io.obs import Observations

__all__ = [
    "Arc",
    "ArcSet",
    "DEFAULT_SIGNALS",
    "SIGNAL_CANDIDATES",
    "default_pair",
    "detect_slips",
    "find_arcs",
    "require_arcs",
]

#: Phase signals of each system's dual-frequency pair, per carrier in order of preference
#: (RINEX 3 codes): without given signals the first of each that the file holds with phases
#: is used. Receivers differ in the tracking modes they record (a Trimble NetR9 writes
#: Galileo E1/E5a as L1X/L5X; a phone GPS L1C/L5Q; BeiDou-3 receivers B1C/B2a as L1P/L5P).
SIGNAL_CANDIDATES: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "G": (
        ("L1C", "L1W", "L1P", "L1X", "L1L", "L1S"),
        ("L2W", "L2P", "L2L", "L2X", "L2S", "L2C", "L2D", "L5Q", "L5X", "L5I"),
    ),
    "E": (("L1C", "L1X", "L1B"), ("L5Q", "L5X", "L5I", "L7Q", "L7X", "L7I", "L8Q", "L8X", "L8I")),
    "J": (("L1C", "L1X", "L1L", "L1S"), ("L2L", "L2X", "L2S", "L5Q", "L5X", "L5I")),
    "C": (
        ("L2I", "L2X", "L2Q", "L1P", "L1X", "L1D"),
        ("L7I", "L7X", "L7Q", "L6I", "L6X", "L6Q", "L5P", "L5X", "L5D", "L7D", "L7P"),
    ),
    "R": (("L1C", "L1P"), ("L2P", "L2C")),
}

#: Default signal pair per system for dual-frequency work (the first candidates).
DEFAULT_SIGNALS: dict[str, tuple[str, str]] = {
    system: (first[0], second[0]) for system, (first, second) in SIGNAL_CANDIDATES.items()
}

_SLIP_WINDOW = 11  # samples in the running median of the geometry-free rate
_NOISE_WINDOW = 61  # samples in the running robust noise level of the jumps
_NOISE_K = 6.0  # a slip must exceed this many robust standard deviations
_MEDIAN_CHUNK = 65536  # window samples partitioned at a time by the running median


@dataclass(frozen=True)
class Arc:
    """One continuous tracking arc of a satellite on a pair of signals.

    Attributes
    ----------
    sat : str
        Satellite, e.g. ``"G05"``.
    signals : tuple of str
        The two observation codes, e.g. ``("L1C", "L2W")``.
    arc_id : int
        Index of the arc within its :class:`ArcSet`.
    epoch_index : ndarray of int
        Indices of the arc's epochs in the source :class:`Observations`.
    t_gps_s : ndarray of float64
        Epochs, GPS seconds.
    phase_m : ndarray of float64, shape (n, 2)
        Carrier phases of the two signals in metres (ambiguities included).
    elevation_deg, azimuth_deg : ndarray of float64 or None
        Satellite elevation and azimuth seen from the receiver, degrees
        (None when no orbit was given).
    start_reason : str
        Why the arc starts where it does (``"first epoch"``, ``"gap"``,
        ``"loss of lock"``, ``"cycle slip"``, ``"power failure"``,
        ``"elevation mask"``).
    third_m : ndarray of float64 or None
        Carrier phase of a third signal at the arc's epochs, metres
        (:func:`psdbound.arcs.third.add_third_carrier`): NaN where it is missing
        and at the first epoch after each of its losses of lock or cycle
        slips, so that no difference of consecutive samples spans one; None
        without a third signal.
    """

    sat: str
    signals: tuple[str, str]
    arc_id: int
    epoch_index: NDArray[np.intp]
    t_gps_s: NDArray[np.float64]
    phase_m: NDArray[np.float64]
    elevation_deg: NDArray[np.float64] | None
    azimuth_deg: NDArray[np.float64] | None
    start_reason: str
    third_m: NDArray[np.float64] | None = None

    @property
    def n(self) -> int:
        """Number of epochs."""
        return int(self.t_gps_s.size)

    @property
    def duration_s(self) -> float:
        """Time from first to last epoch, seconds."""
        return float(self.t_gps_s[-1] - self.t_gps_s[0])

    @property
    def geometry_free_m(self) -> NDArray[np.float64]:
        """Phase difference ``L_a - L_b`` in metres."""
        return self.phase_m[:, 0] - self.phase_m[:, 1]


@dataclass(frozen=True)
class ArcSet:
    """The arcs of one observation file, system and signal pair.

    Attributes
    ----------
    path : str
        Source observation file.
    system : str
        Satellite system letter.
    signals : tuple of str
        Signal pair.
    interval_s : float
        Sampling interval, seconds.
    min_length_s : float
        Arcs shorter than this were dropped.
    arcs : tuple of Arc
        The kept arcs, ordered by satellite then time.
    breaks : collections.Counter
        Number of arc breaks per reason (over all satellites).
    dropped : collections.Counter
        Number of stretches dropped per reason (``"shorter than minimum"``).
    dropped_s : float
        Total duration of the dropped stretches, seconds.
    warnings : tuple of str
        What the orbit left uncovered (satellites or epochs without a
        position), one line each, naming the orbit file; also issued as
        :class:`~psdbound.common.notices.PsdboundWarning`.
    tracked : tuple of str or None
        Satellites tracked on both signals at two or more common epochs
        (None when unknown, e.g. an ArcSet built elsewhere).
    below_mask : tuple of str
        Tracked satellites never above the elevation mask (or never with an
        orbit position), hence without any arc.
    elevation_mask_deg : float or None
        The elevation mask applied, degrees (None without an orbit).
    phase_counts : tuple of int or None
        Number of (satellite, epoch) samples with a phase on each signal.
    coverage : OrbitCoverage or None
        The orbit's coverage of the observations (None without an orbit).
    third_signal : str or None
        Phase code of the third signal the arcs carry in
        :attr:`Arc.third_m` (None: none; :func:`psdbound.arcs.third.add_third_carrier`).
    samples : dict of str to int
        (Satellite, epoch) samples with both phases (``"both_signals"``), of
        them without an orbit position (``"without_orbit"``) and below the
        elevation mask (``"below_mask"``): what the data offered before arcs
        were formed (:func:`psdbound.pipeline.verdict` counts the losses
        from there).
    glonass_channels : dict of str to int
        GLONASS FDMA frequency numbers used for the phases (observation
        header, completed from the orbit's GLONASS records); pass them to
        :func:`psdbound.io.signals.wavelength_m` for GLONASS signals.
    """

    path: str
    system: str
    signals: tuple[str, str]
    interval_s: float
    min_length_s: float
    arcs: tuple[Arc, ...]
    breaks: Counter = field(default_factory=Counter)
    dropped: Counter = field(default_factory=Counter)
    dropped_s: float = 0.0
    warnings: tuple[str, ...] = ()
    tracked: tuple[str, ...] | None = None
    below_mask: tuple[str, ...] = ()
    elevation_mask_deg: float | None = None
    phase_counts: tuple[int, int] | None = None
    coverage: OrbitCoverage | None = None
    glonass_channels: dict[str, int] = field(default_factory=dict)
    samples: dict[str, int] = field(default_factory=dict)
    third_signal: str | None = None

    def __len__(self) -> int:
        return len(self.arcs)

    def __iter__(self) -> Iterator[Arc]:
        return iter(self.arcs)

    def __getitem__(self, i: int) -> Arc:
        return self.arcs[i]

    def azimuth_at(self, sat: str, t_gps_s: NDArray[np.float64]) -> NDArray[np.float64]:
        """Return the azimuth of ``sat`` at the epochs ``t_gps_s`` from its arcs, degrees.

        Parameters
        ----------
        sat : str
            Satellite (``"G05"``).
        t_gps_s : ndarray
            Epochs, GPS seconds.

        Returns
        -------
        ndarray
            The arc's azimuth at the epoch nearest each time within half an
            interval; NaN where no arc of ``sat`` holds one (or no orbit).
        """
        t = np.asarray(t_gps_s, dtype=float)
        az = np.full(t.size, np.nan)
        for a in self.arcs:
            if a.sat != sat or a.azimuth_deg is None:
                continue
            j = np.clip(np.searchsorted(a.t_gps_s, t), 0, a.t_gps_s.size - 1)
            j = np.where(
                np.abs(a.t_gps_s[np.maximum(j - 1, 0)] - t) < np.abs(a.t_gps_s[j] - t),
                np.maximum(j - 1, 0),
                j,
            )
            hit = np.abs(a.t_gps_s[j] - t) < 0.5 * self.interval_s
            az[hit] = a.azimuth_deg[j[hit]]
        return az

    @property
    def total_duration_s(self) -> float:
        """Sum of the kept arcs' durations, seconds."""
        return float(sum(a.duration_s for a in self.arcs))

    def summary(self) -> str:
        """Describe the arcs in a few lines: counts, durations and break reasons."""
        lines = [
            f"{self.system} {self.signals[0]}-{self.signals[1]}: {len(self.arcs)} arcs "
            f">= {self.min_length_s / 60:g} min, {self.total_duration_s / 3600:.2f} h in total "
            f"(interval {self.interval_s:g} s)",
            "  breaks: "
            + (", ".join(f"{k} {v}" for k, v in sorted(self.breaks.items())) or "none"),
            f"  dropped: {sum(self.dropped.values())} short stretches "
            f"({self.dropped_s / 3600:.2f} h)",
        ]
        return "\n".join(lines)

    def empty_reason(self) -> str:
        """Say why there is no arc ('' when there are arcs).

        Returns
        -------
        str
            One of: no satellite tracked on both signals at common epochs
            (naming the signal without phase, if any); tracked satellites
            never above the elevation mask or without an orbit position; all
            tracking stretches shorter than the minimum length.

        """
        if self.arcs:
            return ""
        a, b = self.signals
        if self.dropped:
            return (
                f"no arc long enough: all {sum(self.dropped.values())} tracking stretches of "
                f"{self.system} {a}-{b} are shorter than {self.min_length_s / 60:g} min"
            )
        both = f"no satellite tracked both {a} and {b} ({self.system}) at the same epochs"
        if not self.tracked:
            n_a, n_b = self.phase_counts if self.phase_counts is not None else (1, 0)
            if n_a and not n_b:
                return f"{both}: the second frequency is missing"
            if n_b and not n_a:
                return f"{both}: the first frequency is missing"
            if not (n_a or n_b):
                return f"{both}: neither signal has a phase"
            return f"{both}: each signal was tracked, but never together for two epochs"
        below = self.below_mask
        no_orbit: tuple[str, ...] = ()
        if self.coverage is not None and self.system in self.coverage.systems:
            sc = self.coverage.systems[self.system]
            no_orbit = tuple(s for s in below if s in sc.missing or s in sc.outside)
        mask = self.elevation_mask_deg or 0.0
        text = (
            f"no satellite tracked on both {a} and {b} ({self.system}) is above the "
            f"elevation mask of {mask:g} deg at any epoch ({len(below)} tracked)"
        )
        if no_orbit:
            text += f"; the orbit gives no position for {' '.join(no_orbit)}"
        return text


#: Samples above which the running median imports scipy.ndimage (150 ms once) to run faster.
_SCIPY_MEDIAN_FROM = 4000


def _running_median(x: NDArray[np.float64], size: int) -> NDArray[np.float64]:
    """Return the running median of ``x`` over ``size`` samples, the edges mirrored."""
    # scipy.ndimage.median_filter(x, size, mode="mirror") without importing scipy.ndimage
    # (150 ms): numpy's "reflect" is scipy's "mirror" (d c b | a b c d | c b a), an even size
    # takes the upper middle value and reaches one sample further back; equal while
    # size // 2 < len(x), as for min(window, len(x) | 1) (tests/io/test_running_median.py)
    if x.size > _SCIPY_MEDIAN_FROM:  # long 1 Hz arcs: scipy's filter is 2-4 times faster
        from scipy.ndimage import median_filter

        return median_filter(x, size=size, mode="mirror")
    half = size // 2
    windows = sliding_window_view(np.pad(x, (half, size - 1 - half), mode="reflect"), size)
    out = np.empty(x.size)
    step = max(1, _MEDIAN_CHUNK // size)  # rows at a time: the partitioned copy stays small
    for lo in range(0, x.size, step):
        out[lo : lo + step] = np.partition(windows[lo : lo + step], half, axis=1)[:, half]
    return out


def detect_slips(gf_m: NDArray[np.float64], threshold_m: float) -> NDArray[np.bool_]:
    """Return a boolean per epoch: a slip between the previous epoch and this one.

    The jump ``d - median(d)`` must exceed ``threshold_m`` and ``_NOISE_K``
    robust standard deviations of the local jumps (running median of
    ``|d - median(d)|`` over ``_NOISE_WINDOW`` samples, times 1.4826), so
    that noisy low-elevation stretches are not cut into pieces.
    """
    out = np.zeros(gf_m.size, dtype=bool)
    if gf_m.size < 3:
        return out
    d = np.diff(gf_m)
    ref = _running_median(d, min(_SLIP_WINDOW, d.size | 1))
    r = np.abs(d - ref)
    noise = 1.4826 * _running_median(r, min(_NOISE_WINDOW, r.size | 1))
    out[1:] = r > np.maximum(threshold_m, _NOISE_K * noise)
    return out


def default_pair(obs: Observations, system: str) -> tuple[str, str]:
    """Return the system's dual-frequency pair the file holds: per carrier, the first candidate.

    Parameters
    ----------
    obs : Observations
        The observations.
    system : str
        Satellite system letter.

    Returns
    -------
    tuple of str
        RINEX 3 phase codes, one per carrier of :data:`SIGNAL_CANDIDATES`:
        the first that the file holds with at least one phase (the default
        pair :data:`DEFAULT_SIGNALS` when it does); where none has phases,
        the first the file lists (its arcs are then empty, and say why).

    Raises
    ------
    InputError
        No candidate of a carrier is in the file (the message lists the
        file's codes and how to choose).
    """
    if system not in SIGNAL_CANDIDATES:
        raise InputError(f"no default signal pair for system {system!r}; give signals")
    pair = []
    for band in SIGNAL_CANDIDATES[system]:
        held = [c for c in band if obs.phase_count(system, c) > 0]
        # none with phases: the first the file lists, whose empty arcs say what is missing
        held = held or [c for c in band if obs.file_code(system, c) is not None]
        if not held:
            raise InputError(
                f"none of the phase signals {', '.join(band)} is in the file for "
                f"system {system!r}; it holds {' '.join(obs.codes(system))}: "
                "give the pair with --signals",
                path=obs.path,
            )
        pair.append(held[0])
    return pair[0], pair[1]


def _signal_pair(obs: Observations, signals: Sequence[str] | None, system: str) -> tuple[str, str]:
    """Return the file's codes of the phase pair (the system's default when None), checked."""
    if signals is None:
        signals = default_pair(obs, system)
    if len(signals) != 2:
        raise InputError(f"expected a pair of phase signals, got {tuple(signals)}")
    code_a, code_b = (obs.resolve_code(system, s) for s in signals)
    if not (code_a.startswith("L") and code_b.startswith("L")):
        raise InputError(f"arcs need carrier-phase codes (L..), got {code_a} and {code_b}")
    return code_a, code_b


def _receiver_position(
    obs: Observations, receiver_xyz_m: NDArray[np.float64] | None
) -> NDArray[np.float64]:
    """Return the receiver's ECEF position (m): the one given, else the header's approximate one."""
    if receiver_xyz_m is None:
        receiver_xyz_m = obs.header.approx_position_m
    if receiver_xyz_m is None:
        raise InputError(
            "no receiver position: the header's APPROX POSITION XYZ is missing, zero or not "
            "near the Earth's surface; give receiver_xyz_m",
            path=obs.path,
        )
    return receiver_xyz_m


def _orbit_coverage(
    obs: Observations, orbit: object, system: str, satellites: Sequence[str] | None
) -> tuple[Observations, OrbitCoverage, tuple[str, ...]]:
    """Check the orbit covers the observations, warn about its gaps; GLONASS channels added."""
    coverage = orbit_coverage(orbit, obs, system, satellites=satellites)
    coverage.require(system)
    where = coverage.orbit_path or None
    # stacklevel: warn, this generator, this function, find_arcs, the caller of find_arcs
    notes = tuple(warn(m, path=where, stacklevel=4) for m in coverage.warnings(system))
    channels = getattr(orbit, "glonass_channels", None)
    if system == "R" and channels:
        obs = obs.with_glonass_channels(channels)
    return obs, coverage, notes


@dataclass
class _Track:
    """One satellite's epochs with both phases: indices, times (s), phases (m), el/az (deg)."""

    sat: str
    idx: NDArray[np.intp]
    t: NDArray[np.float64]
    la: NDArray[np.float64]
    lb: NDArray[np.float64]
    el: NDArray[np.float64] | None = None
    az: NDArray[np.float64] | None = None


@dataclass
class _Tally:
    """What find_arcs gathers over the satellites: arcs, breaks, drops, sample counts."""

    arcs: list[Arc] = field(default_factory=list)
    breaks: Counter = field(default_factory=Counter)
    dropped: Counter = field(default_factory=Counter)
    dropped_s: float = 0.0
    tracked: list[str] = field(default_factory=list)
    below: list[str] = field(default_factory=list)
    counts: list[int] = field(default_factory=lambda: [0, 0])
    samples: dict[str, int] = field(
        default_factory=lambda: {"both_signals": 0, "without_orbit": 0, "below_mask": 0}
    )


def _track(obs: Observations, sat: str, codes: tuple[str, str], tally: _Tally) -> _Track | None:
    """Return the epochs where ``sat`` has both phases (None: fewer than two), counted."""
    la = obs.phase_m(sat, codes[0])
    lb = obs.phase_m(sat, codes[1])
    fa, fb = np.isfinite(la), np.isfinite(lb)
    tally.counts[0] += int(fa.sum())
    tally.counts[1] += int(fb.sum())
    idx = np.flatnonzero(fa & fb)
    if idx.size < 2:
        return None
    tally.tracked.append(sat)
    tally.samples["both_signals"] += int(idx.size)
    return _Track(sat, idx, obs.t_gps_s[idx], la, lb)


def _below_mask(
    track: _Track,
    orbit: object | None,
    receiver_xyz_m: NDArray[np.float64] | None,
    elevation_mask_deg: float,
    samples: dict[str, int],
) -> NDArray[np.bool_]:
    """Set the track's elevation and azimuth (deg); return where it is below the mask."""
    if orbit is None:
        return np.zeros(track.idx.size, dtype=bool)
    from psdbound.io.geometry import satellite_azel

    az, el = satellite_azel(orbit, track.sat, track.t, np.asarray(receiver_xyz_m, dtype=float))
    track.az, track.el = az, el
    samples["without_orbit"] += int(np.isnan(el).sum())
    samples["below_mask"] += int((el < elevation_mask_deg).sum())
    return ~(el >= elevation_mask_deg)  # NaN (no orbit) counts as below the mask


def _break_reasons(
    track: _Track,
    lli: tuple[NDArray[np.int8], NDArray[np.int8]],
    power_fail: NDArray[np.bool_],
    max_step_s: float,
    low: NDArray[np.bool_],
) -> tuple[NDArray[np.object_], NDArray[np.bool_]]:
    """Return why an arc starts at each epoch ('' where none) and where stretches start."""
    lli_a, lli_b = lli
    lost = ((lli_a > 0) & (lli_a & 1 > 0)) | ((lli_b > 0) & (lli_b & 1 > 0))
    gap = np.zeros(track.idx.size, dtype=bool)
    gap[1:] = np.diff(track.t) > max_step_s
    reason = np.full(track.idx.size, "", dtype=object)
    # assign reasons in increasing priority; a later assignment wins
    reason[power_fail] = "power failure"
    reason[lost] = "loss of lock"
    reason[gap] = "gap"
    reason[0] = "first epoch"
    starts = (reason != "") | np.r_[True, low[:-1] & ~low[1:]]
    reason[np.r_[False, low[:-1] & ~low[1:]] & (reason == "")] = "elevation mask"
    return reason, starts


def _mark_slips(
    reason: NDArray[np.object_],
    starts: NDArray[np.bool_],
    gf: NDArray[np.float64],
    low: NDArray[np.bool_],
    slip_threshold_m: float,
) -> None:
    """Set 'cycle slip' where ``gf`` (m) jumps, tested inside each stretch above the mask."""
    seg_id = np.cumsum(starts)
    for s in np.unique(seg_id):
        m = np.flatnonzero((seg_id == s) & ~low)
        if m.size < 3:
            continue
        slip = detect_slips(gf[m], slip_threshold_m)
        reason[m[slip]] = "cycle slip"


def _cut_arcs(
    tally: _Tally,
    track: _Track,
    codes: tuple[str, str],
    reason: NDArray[np.object_],
    keep: NDArray[np.bool_],
    min_length_s: float,
) -> None:
    """Cut the kept epochs into arcs at each reason; count the breaks and short stretches."""
    t, idx = track.t, track.idx
    starts = (reason != "") & keep
    starts |= keep & np.r_[True, ~keep[:-1]]
    bounds = np.flatnonzero(starts)
    for b0, b1 in zip(bounds, np.r_[bounds[1:], idx.size], strict=True):
        seg = np.arange(b0, b1)
        seg = seg[keep[seg]]
        r = reason[b0] or "elevation mask"
        if b0 > 0:
            tally.breaks[r] += 1
        if seg.size < 2 or t[seg[-1]] - t[seg[0]] < min_length_s:
            if seg.size:
                tally.dropped["shorter than minimum"] += 1
                tally.dropped_s += float(t[seg[-1]] - t[seg[0]])
            continue
        tally.arcs.append(
            Arc(
                sat=track.sat,
                signals=codes,
                arc_id=len(tally.arcs),
                epoch_index=idx[seg],
                t_gps_s=t[seg],
                phase_m=np.column_stack([track.la[idx[seg]], track.lb[idx[seg]]]),
                elevation_deg=None if track.el is None else track.el[seg],
                azimuth_deg=None if track.az is None else track.az[seg],
                start_reason=r,
            )
        )


def find_arcs(
    obs: Observations,
    signals: Sequence[str] | None = None,
    *,
    system: str = "G",
    orbit: object | None = None,
    receiver_xyz_m: NDArray[np.float64] | None = None,
    min_length_s: float = 1800.0,
    gap_factor: float = 1.5,
    slip_threshold_m: float = 0.04,
    elevation_mask_deg: float = 0.0,
    satellites: Sequence[str] | None = None,
) -> ArcSet:
    """Split observations into continuous dual-signal tracking arcs.

    Parameters
    ----------
    obs : Observations
        Observations from :func:`psdbound.io.read_obs`.
    signals : sequence of two str, optional
        Phase codes of the pair, e.g. ``("L1C", "L2W")``; RINEX 2 files
        accept their own codes or the RINEX 3 equivalents. Defaults to
        :data:`DEFAULT_SIGNALS` for the system.
    system : str, default "G"
        Satellite system letter.
    orbit : OrbitSource, optional
        Navigation or precise orbit (anything with ``positions_ecef_m``);
        when given, arcs carry elevation and azimuth.
    receiver_xyz_m : ndarray of shape (3,), optional
        Receiver ECEF position in metres; defaults to the header's
        approximate position.
    min_length_s : float, default 1800
        Minimum arc duration in seconds (30 min).
    gap_factor : float, default 1.5
        A gap longer than ``gap_factor`` sampling intervals breaks an arc.
    slip_threshold_m : float, default 0.04
        Geometry-free jump, in metres, beyond the local rate that counts as a
        cycle slip. The smallest common GPS L1/L2 slip (one cycle on both)
        moves ``L1 - L2`` by 0.054 m.
    elevation_mask_deg : float, default 0
        Epochs below this elevation are excluded (needs ``orbit``).
    satellites : sequence of str, optional
        Restrict to these satellites.

    Returns
    -------
    ArcSet
        The arcs, with break and drop statistics.

    Raises
    ------
    InputError
        Unknown signals, a missing second signal, no receiver position
        when an orbit is given, or an orbit that gives no position for any
        observed satellite of the system (a file of another day, or without
        the system; the message says which).

    Warns
    -----
    PsdboundWarning
        When the orbit leaves some observed satellites or epochs without a
        position (also in :attr:`ArcSet.warnings`).

    See Also
    --------
    psdbound.isolation.isolate_dual_frequency : The multipath of these arcs.
    read_obs, read_orbit : The inputs.

    References
    ----------
    .. [1] Blewitt, G. (1990). An automatic editing algorithm for GPS data.
       *Geophysical Research Letters*, 17(3), 199-202 (slips in the
       geometry-free combination).

    Examples
    --------
    >>> from psdbound.arcs import find_arcs
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()
    >>> obs, nav = read_obs(d.obs_paths[0], systems="G"), read_orbit(d.nav_path)
    >>> arcs = find_arcs(obs, ("L1C", "L2W"), orbit=nav, elevation_mask_deg=10)
    >>> len(arcs) > 10 and all(a.duration_s >= 1800 for a in arcs)
    True
    """
    code_a, code_b = _signal_pair(obs, signals, system)
    block = obs.blocks[system]
    interval_s = obs.interval_s
    coverage = None
    notes: tuple[str, ...] = ()
    if orbit is not None:
        receiver_xyz_m = _receiver_position(obs, receiver_xyz_m)
        obs, coverage, notes = _orbit_coverage(obs, orbit, system, satellites)

    sats = block.sats if satellites is None else [s for s in block.sats if s in satellites]
    ka, kb = block.codes.index(code_a), block.codes.index(code_b)
    power_fail = obs.epoch_flag == 1
    tally = _Tally()
    for sat in sats:
        track = _track(obs, sat, (code_a, code_b), tally)
        if track is None:
            continue
        i = block.sats.index(sat)
        low = _below_mask(track, orbit, receiver_xyz_m, elevation_mask_deg, tally.samples)
        lli = (block.lli[track.idx, i, ka], block.lli[track.idx, i, kb])
        reason, starts = _break_reasons(
            track, lli, power_fail[track.idx], gap_factor * interval_s, low
        )
        # cycle slips, tested inside each stretch delimited so far
        gf = track.la[track.idx] - track.lb[track.idx]
        _mark_slips(reason, starts, gf, low, slip_threshold_m)
        keep = ~low
        if not keep.any():
            tally.below.append(sat)
            continue  # never above the mask: no arc
        _cut_arcs(tally, track, (code_a, code_b), reason, keep, min_length_s)
    result = ArcSet(
        path=obs.path,
        system=system,
        signals=(code_a, code_b),
        interval_s=interval_s,
        min_length_s=min_length_s,
        arcs=tuple(tally.arcs),
        breaks=tally.breaks,
        dropped=tally.dropped,
        dropped_s=tally.dropped_s,
        warnings=notes,
        tracked=tuple(tally.tracked),
        below_mask=tuple(tally.below),
        elevation_mask_deg=None if orbit is None else float(elevation_mask_deg),
        phase_counts=(tally.counts[0], tally.counts[1]),
        coverage=coverage,
        glonass_channels=dict(obs.header.glonass_channels) if system == "R" else {},
        samples=tally.samples,
    )
    return result


def require_arcs(arcs: ArcSet) -> ArcSet:
    """Return ``arcs`` or raise :class:`NoDataError` when it holds none.

    The message says how many stretches were too short and the minimum.
    """
    if len(arcs):
        return arcs
    raise NoDataError(
        f"no arc long enough: {sum(arcs.dropped.values())} tracking stretches of "
        f"{arcs.system} {arcs.signals[0]}-{arcs.signals[1]} are all shorter than the "
        f"minimum of {arcs.min_length_s / 60:g} min",
        path=arcs.path,
    )
