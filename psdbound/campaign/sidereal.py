"""Sidereal repeat of the spans screened as ionosphere, over a station's consecutive days.

Multipath is fixed to the geometry of antenna, reflectors and satellite: the
GPS geometry repeats one sidereal day later (:data:`~psdbound.constants.SIDEREAL_DAY_S`,
about 236 s earlier each day), and so does the multipath. A travelling
ionospheric disturbance does not. So when a span the screening took out as
ionosphere on one day reappears on the same satellite one sidereal day later
(within ``tolerance_s``: the screening works on 5-minute blocks), more often
than two independent sets of spans would meet by chance, the screening has
probably cut multipath, and the days' bounds are optimistic there.

For each pair of a station's consecutive days :func:`sidereal_repeats`
reports the time screened as ionosphere on the later day (``flagged_s``),
the part of it that repeats a span of the day before shifted by the
sidereal day (``repeated_s``), and what two independent sets with the same
amounts would share on average (``expected_s``: each satellite's flagged
time on the later day times the share of that satellite's *tracked* time on
the later day, its arcs, that the earlier day's spans cover once shifted and
widened by the tolerance; the whole day's share when a document has no arcs).
A span can only be flagged while its satellite is tracked, and the passes
themselves repeat with the sidereal day: against the whole day, spans that
fill the passes of both days looked several times more repeated than chance
(at 78.9 N, where 86 % of two days' data was screened as ionosphere, 3.1
times). ``ratio = repeated_s / expected_s`` far
above 1 with ``repeated_s`` of tens of minutes is the warning sign; a
campaign then fits both days again with those spans kept as multipath
(:func:`repeating_spans`, :attr:`psdbound.screening.ScreeningOptions.keep_spans`).

Caveats: the block length (300 s) is longer than the difference between the
sidereal and the solar day (236 s), so an ionospheric effect that recurs at
the same local time on the same satellite (e.g. post-sunset equatorial
irregularities) repeats too; the test counts only satellites of the system
fitted; and it needs consecutive days with their result documents.
"""

from __future__ import annotations

import datetime as dt
from collections import defaultdict
from typing import Any

from psdbound.constants import SIDEREAL_DAY_S

__all__ = ["DEFAULT_TOLERANCE_S", "repeat_warnings", "repeating_spans", "sidereal_repeats"]

#: Shift allowed between a span and its repeat, s: one screening block.
DEFAULT_TOLERANCE_S = 300.0

Spans = dict[str, list[tuple[float, float]]]


def _ionosphere_spans(document: dict[str, Any]) -> Spans:
    """Return the spans screened as ionosphere, per satellite (GPS seconds)."""
    out: Spans = defaultdict(list)
    for e in (document.get("screening") or {}).get("excluded", []):
        if e.get("kind") == "ionosphere":
            out[e["sat"]].append((float(e["start_gps_s"]), float(e["stop_gps_s"])))
    return out


def _shifted(
    spans: list[tuple[float, float]], shift_s: float, tolerance_s: float
) -> list[tuple[float, float]]:
    """Return spans moved by ``shift_s`` and widened by ``tolerance_s`` on each side, s."""
    return [(a + shift_s - tolerance_s, b + shift_s + tolerance_s) for a, b in spans]


def _length(spans: list[tuple[float, float]]) -> float:
    """Total length of possibly overlapping spans, s."""
    total, end = 0.0, -float("inf")
    for a, b in sorted(spans):
        if b > end:
            total += b - max(a, end)
            end = b
    return total


def _overlap(spans: list[tuple[float, float]], others: list[tuple[float, float]]) -> float:
    """Time of ``spans`` that lies in the union of ``others``, s."""
    cut = [(max(a, c), min(b, d)) for a, b in spans for c, d in others if min(b, d) > max(a, c)]
    return _length(cut)


def _tracked(document: dict[str, Any]) -> Spans:
    """Return each satellite's tracking arcs of a result document (GPS seconds)."""
    out: Spans = defaultdict(list)
    for a in (document.get("figures") or {}).get("arcs") or []:
        out[str(a["sat"])].append((float(a["t0"]), float(a["t1"])))
    return out


def _chance(
    shifted: list[tuple[float, float]], tracked: list[tuple[float, float]], duration_s: float
) -> float:
    """Share of a satellite's tracked time (else of the day) that the shifted spans cover."""
    total = _length(tracked)
    if total > 0:
        return min(1.0, _overlap(tracked, shifted) / total)
    return min(1.0, _length(shifted) / duration_s)


def _pair(early: dict[str, Any], late: dict[str, Any], tolerance_s: float) -> dict[str, float]:
    """Repeat statistics of the later day's ionosphere spans against the earlier day's."""
    s1, s2 = _ionosphere_spans(early), _ionosphere_spans(late)
    span = early["data_span"]
    duration = max(float(span["stop_gps_s"]) - float(span["start_gps_s"]), 1.0)
    shifted = {sat: _shifted(v, SIDEREAL_DAY_S, tolerance_s) for sat, v in s1.items()}
    tracked = _tracked(late)
    flagged = sum(_length(v) for v in s2.values())
    repeated = sum(_overlap(v, shifted.get(sat, [])) for sat, v in s2.items())
    expected = sum(
        _length(v) * _chance(shifted.get(sat, []), tracked.get(sat, []), duration)
        for sat, v in s2.items()
    )
    return {
        "flagged_s": flagged,
        "repeated_s": repeated,
        "expected_s": expected,
        "ratio": repeated / expected if expected > 0 else (0.0 if repeated == 0 else float("inf")),
    }


