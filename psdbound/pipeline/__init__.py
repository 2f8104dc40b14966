"""The end-to-end ``fit`` pipeline: configuration, run, versioned result."""

from __future__ import annotations

from psdbound.pipeline.config import FitConfig
from psdbound.pipeline.fit import THESIS_CUTOFF_HZ, run_fit
from psdbound.pipeline.result import REQUIRED_FIELDS, SCHEMA_VERSION, FitResult

__all__ = [
    "REQUIRED_FIELDS",
    "SCHEMA_VERSION",
    "THESIS_CUTOFF_HZ",
    "FitConfig",
    "FitResult",
    "run_fit",
]
