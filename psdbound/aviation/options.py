"""Options of the code-multipath overbound as the fit runs it (``[code_multipath]``)."""

from __future__ import annotations

from dataclasses import dataclass

from psdbound.common.options import (
    Choice,
    Number,
    OptionError,
    Text,
    Tuple,
    check_fields,
    option,
)

#: Gaussian overbound constructions (:mod:`psdbound.aviation.overbound`).
METHODS = ("paired", "two_step", "cdf")
#: Default elevation bin edges of the overbounds, deg.
DEFAULT_EDGES_DEG = (5.0, 15.0, 30.0, 45.0, 60.0, 90.0)

__all__ = ["CodeMultipathOptions"]


@dataclass(frozen=True)
class CodeMultipathOptions:
    """Code multipath by carrier levelling and its Gaussian overbound per elevation bin.

    Off by default (no ``codes``). With one pseudorange code (``("C1C",)``)
    the fit also computes the single-frequency code multipath (the MP
    combination, ionosphere removed with the two carriers); with two
    (``("C1C", "C5Q")``) the ionosphere-free code-minus-carrier; each arc's
    mean is removed (carrier levelling). The samples are then overbounded
    per elevation bin (:func:`psdbound.aviation.overbound_by_elevation`).

    Parameters
    ----------
    codes : tuple of str, default ()
        Zero (off), one or two pseudorange codes such as ``"C1C"`` (RINEX 2
        files: ``"C1"``, ``"P1"``, ``"P2"`` or the RINEX 3 names).
    edges_deg : tuple of float, default (5, 15, 30, 45, 60, 90)
        Elevation bin edges, degrees, increasing, 0 to 90.
    method : {"paired", "two_step", "cdf"}, default "paired"
        Overbound construction (paired: bias and sigma, no exempted core).
    min_length_s : float, default 600
        Shortest carrier-levelling arc, s (the seeds use 600 s): the arc mean
        is the levelling constant, and a short arc levels poorly.
    min_samples : int, default 100
        Fewest samples an elevation bin may hold (fewer: the bin is reported
        and skipped, never bounded from a handful of points).

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range.
    """

    codes: tuple[str, ...] = option(
        (),
        Tuple(
            Text(r"[CP][1-9][A-Z]?", what="a pseudorange code such as 'C1C' (RINEX 2: P2)"),
            max_len=2,
            split=",",
            distinct=True,
            what="up to two pseudorange codes such as 'C1C,C5Q'",
        ),
    )
    edges_deg: tuple[float, ...] = option(
        DEFAULT_EDGES_DEG,
        Tuple(
            Number(lo=0.0, hi=90.0, unit="deg"),
            min_len=2,
            max_len=30,
            split=",",
            what="increasing elevation edges in degrees such as '5,15,30,60,90'",
        ),
    )
    method: str = option("paired", Choice(METHODS, noun="overbound method"))
    min_length_s: float = option(600.0, Number(lo=0.0, hi=86400.0, lo_open=True, unit="s"))
    min_samples: int = option(100, Number(lo=10, hi=1e9, integer=True))

    def __post_init__(self) -> None:
        check_fields(self)
        e = self.edges_deg
        if any(b <= a for a, b in zip(e, e[1:], strict=False)):
            raise OptionError(
                "edges_deg",
                e,
                "increasing elevation edges in degrees",
                detail="each edge must exceed the one before",
            )

    @property
    def enabled(self) -> bool:
        """True when at least one code is given."""
        return bool(self.codes)
