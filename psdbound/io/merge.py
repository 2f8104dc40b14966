"""Consecutive observation files of one station as one data set.

Stations deliver hourly (or 15-min, or daily) files; the multipath of an arc
that crosses a file boundary is one arc. :func:`merge_observations` joins
files of one antenna in time order into a single :class:`Observations`;
:func:`station_key` says which antenna a file belongs to, so that callers can
tell consecutive files of one station from files of different stations (a
dual-antenna pair, or a mistake).

Rules
-----
* same station: the same marker name (case-insensitive, first four
  characters, the RINEX 3 file-name convention) and, when both headers have
  one, approximate positions within :data:`SAME_STATION_M`;
* same sampling interval (within 0.1 %), else an error naming both files;
* epochs in time order; an epoch present in two files is kept once (from the
  earlier file) and counted in a warning, never silently;
* per system, the union of satellites and observation codes; NaN (and
  LLI/SSI -1) where a file lacks a code or satellite.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError
from psdbound.io.obs import Observations, SystemBlock

__all__ = ["SAME_STATION_M", "merge_observations", "station_key", "same_station"]

#: Largest distance between header positions of files of one station, metres.
SAME_STATION_M = 10.0


def station_key(obs: Observations) -> str:
    """Return the station identifier of a file: its marker name's first four characters.

    Falls back to the file name's first four characters when the header has
    no marker name.

    Parameters
    ----------
    obs : Observations

    Returns
    -------
    str
        Upper-case identifier, e.g. ``"ESBC"``.
    """
    name = (obs.header.marker_name or "").strip()
    if not name:
        from pathlib import Path

        name = Path(obs.path).name
    return name[:4].upper()


def same_station(a: Observations, b: Observations) -> bool:
    """Return whether two files come from the same antenna (marker name and position).

    The four-character station keys must agree, the full marker names too
    (one may extend the other, e.g. ``ESBC`` and ``ESBC00DNK``), and the
    header positions must lie within ``SAME_STATION_M``.

    Parameters
    ----------
    a, b : Observations

    Returns
    -------
    bool
    """
    if station_key(a) != station_key(b):
        return False
    ma, mb = ((o.header.marker_name or "").strip().upper() for o in (a, b))
    if ma and mb and ma != mb:  # "ESBC" and "ESBC00DNK" agree; "DUO-A" and "DUO-B" do not
        short, long_ = sorted((ma, mb), key=len)
        if len(short) < 4 or not long_.startswith(short):
            return False
    pa, pb = a.header.approx_position_m, b.header.approx_position_m
    if pa is None or pb is None or not np.any(pa) or not np.any(pb):
        return True
    return bool(np.linalg.norm(np.asarray(pa) - np.asarray(pb)) <= SAME_STATION_M)


def _scatter(block: SystemBlock, sats: list[str], codes: list[str], n: int):
    """Place a block's arrays into the union layout (n epochs)."""
    vals = np.full((n, len(sats), len(codes)), np.nan)
    lli = np.full(vals.shape, -1, dtype=np.int8)
    ssi = np.full(vals.shape, -1, dtype=np.int8)
    si = [sats.index(s) for s in block.sats]
    ci = [codes.index(c) for c in block.codes]
    ix = np.ix_(np.arange(n), si, ci)
    vals[ix], lli[ix], ssi[ix] = block.values, block.lli, block.ssi
    return vals, lli, ssi


def _check_compatible(order: list[Observations]) -> None:
    """Refuse files of another station or sampling interval than the earliest file's."""
    first = order[0]
    for o in order[1:]:
        if not same_station(first, o):
            raise InputError(
                f"observation files of different stations: {first.path} is "
                f"{station_key(first)!r}, {o.path} is {station_key(o)!r} (or their header "
                f"positions differ by more than {SAME_STATION_M:g} m); give the files of one "
                "station, or exactly two files for a dual-antenna pair"
            )
        if not np.isclose(o.interval_s, first.interval_s, rtol=1e-3):
            raise InputError(
                f"observation files with different sampling intervals: {first.path} "
                f"({first.interval_s:g} s) and {o.path} ({o.interval_s:g} s); decimate them "
                "to one interval first"
            )


def _merged_block(
    order: list[Observations], sys_: str, keep: NDArray[np.bool_], sort: NDArray[np.intp]
) -> SystemBlock:
    """Return one system's block over all files: the union of satellites and codes."""
    sats = sorted({s for o in order if sys_ in o.blocks for s in o.blocks[sys_].sats})
    codes = list(dict.fromkeys(c for o in order if sys_ in o.blocks for c in o.blocks[sys_].codes))
    parts_v, parts_l, parts_s = [], [], []
    for o in order:
        n = o.t_gps_s.size
        if sys_ in o.blocks:
            v, li, ss = _scatter(o.blocks[sys_], sats, codes, n)
        else:
            v = np.full((n, len(sats), len(codes)), np.nan)
            li = np.full(v.shape, -1, dtype=np.int8)
            ss = np.full(v.shape, -1, dtype=np.int8)
        parts_v.append(v)
        parts_l.append(li)
        parts_s.append(ss)

    def pick(parts: list[NDArray]) -> NDArray:
        return np.concatenate(parts)[keep][sort]

    return SystemBlock(sys_, tuple(sats), tuple(codes), pick(parts_v), pick(parts_l), pick(parts_s))


def merge_observations(files: Sequence[Observations]) -> Observations:
    """Join observation files of one antenna into one data set, in time order.

    Parameters
    ----------
    files : sequence of Observations
        Files of one station (any order).

    Returns
    -------
    Observations
        ``path`` joins the file names with ``" + "``; ``header`` is the
        earliest file's; ``warnings`` holds every file's warnings plus one
        line per duplicated epoch range dropped.

    Raises
    ------
    InputError
        No file, files of different stations, or different sampling
        intervals (naming the files and what differs).
    """
    if not files:
        raise InputError("no observation file to merge")
    if len(files) == 1:
        return files[0]
    order = sorted(files, key=lambda o: float(o.t_gps_s[0]) if o.t_gps_s.size else np.inf)
    first = order[0]
    _check_compatible(order)
    t_all = np.concatenate([o.t_gps_s for o in order])
    # keep each epoch once, from the earliest file that has it
    keys = np.round(t_all * 1e3).astype(np.int64)
    _, first_idx = np.unique(keys, return_index=True)
    keep = np.zeros(t_all.size, dtype=bool)
    keep[first_idx] = True
    notes = [w for o in order for w in o.warnings]
    n_dup = int((~keep).sum())
    if n_dup:
        notes.append(
            f"{n_dup} epoch(s) present in more than one of the merged files were kept once "
            "(from the earlier file)"
        )
    t_keep = t_all[keep]
    sort = np.argsort(t_keep, kind="stable")
    systems = list(dict.fromkeys(s for o in order for s in o.blocks))
    blocks = {sys_: _merged_block(order, sys_, keep, sort) for sys_ in systems}
    flags = np.concatenate([o.epoch_flag for o in order])[keep][sort]
    types = {s: b.codes for s, b in blocks.items()}
    return replace(
        first,
        header=replace(first.header, obs_types={**first.header.obs_types, **types}),
        path=" + ".join(o.path for o in order),
        t_gps_s=t_keep[sort],
        epoch_flag=flags,
        blocks=blocks,
        warnings=tuple(notes),
        systems_in_file=tuple(sorted({s for o in order for s in o.systems_in_file})),
    )
