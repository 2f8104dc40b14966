"""Navigation files matched to observation days by their content, not their names.

Each candidate orbit file (broadcast navigation or SP3) is read once and
reduced to the time it covers for each system (:func:`orbit_span`): for
broadcast records, the union of ``reference time +- validity`` of the
healthy records (4 h for GPS, Galileo, BeiDou and QZSS, 30 min for
GLONASS: the ages the fit uses); for SP3, the union of ``epoch +- half the
epoch interval``. An observation day (the span of its files) is served by the
one file that covers at least :data:`MIN_COVERED` of that span for the
system fitted (:func:`match_nav`); no such file is an
:class:`~psdbound.errors.InputError` naming the observation files and every
candidate with the share of the span it covers. When several cover it (each
station's own broadcast file of a day, say), the station's own file is used,
else the one covering the largest share, else the first given, and a warning
names the choice and the others.

A navigation file named for another day, a nearby station's file or the
project's own ``simulate`` output (``<name>_MN.rnx.gz``) are all matched
the same way.
"""

from __future__ import annotations

import datetime as _dt
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError

__all__ = ["MIN_COVERED", "OrbitSpan", "covered_fraction", "match_nav", "nav_choice", "orbit_span"]

#: Share of an observation day's span a navigation file must cover to serve it.
MIN_COVERED = 0.9

_GPS_EPOCH = _dt.datetime(1980, 1, 6)


@dataclass(frozen=True)
class OrbitSpan:
    """What an orbit file covers: per system, merged time intervals in GPS seconds.

    Attributes
    ----------
    path : str
        The file.
    intervals : dict of str to ndarray
        Per system letter, an array of shape (n, 2) of disjoint, sorted
        ``[start, stop]`` intervals, GPS seconds.
    """

    path: str
    intervals: dict[str, NDArray[np.float64]]

    @property
    def systems(self) -> tuple[str, ...]:
        """System letters with any coverage, sorted."""
        return tuple(sorted(s for s, iv in self.intervals.items() if iv.size))

    def extent(self, system: str) -> tuple[float, float] | None:
        """Return the first start and last stop for a system (GPS s), or None."""
        iv = self.intervals.get(system)
        if iv is None or iv.size == 0:
            return None
        return float(iv[0, 0]), float(iv[-1, 1])


def _merge(starts: NDArray[np.float64], stops: NDArray[np.float64]) -> NDArray[np.float64]:
    """Merge intervals ``[starts, stops]`` (seconds) into disjoint sorted ones, shape (n, 2)."""
    if starts.size == 0:
        return np.empty((0, 2))
    order = np.argsort(starts)
    out: list[list[float]] = []
    for a, b in zip(starts[order], stops[order], strict=True):
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], float(b))
        else:
            out.append([float(a), float(b)])
    return np.asarray(out, dtype=float)


def orbit_span(path: str | os.PathLike[str]) -> OrbitSpan:
    """Read an orbit file and return the time it covers per system.

    Parameters
    ----------
    path : path
        Broadcast navigation (RINEX 2/3) or SP3 file, plain or compressed.

    Returns
    -------
    OrbitSpan

    Raises
    ------
    InputError
        The file cannot be read as an orbit file.
    """
    from psdbound.io import read_orbit
    from psdbound.io.sp3 import PreciseOrbit

    orbit = read_orbit(path)
    intervals: dict[str, NDArray[np.float64]] = {}
    if isinstance(orbit, PreciseOrbit):
        t = np.asarray(orbit.t_gps_s, dtype=float)
        half = 0.5 * float(np.median(np.diff(t))) if t.size > 1 else 0.0
        for s in orbit.systems:
            intervals[s] = _merge(t - half, t + half)
        return OrbitSpan(os.fspath(path), intervals)
    for s in orbit.systems:
        ref = orbit.reference_times_gps_s(s)
        v = orbit.validity_s(s)
        intervals[s] = _merge(ref - v, ref + v)
    return OrbitSpan(os.fspath(path), intervals)


