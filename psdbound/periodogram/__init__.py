"""Periodograms: Lomb-Scargle of gappy (replicated) series, and tapered periodograms.

The one owner of periodogram computations; a low-level package (it imports
only NumPy, SciPy, astropy, :mod:`psdbound.errors` and :mod:`psdbound.common`)
that the stages call:

* Lomb-Scargle (:mod:`psdbound.periodogram.lombscargle`, a small front over
  one algorithm per private module): :func:`lomb_scargle` with methods
  :data:`LS_METHODS` (``"gridfft"``: exact, by FFT, for on-grid times;
  ``"astropy"``: any times), :func:`frequency_grid`,
  :func:`to_one_sided_density`, :func:`replicate_series`;
* tapered (:mod:`psdbound.periodogram.tapered`): :func:`tapered_periodogram`
  (one-sided Hann-tapered FFT periodogram), :func:`tapered_lomb_scargle`
  and :func:`hann_taper`.

The PSD *estimators* of the bound (Welch, multitaper, Blackman-Tukey) are in
:mod:`psdbound.spectra`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.periodogram._ls_astropy import replicate_series
    from psdbound.periodogram.lombscargle import (
        LS_METHODS,
        frequency_grid,
        lomb_scargle,
        to_one_sided_density,
    )
    from psdbound.periodogram.tapered import hann_taper, tapered_lomb_scargle, tapered_periodogram

__all__ = [
    "LS_METHODS",
    "frequency_grid",
    "hann_taper",
    "lomb_scargle",
    "replicate_series",
    "tapered_lomb_scargle",
    "tapered_periodogram",
    "to_one_sided_density",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "replicate_series": ("psdbound.periodogram._ls_astropy", "replicate_series"),
    "LS_METHODS": ("psdbound.periodogram.lombscargle", "LS_METHODS"),
    "frequency_grid": ("psdbound.periodogram.lombscargle", "frequency_grid"),
    "lomb_scargle": ("psdbound.periodogram.lombscargle", "lomb_scargle"),
    "to_one_sided_density": ("psdbound.periodogram.lombscargle", "to_one_sided_density"),
    "hann_taper": ("psdbound.periodogram.tapered", "hann_taper"),
    "tapered_lomb_scargle": ("psdbound.periodogram.tapered", "tapered_lomb_scargle"),
    "tapered_periodogram": ("psdbound.periodogram.tapered", "tapered_periodogram"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
