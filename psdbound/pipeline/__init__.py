"""The fit pipeline: typed stages, the result document, and the library's front door.

* :func:`fit` -> :class:`FitResults` (also ``psdbound.fit``), :func:`load`
* :class:`FitConfig`: every option, composed of the stage options objects
* :mod:`psdbound.pipeline.stages`: ``read_inputs``, ``choose_cutoff``,
  ``isolate``, ``window``, ``bound``, ``validate``
"""

from __future__ import annotations

from psdbound.ionosphere.policy import THESIS_CUTOFF_HZ
from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.front import FitResults, fit, load
from psdbound.results import REQUIRED_FIELDS, SCHEMA_VERSION

__all__ = [
    "REQUIRED_FIELDS",
    "SCHEMA_VERSION",
    "THESIS_CUTOFF_HZ",
    "FitConfig",
    "FitResults",
    "fit",
    "load",
]
