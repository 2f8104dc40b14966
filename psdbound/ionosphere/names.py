"""Defaults of the cutoff criterion, in a module that imports nothing.

The cutoff policy (options), the residual-ionosphere criterion and the batch
settings all use them; living at the bottom, they create no import cycle.
"""

from __future__ import annotations

__all__ = ["DEFAULT_MARGIN_DB", "DEFAULT_MP_SIGMA_M"]

#: Reference multipath sigma (per carrier, the bound's units), m.
DEFAULT_MP_SIGMA_M = 1e-3
#: Residual ionosphere below the reference multipath, dB (amplitude factor 100).
DEFAULT_MARGIN_DB = 40.0
