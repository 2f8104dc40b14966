"""Options of the stationarity stage: the elevation mapping and the windowing."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

from numpy.typing import ArrayLike

from psdbound.common.options import Choice, Number, check_fields, option
from psdbound.errors import InputError

if TYPE_CHECKING:
    from psdbound.stationarity.mapping import ElevationMapping

#: Stationarity tests: the thesis's (Levene then K-S) or spectral homogeneity of the halves.
STATIONARITY_TESTS = ("thesis", "spectral")

__all__ = [
    "MAPPING_KINDS",
    "STATIONARITY_TESTS",
    "MappingOptions",
    "StationarityOptions",
    "choose_mapping",
]

MAPPING_KINDS = ("thesis", "fixed", "fit")


@dataclass(frozen=True)
class MappingOptions:
    """Elevation mapping ``m(el) = a + b exp(-el^2 / (2 c^2))``.

    Parameters
    ----------
    kind : {"fit", "thesis", "fixed"}
        ``"fit"`` (default): fitted to the data's RMS per elevation bin, with
        the covariance of ``b, c`` (:func:`~psdbound.stationarity.fit_mapping`;
        when fewer than four elevation bins are populated the thesis mapping
        is used and its ``source`` says why); ``"thesis"``: (1, 29, 10 deg);
        ``"fixed"``: the given ``a, b, c_deg``.
    a, b : float
        Dimensionless coefficients (``kind="fixed"``): ``0 < a <= 1000``,
        ``0 <= b <= 10000`` (so that ``m(el) > 0``).
    c_deg : float
        Width, degrees (``kind="fixed"``), ``0 < c_deg <= 90``.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range. That ``a, b, c_deg``
        are only set with ``kind="fixed"`` is checked by ``FitConfig.check``.
    """

    kind: str = option("fit", Choice(MAPPING_KINDS, noun="mapping kind"))
    a: float = option(1.0, Number(lo=0.0, hi=1e3, lo_open=True))
    b: float = option(29.0, Number(lo=0.0, hi=1e4))
    c_deg: float = option(10.0, Number(lo=0.0, hi=90.0, lo_open=True, unit="deg"))

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class StationarityOptions:
    """Windowing options (slide/trim algorithm of the thesis, with a choice of test).

    Parameters
    ----------
    test : {"spectral", "thesis"}
        Stationarity test of each candidate window: ``"spectral"`` (default)
        compares the multitaper log spectra of the window's halves and is
        valid for autocorrelated samples
        (:func:`~psdbound.stationarity.test_spectral_homogeneity`);
        ``"thesis"``: Levene then Kolmogorov-Smirnov, which assume
        independent samples.
    windows : {"disjoint", "slide"}
        ``"disjoint"`` (default): after a stationary window the next one
        starts right after it (what the pooled bound needs); ``"slide"``:
        the thesis's overlapping slide rule.
    alpha : float
        Significance level of the stationarity test, in (0, 1).
    p_slide, p_trim : float
        Slide (> 1, at most 100) and trim (in (0, 1)) coefficients.
    min_window_s : float
        Minimum window length, seconds (> 0, at most 86400).
    levene_center : {"mean", "median"}
        Centre of the Levene test.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range.
    """

    test: str = option("spectral", Choice(STATIONARITY_TESTS, noun="stationarity test"))
    windows: str = option("disjoint", Choice(("disjoint", "slide"), noun="window rule"))
    alpha: float = option(0.05, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    p_slide: float = option(1.2, Number(lo=1.0, hi=100.0, lo_open=True))
    p_trim: float = option(0.8, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    min_window_s: float = option(600.0, Number(lo=0.0, hi=86400.0, lo_open=True, unit="s"))
    levene_center: str = option("mean", Choice(("mean", "median"), noun="Levene centre"))

    def __post_init__(self) -> None:
        check_fields(self)


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
    from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping, fit_mapping

    if options.kind == "thesis":
        return THESIS_MAPPING
    if options.kind == "fixed":
        return ElevationMapping(options.a, options.b, options.c_deg, "fixed")
    if options.kind == "fit":
        try:
            return fit_mapping(value_m, elevation_deg)
        except InputError as exc:  # too few elevations: say so and use the thesis mapping
            return replace(THESIS_MAPPING, source=f"thesis (fit impossible: {exc})")
    raise InputError(f"unknown mapping kind {options.kind!r}; use {', '.join(MAPPING_KINDS)}")
