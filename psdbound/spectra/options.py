"""Options of the spectra stage: the PSD estimator and the bound fit."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from psdbound.common.options import (
    Boolean,
    Choice,
    Number,
    OptionError,
    Spec,
    Table,
    Text,
    check_fields,
    option,
)
from psdbound.spectra.names import METHODS, OBJECTIVES, RULES, TAU_MAX_S

__all__ = ["BoundOptions", "ESTIMATOR_OPTIONS", "SpectraOptions", "check_estimator_options"]


class _TextOrFlag(Spec):
    """A name (``"constant"``) or a boolean (``False``: no detrending)."""

    def describe(self) -> str:
        return "a name or true/false"

    def check(self, value: Any) -> Any:
        if isinstance(value, bool):
            return value
        return Text().check(value)


_NFFT = Number(lo=1, hi=1e7, integer=True)

#: The keyword options of each estimator (see :func:`psdbound.spectra.estimate_psd`) and
#: what they accept before the data are known (ranges that depend on the window length
#: are checked by the estimators).
ESTIMATOR_OPTIONS: dict[str, dict[str, Spec]] = {
    "multitaper": {
        "nw": Number(lo=0.0, hi=1e4, lo_open=True),
        "k": Number(lo=1, hi=1e4, integer=True),
        "adaptive": Boolean(),
        "nfft": _NFFT,
    },
    "welch": {
        "nperseg": Number(lo=2, hi=1e7, integer=True),
        "noverlap": Number(lo=0, hi=1e7, integer=True),
        "window": Text(what="a window name such as 'hann'"),
        "detrend": _TextOrFlag(),
        "nfft": _NFFT,
    },
    "blackman-tukey": {
        "max_lag_fraction": Number(lo=0.0, hi=1.0, lo_open=True),
        "alpha": Number(lo=0.0, hi=1.0),
        "nfft": _NFFT,
    },
}


def check_estimator_options(estimator: str | None, options: dict[str, Any]) -> dict[str, Any]:
    """Check the estimator keyword options; return them normalised.

    Parameters
    ----------
    estimator : str or None
        The estimator the options are for; None: any estimator that has
        the option.
    options : dict
        ``{name: value}``.

    Returns
    -------
    dict

    Raises
    ------
    OptionError
        An option the estimator does not have (naming the valid ones), or a
        value of the wrong type or range.
    """
    table = ESTIMATOR_OPTIONS.get(estimator, {}) if estimator else {}
    out = {}
    for key, value in options.items():
        spec = table.get(key)
        if spec is None and estimator is None:
            spec = next((t[key] for t in ESTIMATOR_OPTIONS.values() if key in t), None)
        if spec is None:
            valid = (
                sorted(table)
                if estimator
                else sorted({k for t in ESTIMATOR_OPTIONS.values() for k in t})
            )
            whose = f"{estimator} options" if estimator else "estimator options"
            raise OptionError("options", key, f"names of {whose} ({', '.join(valid)})")
        try:
            out[key] = spec(f"options.{key}", value)
        except OptionError as exc:
            raise OptionError(f"options.{key}", value, exc.expected, detail=exc.detail) from None
    return out


class _EstimatorOptions(Table):
    def check(self, value: Any) -> Any:
        return check_estimator_options(None, super().check(value))


@dataclass(frozen=True)
class SpectraOptions:
    """PSD estimator and its keyword options.

    Parameters
    ----------
    estimator : {"multitaper", "welch", "blackman-tukey"}
        Estimator (see :func:`psdbound.spectra.estimate_psd`).
    options : dict
        Estimator keyword options (e.g. ``{"nw": 4}`` for multitaper; see
        :data:`ESTIMATOR_OPTIONS`). That they belong to ``estimator`` is
        checked by ``FitConfig.check`` (they may be set before it).

    Raises
    ------
    OptionError
        An unknown estimator, an option no estimator has, or a value of the
        wrong type.
    """

    estimator: str = option("multitaper", Choice(METHODS, noun="PSD estimator"))
    options: dict[str, Any] = option(default_factory=dict, spec=_EstimatorOptions())

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class BoundOptions:
    """How the bound is fitted.

    Parameters
    ----------
    rule : {"pooled", "envelope"}
        ``"pooled"`` (default): upper confidence limits of the windows'
        pooled band spectra at a family-wise ``confidence_level``
        (:mod:`psdbound.spectra.pooled`); ``"envelope"``: the thesis's
        envelope of every window's PSD (``target``, ``level``).
    objective : {"variance", "area"}
        Tightness objective minimised.
    confidence_level : float
        Confidence of the pooled rule's statement, in (0, 1).
    coverage : float
        Pooled rule: fraction of the windows whose true PSD the bound
        covers (all but ``floor((1 - coverage) M)`` of ``M``), in (0.5, 1].
    shape_alpha : float
        Pooled rule: family-wise level of the tests that give a window of
        another spectral shape a group of its own.
    bands_per_decade : int
        Pooled rule: frequency bands per decade.
    target : {"point", "upper"}
        Envelope rule: bound the PSD estimates or their upper confidence limits.
    level : float
        Envelope rule: confidence level of the per-window upper limits
        (``target="upper"``), in (0, 1).
    tau_max_s : float
        Pooled rule: prior upper limit of the multipath time constant,
        seconds. Below the lowest band the bound lies above every model the
        data admit; where the data do not bound ``tau`` above, only models up
        to this one (:mod:`psdbound.spectra.lowfreq`).

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range.
    """

    rule: str = option("pooled", Choice(RULES, noun="bound rule"))
    objective: str = option("variance", Choice(OBJECTIVES, noun="objective"))
    confidence_level: float = option(0.95, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    coverage: float = option(0.99, Number(lo=0.5, hi=1.0, lo_open=True))
    shape_alpha: float = option(0.05, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    bands_per_decade: int = option(10, Number(lo=1, hi=100, integer=True))
    target: str = option("point", Choice(("point", "upper"), noun="target"))
    level: float = option(0.95, Number(lo=0.0, hi=1.0, lo_open=True, hi_open=True))
    tau_max_s: float = option(TAU_MAX_S, Number(lo=0.0, hi=1e6, lo_open=True, unit="s"))

    def __post_init__(self) -> None:
        check_fields(self)
