"""Options of the cutoff validation as the fit runs it."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ValidationOptions"]


@dataclass(frozen=True)
class ValidationOptions:
    """Cutoff validation: reflection geometries, amplitude ratio alpha, threshold.

    ``geometries``: ``"wall:d=25"``, ``"ground:h=1.5"`` ...; ``"ground:h=header"``
    takes the antenna height ``ANTENNA: DELTA H`` of the (first) observation
    file, or ``ground_height_m`` when the header gives 0. ``alpha``:
    reflection amplitude ratio; ``threshold``: the thesis's largest fraction
    of a geometry's multipath power below f_c; ``rate``: geometry rate for
    the expansion (orbit, an aircraft mode or Hz).
    """

    geometries: tuple[str, ...] = ("wall:d=25", "ground:h=header")
    alpha: float = 0.1
    threshold: float = 0.10
    rate: str = "orbit"
    ground_height_m: float = 1.5
