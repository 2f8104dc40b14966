"""Spectra and bounds: PSD estimators, the GMRP + white-noise model, bound fitting.

Public surface:

* :func:`estimate_psd` -> :class:`PSDEstimate` (Blackman-Tukey with the
  thesis's 80 %/20 % lag taper, Welch, multitaper; one-sided, m^2/Hz, with
  degrees of freedom and chi-square confidence intervals)
* :func:`fit_bound` -> :class:`BoundFit` (tightest GMRP + white-noise bound)
* :func:`bound_series` -> :class:`SeriesBound` (any evenly sampled error series:
  the pooled bound with its statement and verdict; ``psdbound.bound_series``)
* :class:`BoundModel` / :class:`BoundResults` (windows -> PSDs -> bound)
* the model: :class:`GaussMarkovWhiteNoise` (also the base of
  :class:`psdbound.kalman.GaussMarkovBound`); options :class:`SpectraOptions`,
  :class:`BoundOptions`
* closed forms: :func:`gm_psd_sampled`, :func:`gm_psd_continuous`,
  :func:`white_psd`, :func:`gm_acf`
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.spectra.bound import OBJECTIVES, BoundFit, fit_bound
    from psdbound.spectra.estimators import METHODS, PSDEstimate, estimate_psd
    from psdbound.spectra.fitting import BoundModel, BoundResults
    from psdbound.spectra.models import (
        WHITE_NOISE_MODES,
        GaussMarkovWhiteNoise,
        gm_acf,
        gm_psd_continuous,
        gm_psd_sampled,
        white_psd,
    )
    from psdbound.spectra.options import BoundOptions, SpectraOptions
    from psdbound.spectra.series import SeriesBound, bound_series

__all__ = [
    "METHODS",
    "OBJECTIVES",
    "WHITE_NOISE_MODES",
    "BoundFit",
    "BoundOptions",
    "GaussMarkovWhiteNoise",
    "SpectraOptions",
    "BoundModel",
    "BoundResults",
    "PSDEstimate",
    "SeriesBound",
    "bound_series",
    "estimate_psd",
    "fit_bound",
    "gm_acf",
    "gm_psd_continuous",
    "gm_psd_sampled",
    "white_psd",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "OBJECTIVES": ("psdbound.spectra.bound", "OBJECTIVES"),
    "BoundFit": ("psdbound.spectra.bound", "BoundFit"),
    "fit_bound": ("psdbound.spectra.bound", "fit_bound"),
    "METHODS": ("psdbound.spectra.estimators", "METHODS"),
    "PSDEstimate": ("psdbound.spectra.estimators", "PSDEstimate"),
    "estimate_psd": ("psdbound.spectra.estimators", "estimate_psd"),
    "BoundModel": ("psdbound.spectra.fitting", "BoundModel"),
    "BoundResults": ("psdbound.spectra.fitting", "BoundResults"),
    "WHITE_NOISE_MODES": ("psdbound.spectra.models", "WHITE_NOISE_MODES"),
    "GaussMarkovWhiteNoise": ("psdbound.spectra.models", "GaussMarkovWhiteNoise"),
    "gm_acf": ("psdbound.spectra.models", "gm_acf"),
    "gm_psd_continuous": ("psdbound.spectra.models", "gm_psd_continuous"),
    "gm_psd_sampled": ("psdbound.spectra.models", "gm_psd_sampled"),
    "white_psd": ("psdbound.spectra.models", "white_psd"),
    "BoundOptions": ("psdbound.spectra.options", "BoundOptions"),
    "SpectraOptions": ("psdbound.spectra.options", "SpectraOptions"),
    "SeriesBound": ("psdbound.spectra.series", "SeriesBound"),
    "bound_series": ("psdbound.spectra.series", "bound_series"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