def covered_fraction(span: OrbitSpan, system: str, start_s: float, stop_s: float) -> float:
    """Share of ``[start_s, stop_s]`` (GPS s) that an orbit file covers for one system.

    Parameters
    ----------
    span : OrbitSpan
    system : str
        System letter, e.g. ``"G"``.
    start_s, stop_s : float
        The observation span, GPS seconds.

    Returns
    -------
    float
        From 0 to 1 (1 for an empty span inside the coverage).
    """
    iv = span.intervals.get(system)
    if iv is None or iv.size == 0:
        return 0.0
    overlap = np.clip(np.minimum(iv[:, 1], stop_s) - np.maximum(iv[:, 0], start_s), 0.0, None)
    length = stop_s - start_s
    if length <= 0:
        return float(np.any((iv[:, 0] <= start_s) & (iv[:, 1] >= stop_s)))
    return float(overlap.sum() / length)


def _when(t_gps_s: float) -> str:
    return (_GPS_EPOCH + _dt.timedelta(seconds=float(t_gps_s))).strftime("%Y-%m-%d %H:%M:%S")


def _describe(span: OrbitSpan, system: str, fraction: float) -> str:
    name = Path(span.path).name
    ext = span.extent(system)
    if ext is None:
        held = ", ".join(span.systems) or "none"
        return f"{name} (no {system} records; systems {held})"
    return f"{name} ({100 * fraction:.0f} %: {_when(ext[0])} to {_when(ext[1])})"


def match_nav(
    obs: Sequence[str],
    span_s: tuple[float, float],
    system: str,
    candidates: Sequence[OrbitSpan],
    *,
    station: str | None = None,
) -> str:
    """Return the orbit file that serves an observation day.

    Parameters
    ----------
    obs : sequence of str
        The day's observation files (named in messages).
    span_s : (float, float)
        First and last epoch of those files, GPS seconds.
    system : str
        System letter fitted.
    candidates : sequence of OrbitSpan
        Every orbit file given, in the order given.
    station : str, optional
        The station's four-character identifier: among several files that
        cover the span, one whose name starts with it is preferred.

    Returns
    -------
    str
        Path of a file covering at least :data:`MIN_COVERED` of the span.
        When several do: the station's own file, else the one covering the
        largest share, else the first given; a
        :class:`~psdbound.common.notices.PsdboundWarning` names the choice
        (:func:`nav_choice` returns its text instead).

    Raises
    ------
    InputError
        No file covers the span; the message names the observation files,
        their span and every candidate with its share.
    """
    from psdbound.common.notices import warn

    path, note = nav_choice(obs, span_s, system, candidates, station=station)
    if note:
        warn(note, path=" + ".join(obs))
    return path


def nav_choice(
    obs: Sequence[str],
    span_s: tuple[float, float],
    system: str,
    candidates: Sequence[OrbitSpan],
    *,
    station: str | None = None,
) -> tuple[str, str]:
    """Return the file :func:`match_nav` uses and what it says of the choice.

    Parameters are those of :func:`match_nav`.

    Returns
    -------
    path : str
        The file used.
    note : str
        When several files cover the span: which was used, why, and the
        others; ``""`` when one does.

    Raises
    ------
    InputError
        No file covers the span.
    """
    shares = [covered_fraction(c, system, *span_s) for c in candidates]
    hits = [(c, f) for c, f in zip(candidates, shares, strict=True) if f >= MIN_COVERED]
    if len(hits) == 1:
        return hits[0][0].path, ""
    if hits:
        return _choose(system, hits, station)
    listed = "; ".join(_describe(c, system, f) for c, f in zip(candidates, shares, strict=True))
    raise InputError(
        f"no navigation file covers {100 * MIN_COVERED:.0f} % of its span {_when(span_s[0])} to "
        f"{_when(span_s[1])} GPS time for system {system}; candidates: {listed}; give the "
        "navigation (or SP3) file of that day",
        path=" + ".join(obs),
    )


def _choose(
    system: str, hits: list[tuple[OrbitSpan, float]], station: str | None
) -> tuple[str, str]:
    """Pick the station's own file, else the largest share, else the first given; say so."""

    def own(c: OrbitSpan) -> bool:
        return bool(station) and Path(c.path).name[:4].upper() == str(station).upper()

    order = sorted(range(len(hits)), key=lambda k: (not own(hits[k][0]), -hits[k][1], k))
    best, share = hits[order[0]]
    if own(best):
        why = "the station's own file"
    elif share > hits[order[1]][1]:
        why = "the largest share of the day"
    else:
        why = "the first given"
    others = "; ".join(_describe(hits[k][0], system, hits[k][1]) for k in order[1:])
    note = (
        f"{len(hits)} navigation files cover this day for system {system}: used "
        f"{_describe(best, system, share)} ({why}); not used: {others}"
    )
    return best.path, note
