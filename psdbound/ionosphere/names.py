"""Defaults of the cutoff criterion and the thesis's cutoffs, in a module that imports nothing.

The cutoff policy (options), the residual-ionosphere criterion and the batch
settings all use them; living at the bottom, they create no import cycle.
"""

from __future__ import annotations

__all__ = ["DEFAULT_MARGIN_DB", "DEFAULT_MP_SIGMA_M", "THESIS_CHICAGO_2020_HZ"]

#: Reference multipath sigma (per carrier, the bound's units), m.
DEFAULT_MP_SIGMA_M = 1e-3
#: Residual ionosphere below the reference multipath, dB (amplitude factor 100).
DEFAULT_MARGIN_DB = 40.0
#: The thesis's Chicago 2020 cutoffs (section 4.3.3): mean, min and max over
#: about 350 satellite-days, Hz; the maximum is its recommended cutoff (eq. 4.2).
THESIS_CHICAGO_2020_HZ = {"mean": 6.73e-4, "min": 5.03e-4, "max": 9.55e-4}
