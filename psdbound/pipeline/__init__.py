"""The fit pipeline: typed stages, the result document, and the library's front door.

* :func:`fit` -> :class:`FitResults` (also ``psdbound.fit``), :func:`load`
* :class:`FitConfig`: every option, composed of the stage options objects
* :func:`run_stages` -> :class:`StageProducts`: the one runner of the chain
  (``fit``, the campaign's tasks and the tests use it), up to any stage
* :mod:`psdbound.pipeline.stages`: ``read_inputs``, ``choose_cutoff``,
  ``isolate``, ``map_elevation``, ``screen``, ``window``, ``bound``, ``validate``
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.ionosphere.policy import THESIS_CUTOFF_HZ
    from psdbound.pipeline.config import FitConfig
    from psdbound.pipeline.front import FitResults, fit, load
    from psdbound.pipeline.runner import STAGES, StageProducts, run_stages
    from psdbound.results import REQUIRED_FIELDS, SCHEMA_VERSION

__all__ = [
    "REQUIRED_FIELDS",
    "SCHEMA_VERSION",
    "STAGES",
    "THESIS_CUTOFF_HZ",
    "FitConfig",
    "FitResults",
    "StageProducts",
    "fit",
    "load",
    "run_stages",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "THESIS_CUTOFF_HZ": ("psdbound.ionosphere.policy", "THESIS_CUTOFF_HZ"),
    "FitConfig": ("psdbound.pipeline.config", "FitConfig"),
    "FitResults": ("psdbound.pipeline.front", "FitResults"),
    "fit": ("psdbound.pipeline.front", "fit"),
    "load": ("psdbound.pipeline.front", "load"),
    "STAGES": ("psdbound.pipeline.runner", "STAGES"),
    "StageProducts": ("psdbound.pipeline.runner", "StageProducts"),
    "run_stages": ("psdbound.pipeline.runner", "run_stages"),
    "REQUIRED_FIELDS": ("psdbound.results", "REQUIRED_FIELDS"),
    "SCHEMA_VERSION": ("psdbound.results", "SCHEMA_VERSION"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
