"""Options of the arc stage (tracking arcs from observations)."""

from __future__ import annotations

from dataclasses import dataclass

from psdbound.common.options import Number, check_fields, option

__all__ = ["ArcOptions", "MIN_LENGTH_RANGE_S"]

#: Allowed shortest-arc length, s: above 0, at most a day.
MIN_LENGTH_RANGE_S = (0.0, 86400.0)


@dataclass(frozen=True)
class ArcOptions:
    """How tracking arcs are built (see :func:`find_arcs`).

    Parameters
    ----------
    min_length_s : float, default 1800
        Shortest arc kept, s; > 0 and at most 86400 (a day).
    elevation_mask_deg : float, default 10
        Elevation mask, degrees; from 0 up to (not including) 90.
    slip_threshold_m : float, default 0.04
        Geometry-free jump that counts as a cycle slip, metres; > 0 and at
        most 10.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range (the message names
        the option, the value and the range).
    """

    min_length_s: float = option(
        1800.0, Number(lo=MIN_LENGTH_RANGE_S[0], hi=MIN_LENGTH_RANGE_S[1], lo_open=True, unit="s")
    )
    elevation_mask_deg: float = option(10.0, Number(lo=0.0, hi=90.0, hi_open=True, unit="deg"))
    slip_threshold_m: float = option(0.04, Number(lo=0.0, hi=10.0, lo_open=True, unit="m"))

    def __post_init__(self) -> None:
        check_fields(self)
