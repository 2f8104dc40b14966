"""Options of the arc stage (tracking arcs from observations)."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["ArcOptions"]


@dataclass(frozen=True)
class ArcOptions:
    """How tracking arcs are built (see :func:`find_arcs`).

    Parameters
    ----------
    min_length_s : float, default 1800
        Shortest arc kept, s.
    elevation_mask_deg : float, default 10
        Elevation mask, degrees.
    slip_threshold_m : float, default 0.04
        Geometry-free jump that counts as a cycle slip, metres.
    """

    min_length_s: float = 1800.0
    elevation_mask_deg: float = 10.0
    slip_threshold_m: float = 0.04
