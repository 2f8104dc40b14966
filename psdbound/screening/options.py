"""What the screening excludes: its options, in a module that imports nothing heavy.

The configuration and every command's ``--help`` check these options without
loading the screening's statistics (scipy).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from psdbound.common.options import (
    Boolean,
    Number,
    OptionError,
    Spec,
    Text,
    Tuple,
    check_fields,
    option,
)

__all__ = ["FALSE_ALARM", "ScreeningOptions"]

#: Default false-alarm probability per 5-min block.
FALSE_ALARM = 1e-3


class _Span(Spec):
    """A satellite's time span ``[sat, start_gps_s, stop_gps_s]``, GPS seconds."""

    def describe(self) -> str:
        """Describe what is allowed."""
        return "a span [satellite, start, stop] in GPS seconds, start < stop"

    def check(self, value: Any) -> Any:
        """Check and normalise ``value``."""
        if not isinstance(value, list | tuple) or len(value) != 3:
            raise ValueError("")
        sat = Text(what="a satellite id").check(value[0])
        a, b = (Number(lo=0.0, hi=1e11).check(v) for v in value[1:])
        if not a < b:
            raise ValueError("start must be before stop")
        return (sat, float(a), float(b))


@dataclass(frozen=True)
class ScreeningOptions:
    """What the screening excludes.

    Parameters
    ----------
    roti_threshold_tecu_min : float, default 0.15
        With the multipath null, the ionospheric significance level: no block
        with a smaller ROTI is called ionosphere, whatever the null says
        (dual-frequency), TECU/min. For the fixed threshold (and as well
        under an untrusted null), the level multiplied by the elevation
        mapping when ``elevation_scaled``.
    roti_cap_tecu_min : float or None, default None
        Largest threshold after the elevation scaling, TECU/min (None: no cap).
    elevation_scaled : bool, default True
        Scale the threshold by ``m(el)`` (needs a mapping; see the module
        docstring).
    guard_s : float or None, default None
        Widening of every flagged span on each side, s; None: half a cutoff
        period ``0.5 / f_c`` of the series' high-pass (0 without one).
    ionosphere : bool, default True
        Apply the ROTI test (dual-frequency only).
    plausibility : bool, default True
        Apply the carrier-multipath limit.
    multipath_null : bool, default True
        Compare ROTI with what the series' own multipath produces at that
        elevation (:mod:`psdbound.screening.null`): a block is ionosphere
        when its ROTI exceeds both ``roti_threshold_tecu_min`` (unscaled) and
        the null's ``1 - false_alarm`` quantile. False: the elevation-scaled
        fixed threshold (``elevation_scaled``, ``roti_cap_tecu_min``).
    false_alarm : float, default 1e-3
        False-alarm probability per 5-min block under multipath alone.
    three_frequency : bool, default True
        Where the series has a third carrier, apply the three-frequency test
        (:mod:`psdbound.screening.threefreq`; with the multipath null only).
    keep_spans : tuple of (str, float, float), default ()
        Spans ``(satellite, start_gps_s, stop_gps_s)`` known to hold
        multipath: blocks the ionosphere tests flag there are kept (counted
        in the notes). A campaign fills it with the spans that repeat one
        sidereal day later (:mod:`psdbound.campaign.sidereal`); the physical
        limit still applies.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range (thresholds > 0 and at
        most 100 TECU/min, the cap not below the threshold, the guard from 0
        to 86400 s).
    """

    roti_threshold_tecu_min: float = option(
        0.15, Number(lo=0.0, hi=100.0, lo_open=True, unit="TECU/min")
    )
    roti_cap_tecu_min: float | None = option(
        None, Number(lo=0.0, hi=100.0, lo_open=True, unit="TECU/min", optional=True)
    )
    elevation_scaled: bool = option(True, Boolean())
    guard_s: float | None = option(None, Number(lo=0.0, hi=86400.0, unit="s", optional=True))
    ionosphere: bool = option(True, Boolean())
    plausibility: bool = option(True, Boolean())
    multipath_null: bool = option(True, Boolean())
    false_alarm: float = option(FALSE_ALARM, Number(lo=0.0, hi=0.5, lo_open=True))
    three_frequency: bool = option(True, Boolean())
    keep_spans: tuple[tuple[str, float, float], ...] = option(
        (), Tuple(_Span(), max_len=100000, what="a list of spans [satellite, start, stop]")
    )

    def __post_init__(self) -> None:
        check_fields(self)
        cap = self.roti_cap_tecu_min
        if cap is not None and cap < self.roti_threshold_tecu_min:
            raise OptionError(
                "roti_cap_tecu_min",
                cap,
                f"a number >= roti_threshold_tecu_min = {self.roti_threshold_tecu_min:g} "
                "TECU/min (or unset)",
            )
