"""Options of the cutoff validation as the fit runs it."""

from __future__ import annotations

from dataclasses import dataclass

from psdbound.common.options import Boolean, Number, Text, Tuple, check_fields, option

__all__ = ["ValidationOptions"]


def _check_geometry(text: str) -> None:
    """Raise InputError unless ``text`` is a geometry the fit can use."""
    from psdbound.validation.geometry import parse_geometry

    if text.replace(" ", "").lower() != "ground:h=header":
        parse_geometry(text)


def _check_rate(text: str) -> None:
    """Raise InputError unless ``text`` is a known rate or a frequency in Hz."""
    from psdbound.validation.modes import resolve_rate

    resolve_rate(text)


@dataclass(frozen=True)
class ValidationOptions:
    """Cutoff validation: reflection geometries, amplitude ratio alpha, threshold.

    ``geometries``: ``"wall:d=25"``, ``"ground:h=1.5"`` ...; ``"ground:h=header"``
    takes the antenna height ``ANTENNA: DELTA H`` of the (first) observation
    file, or ``ground_height_m`` when the header gives 0 (at least one
    geometry). ``alpha``: reflection amplitude ratio, in (0, 1];
    ``threshold``: the thesis's largest fraction of a geometry's multipath
    power below f_c, in (0, 1); ``rate``: geometry rate for the expansion
    (orbit, an aircraft mode or a frequency in Hz); ``ground_height_m``: > 0
    and at most 1000 m. ``snr``: measure the ground reflector's height and
    the amplitude ratio from the file's SNR where it has enough (GNSS-IR,
    :mod:`psdbound.validation.site`); they then replace ``ground:h=header``
    and ``alpha``.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range, or a geometry or
        rate that does not parse.
    """

    geometries: tuple[str, ...] = option(
        ("wall:d=25", "ground:h=header"),
        Tuple(
            Text(what="a geometry such as 'wall:d=25'", validate=_check_geometry),
            min_len=1,
            max_len=50,
            what="a list of geometries such as ['wall:d=25', 'ground:h=header']",
        ),
    )
    alpha: float = option(0.1, Number(lo=0.0, hi=1.0, lo_open=True))
    threshold: float = option(0.10, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    rate: str = option(
        "orbit", Text(what="'orbit', an aircraft mode or a frequency in Hz", validate=_check_rate)
    )
    ground_height_m: float = option(1.5, Number(lo=0.0, hi=1000.0, lo_open=True, unit="m"))
    snr: bool = option(True, Boolean())

    def __post_init__(self) -> None:
        check_fields(self)
