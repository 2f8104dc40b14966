"""Code-multipath samples for the overbounds: from RINEX files, and their description.

:func:`code_multipath_from_files` reads an observation file and an orbit
and returns the carrier-levelled code multipath
(:func:`psdbound.isolation.isolate_code_multipath`);
:func:`describe_code_series` is the JSON section both ``psdbound overbound
--code`` and ``psdbound fit --code-multipath`` write about it.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import Any

import numpy as np

from psdbound.aviation.overbound import (
    DEFAULT_MIN_ABS_Z,
    OverboundResult,
    overbound_by_elevation,
    samples_in_full_bins,
)
from psdbound.errors import InputError
from psdbound.isolation import MultipathSeries, isolate_code_multipath, rms_by_satellite

__all__ = ["code_multipath_from_files", "describe_code_series", "overbound_code_series"]


def code_multipath_from_files(
    obs_path: str | os.PathLike[str],
    nav_path: str | os.PathLike[str],
    codes: str | Sequence[str],
    *,
    system: str = "G",
    elevation_mask_deg: float = 5.0,
    min_length_s: float = 600.0,
) -> MultipathSeries:
    """Carrier-levelled code multipath of one RINEX observation file.

    Parameters
    ----------
    obs_path : path
        RINEX 2/3/4 observation file (gzip, Hatanaka, zip).
    nav_path : path
        Navigation or SP3 file, for elevations.
    codes : str or sequence of str
        One pseudorange code (``"C1C"``: the MP combination) or two
        (``"C1C,C5Q"`` or ``("C1C", "C5Q")``: ionosphere-free).
    system : str, default "G"
        Satellite system letter.
    elevation_mask_deg : float, default 5
        Samples below are not used, degrees.
    min_length_s : float, default 600
        Shortest levelling arc, s.

    Returns
    -------
    MultipathSeries
        ``method`` ``"CODE"`` or ``"CODE-IF"``, metres, with elevations.

    Raises
    ------
    InputError
        Not one or two codes; a code or its carriers not in the file; unreadable files.
    NoDataError
        No arc long enough.
    """
    from psdbound.io import read_obs, read_orbit

    items = codes.split(",") if isinstance(codes, str) else list(codes)
    items = [c.strip() for c in items if c.strip()]
    if not 1 <= len(items) <= 2:
        raise InputError(f"give one pseudorange code or two separated by a comma, got {codes!r}")
    if not min_length_s > 0:
        raise InputError(f"the shortest levelling arc must be > 0 s, got {min_length_s}")
    obs = read_obs(obs_path, systems=system)
    return isolate_code_multipath(
        obs,
        tuple(items),
        orbit=read_orbit(nav_path),
        system=system,
        elevation_mask_deg=elevation_mask_deg,
        min_length_s=min_length_s,
    )


def describe_code_series(series: MultipathSeries, *, min_length_s: float) -> dict[str, Any]:
    """Describe a code-multipath series: codes, combination, RMS overall and per satellite.

    Parameters
    ----------
    series : MultipathSeries
        From :func:`~psdbound.isolation.isolate_code_multipath`.
    min_length_s : float
        Shortest levelling arc used, s.

    Returns
    -------
    dict
        ``codes``, ``combination``, ``signals``, ``n_arcs``, ``n_samples``,
        ``min_arc_s``, ``rms_m``, ``rms_by_satellite_m`` (m), ``outlier_samples``.
    """
    x = series.value_m
    return {
        "codes": list(series.meta["codes"]),
        "combination": series.meta.get("combination"),
        "signals": list(series.signals),
        "n_arcs": series.n_arcs,
        "n_samples": int(x.size),
        "min_arc_s": float(min_length_s),
        "rms_m": float(np.sqrt(np.mean(x**2))) if x.size else float("nan"),
        "rms_by_satellite_m": rms_by_satellite(series),
        "outlier_samples": series.meta.get("outlier_samples_gt_m"),
    }


def overbound_code_series(
    series: MultipathSeries,
    edges_deg: Sequence[float],
    *,
    method: str = "paired",
    min_samples: int = 100,
    min_abs_z: float = DEFAULT_MIN_ABS_Z,
    bias: float = 0.0,
    confidence: float = 0.95,
) -> tuple[OverboundResult, list[str]]:
    """Overbound a code-multipath series per elevation bin, skipping (and naming) sparse bins.

    A bin with fewer than ``min_samples`` samples is a property of the
    station's sky (few satellites ever rise above 60 deg at high latitude),
    not bad input: it is left out and named in the returned notes.

    Parameters
    ----------
    series : MultipathSeries
        Code multipath with elevations (metres, degrees).
    edges_deg : sequence of float
        Increasing elevation bin edges, degrees.
    method, min_abs_z, bias, confidence
        As for :func:`~psdbound.aviation.overbound_by_elevation` (the arcs are
        the continuous segments of the effective sample size).
    min_samples : int, default 100
        Fewest samples a bin must hold to be overbounded.

    Returns
    -------
    result : OverboundResult
    notes : list of str
        The bins left out.

    Raises
    ------
    InputError
        No bin holds ``min_samples`` (every non-empty bin is named), or a
        sample lies outside the edges only (nothing to bound).
    """
    keep, notes = samples_in_full_bins(series.elevation_deg, edges_deg, min_samples)
    if not keep.any():
        raise InputError(
            "no elevation bin holds enough samples to overbound: "
            + ("; ".join(notes) or f"no sample inside the edges {list(edges_deg)}")
        )
    result = overbound_by_elevation(
        series.value_m[keep],
        series.elevation_deg[keep],
        edges_deg=edges_deg,
        method=method,
        bias=bias,
        min_abs_z=min_abs_z,
        min_samples=min_samples,
        confidence=confidence,
        segment_id=series.arc_id[keep],
    )
    return result, notes
