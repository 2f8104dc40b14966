"""Options of the stationarity stage: the elevation mapping and the windowing."""

from __future__ import annotations

from dataclasses import dataclass

from numpy.typing import ArrayLike

from psdbound.errors import InputError
from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping, fit_mapping

__all__ = ["MAPPING_KINDS", "MappingOptions", "StationarityOptions", "choose_mapping"]

MAPPING_KINDS = ("thesis", "fixed", "fit")


@dataclass(frozen=True)
class MappingOptions:
    """Elevation mapping ``m(el) = a + b exp(-el^2 / (2 c^2))``.

    Parameters
    ----------
    kind : {"thesis", "fixed", "fit"}
        The thesis's (1, 29, 10 deg), the given ``a, b, c_deg``, or fitted
        to the data's RMS per elevation bin.
    a, b : float
        Dimensionless coefficients (``kind="fixed"``).
    c_deg : float
        Width, degrees (``kind="fixed"``).
    """

    kind: str = "thesis"
    a: float = 1.0
    b: float = 29.0
    c_deg: float = 10.0


@dataclass(frozen=True)
class StationarityOptions:
    """Windowing options (thesis slide/trim algorithm).

    Parameters
    ----------
    alpha : float
        Significance level of the Levene and K-S tests.
    p_slide, p_trim : float
        Slide and trim coefficients.
    min_window_s : float
        Minimum window length, seconds.
    levene_center : {"mean", "median"}
        Centre of the Levene test.
    """

    alpha: float = 0.05
    p_slide: float = 1.2
    p_trim: float = 0.8
    min_window_s: float = 600.0
    levene_center: str = "mean"


def choose_mapping(
    options: MappingOptions, value_m: ArrayLike, elevation_deg: ArrayLike
) -> ElevationMapping:
    """Return the elevation mapping the options ask for.

    Parameters
    ----------
    options : MappingOptions
        Which mapping.
    value_m, elevation_deg : array_like
        The isolated multipath (metres) and elevations (degrees), used when
        ``options.kind == "fit"``.

    Returns
    -------
    ElevationMapping
    """
    if options.kind == "thesis":
        return THESIS_MAPPING
    if options.kind == "fixed":
        return ElevationMapping(options.a, options.b, options.c_deg, "fixed")
    if options.kind == "fit":
        return fit_mapping(value_m, elevation_deg)
    raise InputError(
        f"unknown mapping kind {options.kind!r}; use {', '.join(MAPPING_KINDS)}"
    )
