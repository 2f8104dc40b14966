"""psdbound: Gauss-Markov + white-noise PSD bounds of GNSS carrier-phase multipath, with confidence.

The front door (statsmodels-style)::

    import psdbound
    res = psdbound.fit("SITE.crx.gz", nav="SITE_MN.rnx.gz")   # or psdbound.fit() for the demo
    print(res.summary())
    res.report("reports/site")                                # result.json, HTML, PDF
    again = psdbound.load("reports/site/result.json")

Any evenly sampled error series (stationary stretches, NaN gaps)::

    res = psdbound.bound_series([x1, x2, x3], dt_s=1.0)   # .bound, .verdict, .covers

Pipeline stages, one subpackage each (data flows one way)::

    io -> isolation -> stationarity -> spectra -> pipeline (result) -> reports
    (ionosphere: cutoff; validation: cutoff check; kalman: filter tools;
     simulate: data with known truth; cli: ``python -m psdbound``)
"""

from __future__ import annotations

from typing import Any

from psdbound.errors import InputError, NoDataError
from psdbound.version import __version__

__all__ = [
    "FitConfig",
    "FitResults",
    "InputError",
    "NoDataError",
    "__version__",
    "bound_series",
    "fit",
    "load",
]

_LAZY = {"fit", "load", "FitResults", "FitConfig"}


def __getattr__(name: str) -> Any:
    # the front door imports every stage: load it on first use, not on `import psdbound`
    if name in _LAZY:
        from psdbound import pipeline

        return getattr(pipeline, name)
    if name == "bound_series":
        from psdbound.spectra.series import bound_series

        return bound_series
    raise AttributeError(f"module 'psdbound' has no attribute {name!r}")