def sidereal_repeats(
    days: list[dict[str, Any]],
    documents: list[dict[str, Any] | None],
    *,
    tolerance_s: float = DEFAULT_TOLERANCE_S,
) -> list[dict[str, Any]]:
    """Return, per station and pair of consecutive days, how the ionosphere spans repeat.

    Parameters
    ----------
    days : list of dict
        The campaign's station-days (``station``, ``day`` as an ISO date).
    documents : list of dict or None
        Each day's result document (None: the day failed), in the order of ``days``.
    tolerance_s : float, default :data:`DEFAULT_TOLERANCE_S`
        Shift allowed between a span and its repeat, s.

    Returns
    -------
    list of dict
        ``station``, ``days`` (the two dates), ``flagged_s``, ``repeated_s``,
        ``expected_s`` (s) and ``ratio`` (see the module docstring); pairs
        with nothing flagged on the later day are left out.
    """
    by_station: dict[str, list[tuple[dt.date, dict[str, Any]]]] = defaultdict(list)
    for d, doc in zip(days, documents, strict=True):
        if doc is not None:
            by_station[d["station"]].append((dt.date.fromisoformat(d["day"]), doc))
    out = []
    for station, items in sorted(by_station.items()):
        items.sort(key=lambda x: x[0])
        for (d1, doc1), (d2, doc2) in zip(items, items[1:], strict=False):
            if (d2 - d1).days != 1:
                continue
            stats = _pair(doc1, doc2, tolerance_s)
            if stats["flagged_s"] > 0:
                out.append({"station": station, "days": [str(d1), str(d2)], **stats})
    return out


def repeat_warnings(
    repeats: list[dict[str, Any]], *, min_ratio: float = 3.0, min_repeated_s: float = 600.0
) -> list[str]:
    """Return one sentence per day pair whose ionosphere spans repeat with the sidereal day.

    Parameters
    ----------
    repeats : list of dict
        :func:`sidereal_repeats`.
    min_ratio : float, default 3
        Repeated time over the time independent spans would share.
    min_repeated_s : float, default 600
        Repeated time, s.

    Returns
    -------
    list of str
    """
    return [
        f"{r['station']} {r['days'][1]}: {r['repeated_s'] / 60:.0f} of the "
        f"{r['flagged_s'] / 60:.0f} min screened as ionosphere repeat {r['days'][0]}'s spans "
        f"one sidereal day later on the same satellites ({r['ratio']:.1f} times what "
        "independent spans would share): multipath repeats with the geometry, a disturbance "
        "does not, so part of it is probably multipath and the day's bound optimistic there"
        for r in repeats
        if r["ratio"] >= min_ratio and r["repeated_s"] >= min_repeated_s
    ]


def _repeating(spans: Spans, others: Spans, shift_s: float, tolerance_s: float) -> list:
    """Return the spans of ``spans`` that meet ``others`` shifted by ``shift_s`` (sat, a, b)."""
    out = []
    for sat, v in spans.items():
        moved = _shifted(others[sat], shift_s, tolerance_s)
        out += [(sat, a, b) for a, b in v if _overlap([(a, b)], moved) > 0]
    return out


def repeating_spans(
    days: list[dict[str, Any]],
    documents: list[dict[str, Any] | None],
    *,
    tolerance_s: float = DEFAULT_TOLERANCE_S,
    min_ratio: float = 3.0,
    min_repeated_s: float = 600.0,
) -> dict[int, list[tuple[str, float, float]]]:
    """Return, per day (its index), the ionosphere spans that repeat on a neighbouring day.

    Only day pairs whose repeat is a warning (:func:`repeat_warnings`:
    ``min_ratio`` times the chance overlap and ``min_repeated_s``) count;
    both days of such a pair get their spans that meet the other day's,
    shifted by one sidereal day forwards or backwards. A campaign fits those
    days again with the spans kept as multipath
    (:attr:`psdbound.screening.ScreeningOptions.keep_spans`).

    Parameters
    ----------
    days, documents : list
        As :func:`sidereal_repeats`.
    tolerance_s, min_ratio, min_repeated_s : float
        As :func:`sidereal_repeats` and :func:`repeat_warnings`.

    Returns
    -------
    dict of int to list of (str, float, float)
        ``{day index: [(satellite, start_gps_s, stop_gps_s), ...]}``.
    """
    flagged = {
        (r["station"], r["days"][1])
        for r in sidereal_repeats(days, documents, tolerance_s=tolerance_s)
        if r["ratio"] >= min_ratio and r["repeated_s"] >= min_repeated_s
    }
    index = {(d["station"], d["day"]): i for i, d in enumerate(days)}
    out: dict[int, list[tuple[str, float, float]]] = defaultdict(list)
    for station, late in sorted(flagged):
        early = str(dt.date.fromisoformat(late) - dt.timedelta(days=1))
        i, j = index[(station, early)], index[(station, late)]
        s1, s2 = _ionosphere_spans(documents[i]), _ionosphere_spans(documents[j])
        out[j] += _repeating(s2, s1, SIDEREAL_DAY_S, tolerance_s)
        out[i] += _repeating(s1, s2, -SIDEREAL_DAY_S, tolerance_s)
    return {k: sorted(set(v)) for k, v in out.items() if v}
