"""Options of the spectra stage: the PSD estimator and the bound fit."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["BoundOptions", "SpectraOptions"]


@dataclass(frozen=True)
class SpectraOptions:
    """PSD estimator and its keyword options.

    Parameters
    ----------
    estimator : {"multitaper", "welch", "blackman-tukey"}
        Estimator (see :func:`psdbound.spectra.estimate_psd`).
    options : dict
        Estimator keyword options (e.g. ``{"nw": 4}`` for multitaper).
    """

    estimator: str = "multitaper"
    options: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class BoundOptions:
    """How the bound is fitted.

    Parameters
    ----------
    objective : {"variance", "area"}
        Tightness objective minimised.
    target : {"point", "upper"}
        Bound the PSD estimates or their upper confidence limits.
    level : float
        Confidence level of the upper limits (``target="upper"``).
    """

    objective: str = "variance"
    target: str = "point"
    level: float = 0.95
