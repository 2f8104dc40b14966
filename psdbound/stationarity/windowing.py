"""The thesis's slide/trim windowing of arcs into stationary windows (figure 4.4).

Index conventions (the thesis's ``floor(p * index)`` rules depend on where
indices start, and stall at an origin of 0 or 1): here every window is a
pair of 0-based inclusive sample indices ``[s, e]`` inside its arc, and the
coefficients act on the **current window length** ``n_w = e - s + 1``,
measured from the window start -- which is what the thesis describes in
words ("these sliding and trimming coefficients ... depend on the current
window size"):

* trim: ``e <- s + floor(p_trim * n_w) - 1`` (keep the first 80 %);
* slide: ``s <- s + ceil((p_slide - 1) * n_w)``, ``e <- last index of the arc``
  (move the start by 20 % of the window and reopen to the arc end).

Algorithm, per arc, starting from the whole arc, with ``L`` the minimum
window length in samples: test the window; if stationary, keep it, then
slide if the arc end is not reached and the slid window is ``>= L``, else
stop; if not stationary, trim if the trimmed window is ``>= L``, else slide
if the end is not reached and the slid window is ``>= L``, else stop.
Samples covered by no stationary window are reported, not silently dropped.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError, NoDataError
from psdbound.isolation.series import MultipathSeries
from psdbound.stationarity.coverage import covered_time_s
from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping
from psdbound.stationarity.options import STATIONARITY_TESTS
from psdbound.stationarity.spectral import min_samples, test_spectral_homogeneity
from psdbound.stationarity.thesis_test import StationarityTest, test_stationarity

__all__ = [
    "STATIONARITY_TESTS",
    "Window",
    "WindowSet",
    "find_stationary_windows",
    "window_arc",
]

#: Stationarity tests :func:`window_arc` can use.


@dataclass(frozen=True)
class Window:
    """A stationary window.

    Attributes
    ----------
    arc_id : int
        Arc of the source series.
    sats : str
        Satellite(s) of the arc.
    start, stop : int
        0-based inclusive sample indices within the arc.
    offset : int
        Index of the arc's first sample in the series arrays.
    t_start_gps_s, t_stop_gps_s : float
        First and last epoch, GPS seconds.
    levene_p, ks_p : float
        p-values of the tests that accepted the window.
    """

    arc_id: int
    sats: str
    start: int
    stop: int
    offset: int
    t_start_gps_s: float
    t_stop_gps_s: float
    levene_p: float
    ks_p: float

    @property
    def n(self) -> int:
        """Number of samples."""
        return self.stop - self.start + 1

    @property
    def duration_s(self) -> float:
        """First to last epoch, seconds."""
        return self.t_stop_gps_s - self.t_start_gps_s

    def slice(self) -> slice:
        """Slice of the window in the series arrays."""
        return slice(self.offset + self.start, self.offset + self.stop + 1)


@dataclass(frozen=True)
class WindowSet:
    """Stationary windows of a multipath series, with what they leave out.

    Attributes
    ----------
    windows : tuple of Window
        Stationary windows (they may overlap, as in the thesis).
    mapped_m : ndarray
        The mapped (elevation-normalised) series the windows index into.
    interval_s : float
        Sampling interval, seconds.
    mapping : ElevationMapping
        The mapping applied.
    params : dict
        ``alpha``, ``p_slide``, ``p_trim``, ``min_length_s``, ``center``.
    n_tests : int
        Stationarity tests run.
    uncovered : tuple of (int, str, float, float)
        ``(arc_id, sats, t_start_gps_s, t_stop_gps_s)`` of every stretch of
        at least two samples covered by no stationary window.
    uncovered_s : float
        Their total duration, seconds.
    short_s : float
        Part of ``uncovered_s`` in arcs shorter than the minimum window:
        never tested (too short), as opposed to tested and rejected.
    """

    windows: tuple[Window, ...]
    mapped_m: NDArray[np.float64]
    interval_s: float
    mapping: ElevationMapping
    params: dict[str, Any] = field(default_factory=dict)
    n_tests: int = 0
    uncovered: tuple[tuple[int, str, float, float], ...] = ()
    uncovered_s: float = 0.0
    short_s: float = 0.0

    @property
    def covered_s(self) -> float:
        """Time in the windows, every sample once (:func:`covered_time_s`), seconds."""
        spans = ((w.arc_id, w.t_start_gps_s, w.t_stop_gps_s) for w in self.windows)
        return covered_time_s(spans, self.interval_s)

    @property
    def rejected_s(self) -> float:
        """Time in arcs long enough to test that no stationary window covers, seconds."""
        return max(self.uncovered_s - self.short_s, 0.0)

    def __len__(self) -> int:
        return len(self.windows)

    def data(self, k: int) -> NDArray[np.float64]:
        """Return the mapped samples of window ``k``, metres."""
        return self.mapped_m[self.windows[k].slice()]

    @property
    def total_duration_s(self) -> float:
        """Sum of window durations (overlaps counted twice), seconds."""
        return float(sum(w.duration_s for w in self.windows))

    def summary(self) -> str:
        """Describe the windows in a few lines."""
        d = np.array([w.duration_s for w in self.windows]) / 60 if self.windows else np.zeros(1)
        return (
            f"{len(self.windows)} stationary windows (alpha {self.params.get('alpha')}, "
            f"p_slide {self.params.get('p_slide')}, p_trim {self.params.get('p_trim')}, "
            f"L {self.params.get('min_length_s'):g} s) from {self.n_tests} tests; "
            f"durations {d.min():.1f}-{d.max():.1f} min; never stationary: "
            f"{len(self.uncovered)} stretches, {self.uncovered_s / 60:.1f} min"
        )


def window_arc(
    x: NDArray[np.float64],
    min_length: int,
    *,
    alpha: float = 0.05,
    p_slide: float = 1.2,
    p_trim: float = 0.8,
    center: str = "mean",
    test: str = "thesis",
    overlap: bool = True,
) -> tuple[list[tuple[int, int, float, float]], int]:
    """Run the slide/trim algorithm on one arc.

    Parameters
    ----------
    x : ndarray
        The arc's (mapped) samples.
    min_length : int
        Minimum window length ``L``, samples (>= 8).
    alpha : float, default 0.05
        Significance level of the stationarity tests.
    p_slide : float, default 1.2
        Slide coefficient (> 1).
    p_trim : float, default 0.8
        Trim coefficient (in (0, 1)).
    center : str, default "mean"
        Levene centre.
    test : {"thesis", "spectral"}, default "thesis"
        Levene then K-S (:func:`~psdbound.stationarity.test_stationarity`), or
        the spectral-homogeneity test valid for correlated samples
        (:func:`~psdbound.stationarity.test_spectral_homogeneity`).
    overlap : bool, default True
        True: the thesis's slide/trim rule (after a stationary window the
        start moves by ``p_slide - 1`` of its length, so windows overlap).
        False: binary segmentation (Vostrikova 1981) -- a segment that fails
        the test is split in two halves, each tested in turn, down to
        segments shorter than ``2 L``; the windows are disjoint (what
        pooling the windows' spectra needs) and no remainder is left
        untested. ``p_slide`` and ``p_trim`` are not used.

    Returns
    -------
    windows : list of (start, stop, p1, p2)
        0-based inclusive indices of the stationary windows and the tests'
        p-values (Levene and K-S; for ``test="spectral"`` both are the
        spectral test's p-value).
    n_tests : int
        Number of tests run.
    """
    _check_window_options(min_length, p_slide, p_trim, test)
    if x.size < min_length:
        return [], 0
    run = _tester(x, test=test, alpha=alpha, center=center)
    if not overlap:  # binary segmentation: disjoint windows, no untested remainders
        return _bisect(run, x.size - 1, min_length)
    return _slide_trim(run, x.size - 1, min_length, p_slide, p_trim)


#: A stationarity test of the samples ``a..b`` (inclusive) of one arc.
_Run = Callable[[int, int], StationarityTest]


def _check_window_options(min_length: int, p_slide: float, p_trim: float, test: str) -> None:
    """Check the windowing coefficients, the minimum length (samples) and the test's name."""
    if not p_slide > 1.0 or not 0.0 < p_trim < 1.0:
        raise InputError(f"need p_slide > 1 and 0 < p_trim < 1; got {p_slide}, {p_trim}")
    if min_length < 8:
        raise InputError(f"minimum window length must be >= 8 samples, got {min_length}")
    if test not in STATIONARITY_TESTS:
        raise InputError(f"unknown stationarity test {test!r}; use {', '.join(STATIONARITY_TESTS)}")


def _tester(x: NDArray[np.float64], *, test: str, alpha: float, center: str) -> _Run:
    """Return the stationarity test of a stretch of ``x`` (inclusive sample indices)."""

    def run(a: int, b: int) -> StationarityTest:
        if test == "spectral":
            sp = test_spectral_homogeneity(x[a : b + 1], alpha=alpha)
            return StationarityTest(sp.stationary, sp.p_value, sp.p_value, alpha)
        return test_stationarity(x[a : b + 1], alpha=alpha, center=center)

    return run


def _bisect(
    run: _Run, last: int, min_length: int
) -> tuple[list[tuple[int, int, float, float]], int]:
    """Binary segmentation of samples ``0..last``: disjoint windows and the number of tests."""
    out: list[tuple[int, int, float, float]] = []
    n_tests = 0
    todo = [(0, last)]
    while todo:
        a, b = todo.pop()
        res = run(a, b)
        n_tests += 1
        if res.stationary:
            out.append((a, b, res.levene_p, float(res.ks_p)))
        elif b - a + 1 >= 2 * min_length:
            mid = (a + b) // 2
            todo += [(mid + 1, b), (a, mid)]
    return sorted(out), n_tests


def _slide_trim(
    run: _Run, last: int, min_length: int, p_slide: float, p_trim: float
) -> tuple[list[tuple[int, int, float, float]], int]:
    """Apply the thesis's slide/trim rule to samples ``0..last``; return windows, test count."""
    s, e = 0, last
    out: list[tuple[int, int, float, float]] = []
    n_tests = 0
    while True:
        n_w = e - s + 1
        res = run(s, e)
        n_tests += 1
        end_reached = e == last
        s_slid = s + math.ceil((p_slide - 1.0) * n_w)
        can_slide = (not end_reached) and (last - s_slid + 1 >= min_length)
        if res.stationary:
            out.append((s, e, res.levene_p, float(res.ks_p)))
            if can_slide:
                s, e = s_slid, last
                continue
            break
        e_trim = s + math.floor(p_trim * n_w) - 1
        if e_trim - s + 1 >= min_length:
            e = e_trim
        elif can_slide:
            s, e = s_slid, last
        else:
            break
    return out, n_tests


def find_stationary_windows(
    series: MultipathSeries,
    *,
    mapping: ElevationMapping | None = None,
    alpha: float = 0.05,
    p_slide: float = 1.2,
    p_trim: float = 0.8,
    min_length_s: float = 600.0,
    center: str = "mean",
    test: str = "spectral",
    overlap: bool = False,
) -> WindowSet:
    """Map a multipath series by elevation and window every arc into stationary pieces.

    Parameters
    ----------
    series : MultipathSeries
        Isolated multipath (DF or DA).
    mapping : ElevationMapping, optional
        Elevation normalisation; default the thesis's ``(1, 29, 10 deg)``.
        Use :func:`psdbound.stationarity.fit_mapping` for fitted parameters.
    alpha : float, default 0.05
        Significance level of the stationarity test.
    p_slide, p_trim : float, default 1.2, 0.8
        Thesis windowing coefficients (see the module docstring).
    min_length_s : float, default 600
        Minimum window length ``L``, seconds. With ``test="spectral"`` it is
        raised to the test's minimum (:func:`psdbound.stationarity.spectral.min_samples`,
        68 samples: 34 min at 30 s sampling); ``params["effective_min_length_s"]``
        records the length used.
    center : str, default "mean"
        Levene centre ("mean": Levene 1960; "median": Brown-Forsythe).
    test : {"spectral", "thesis"}, default "spectral"
        Stationarity test of each candidate window (see :func:`window_arc`):
        valid for correlated samples, or the thesis's Levene then K-S.
    overlap : bool, default False
        Disjoint tiling (what the pooled bound needs) or the thesis's
        overlapping slide rule (see :func:`window_arc`).

    Returns
    -------
    WindowSet
        Windows, the mapped series and the never-stationary stretches.

    Raises
    ------
    NoDataError
        If no arc is at least ``min_length_s`` long.

    See Also
    --------
    psdbound.stationarity.test_spectral_homogeneity : The test of each split.
    psdbound.spectra.BoundModel : Bound the windows found.

    References
    ----------
    .. [1] Priestley, M. B., & Subba Rao, T. (1969). A test for non-stationarity
       of time-series. *JRSS B*, 31(1), 140-149.
    .. [2] Vostrikova, L. J. (1981). Detecting "disorder" in multidimensional
       random processes. *Soviet Mathematics Doklady*, 24, 55-59 (binary
       segmentation).
    .. [3] docs/method/stationarity.rst.

    Examples
    --------
    >>> from psdbound.arcs import find_arcs
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.isolation import isolate_dual_frequency
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()
    >>> arcs = find_arcs(read_obs(d.obs_paths[0], systems="G"), ("L1C", "L2W"),
    ...                  orbit=read_orbit(d.nav_path))
    >>> windows = find_stationary_windows(isolate_dual_frequency(arcs, 1.5e-3))
    >>> len(windows) > 10
    True
    """
    mp = THESIS_MAPPING if mapping is None else mapping
    mapped = mp.apply(series.value_m, series.elevation_deg)
    L = _min_window_samples(min_length_s, series.interval_s, test)
    windows: list[Window] = []
    uncovered: list[tuple[int, str, float, float]] = []
    n_tests = 0
    long_enough = 0
    short_s = 0.0
    for k, (lo, hi) in enumerate(series.arc_bounds()):
        x = mapped[lo:hi]
        t = series.t_gps_s[lo:hi]
        if x.size >= L:
            long_enough += 1
        elif x.size >= 2:
            short_s += float(t[-1] - t[0])
        found, nt = window_arc(
            x,
            L,
            alpha=alpha,
            p_slide=p_slide,
            p_trim=p_trim,
            center=center,
            test=test,
            overlap=overlap,
        )
        n_tests += nt
        for s, e, lp, kp in found:
            windows.append(
                Window(k, series.arc_sats[k], s, e, lo, float(t[s]), float(t[e]), lp, kp)
            )
        uncovered += _uncovered(k, series.arc_sats[k], t, found)
    if long_enough == 0:
        raise _no_long_arc_error(series, L, min_length_s)
    return WindowSet(
        windows=tuple(windows),
        mapped_m=mapped,
        interval_s=series.interval_s,
        mapping=mp,
        params={
            "alpha": alpha,
            "p_slide": p_slide,
            "p_trim": p_trim,
            "min_length_s": min_length_s,
            "min_length_samples": L,
            "effective_min_length_s": (L - 1) * series.interval_s,
            "center": center,
            "test": test,
            "overlap": overlap,
        },
        n_tests=n_tests,
        uncovered=tuple(uncovered),
        uncovered_s=float(sum(b - a for _, _, a, b in uncovered)),
        short_s=short_s,
    )


def _min_window_samples(min_length_s: float, interval_s: float, test: str) -> int:
    """Return the minimum window length ``L``, samples (raised to the spectral test's minimum)."""
    L = max(8, int(math.ceil(min_length_s / interval_s)) + 1)
    if test == "spectral":
        # the spectral test needs two parts with two test frequencies each
        L = max(L, min_samples())
    return L


def _uncovered(
    k: int, sats: str, t: NDArray[np.float64], found: list[tuple[int, int, float, float]]
) -> list[tuple[int, str, float, float]]:
    """Return the stretches of at least two samples of arc ``k`` that no window covers."""
    covered = np.zeros(t.size, dtype=bool)
    for s, e, _, _ in found:
        covered[s : e + 1] = True
    edges = np.flatnonzero(np.diff(np.r_[False, ~covered, False].astype(np.int8)))
    return [
        (k, sats, float(t[a]), float(t[b - 1]))
        for a, b in zip(edges[::2], edges[1::2], strict=True)
        if b - a >= 2
    ]


def _no_long_arc_error(series: MultipathSeries, L: int, min_length_s: float) -> NoDataError:
    """Return the error for a series with no arc as long as the minimum window (``L`` samples)."""
    why = ""
    if (L - 1) * series.interval_s > min_length_s:
        why = (
            f" (the spectral stationarity test needs {min_samples()} samples: "
            f"{(L - 1) * series.interval_s / 60:.0f} min at {series.interval_s:g} s; use "
            "longer data, a higher sampling rate or the thesis test)"
        )
    longest = max((hi - lo for lo, hi in series.arc_bounds()), default=0)
    return NoDataError(
        f"no arc is as long as the minimum window length {(L - 1) * series.interval_s:g} s"
        f"{why}; the longest of the {series.n_arcs} arcs after filtering is "
        f"{max(longest - 1, 0) * series.interval_s / 60:.1f} min"
    )
