"""psdbound: provable Gauss-Markov + white-noise PSD bounds of GNSS carrier-phase multipath.

Pipeline stages, one subpackage each (data flows one way)::

    io          observations, orbits, geometry -> arcs
    (isolation, ionosphere, stationarity, spectra, validation, kalman, reports)
    cli         the ``python -m psdbound`` command line
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from psdbound.errors import InputError, NoDataError

try:
    __version__ = version("psdbound")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0.0.0+unknown"

__all__ = ["InputError", "NoDataError", "__version__"]
