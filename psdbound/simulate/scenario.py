"""Simulation scenarios: every parameter of a simulated data set, presets, and text forms.

Every field of :class:`Scenario` and :class:`MultipathModel` has a schema
(:mod:`psdbound.common.options`), so a scenario built in the library, read
from a TOML file (:meth:`Scenario.from_toml`: top-level keys are scenario
fields, a ``[multipath]`` table holds multipath fields or ``mapping = [a, b,
c_deg]``, ``[[multipath.reflections]]`` and ``[[disturbances]]`` are arrays
of tables) or given as ``--multipath`` text (:meth:`MultipathModel.from_spec`,
``"sigma_gm_m=0.004,tau_s=120,mapping=1,12,10"``) is checked alike: a bad
value raises an :class:`~psdbound.common.options.OptionError` naming it.

Carrier-phase multipath cannot exceed a quarter of the carrier wavelength
(4.8 cm on GPS L1), so the standard deviations of the injected error are
limited to :data:`MAX_MULTIPATH_M` = 0.05 m (zenith scale).
"""

from __future__ import annotations

import datetime as _dt
import hashlib
import json
import math
import os
import re
from collections.abc import Mapping
from dataclasses import MISSING, asdict, dataclass, field, fields, replace
from pathlib import Path
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
    spec_of,
)
from psdbound.common.tomlfile import read_toml
from psdbound.errors import InputError

__all__ = [
    "MAX_MULTIPATH_M",
    "MULTIPATH_SPEC_EXAMPLE",
    "IonoDisturbance",
    "Reflection",
    "MultipathModel",
    "Scenario",
    "PRESETS",
    "preset",
]

#: Largest standard deviation of injected carrier error, m: about a quarter wavelength.
MAX_MULTIPATH_M = 0.05
#: An example of :meth:`MultipathModel.from_spec` text (used in messages).
MULTIPATH_SPEC_EXAMPLE = "sigma_gm_m=0.003,tau_s=120,sigma_wn_m=0.001,mapping=1,12,10"
_QUARTER_WAVE = "carrier multipath cannot exceed a quarter wavelength, about 5 cm"
_SIGMAS = ("sigma_gm_m", "sigma_wn_m", "receiver_noise_m")


def _required(spec: Spec) -> Any:
    """Return a dataclass field without default, with its schema."""
    return field(metadata={"spec": spec})


@dataclass(frozen=True)
class Reflection:
    """A deterministic specular reflector (docs/method/isolation.rst).

    Parameters
    ----------
    kind : {"ground", "wall"}
        Ground: extra path ``2 h sin(el)``; wall: ``2 d cos(el)``.
    distance_m : float
        Antenna height ``h`` above the ground, or distance ``d`` to the wall, m.
    alpha : float
        Reflected-to-direct amplitude ratio (< 1).
    """

    kind: str = _required(Text(pattern="ground|wall", what="'ground' or 'wall'"))
    distance_m: float = _required(Number(lo=0.0, lo_open=True, unit="m"))
    alpha: float = _required(Number(lo=0.0, hi=1.0, hi_open=True))

    def __post_init__(self) -> None:
        if self.kind not in ("ground", "wall"):
            raise InputError(f"reflection kind must be 'ground' or 'wall', got {self.kind!r}")
        if not self.distance_m > 0 or not 0 <= self.alpha < 1:
            raise InputError(
                f"reflection needs distance > 0 m and 0 <= alpha < 1; got {self.distance_m}, "
                f"{self.alpha}"
            )


@dataclass(frozen=True)
class IonoDisturbance:
    """A span of fast ionospheric phase fluctuations (ground truth for the screening).

    Inside the span the slant TEC of the chosen satellites gets a random walk
    whose 30-s increments have the standard deviation ``0.5 roti_tecu_min``
    TECU, so that ROT (TECU/min, 30 s) has the standard deviation
    ``roti_tecu_min``: the span's ROTI (Pi et al. 1997). Outside the span
    the walk is frozen, so the TEC stays continuous.

    Parameters
    ----------
    start_s : float
        Start, seconds after the scenario's start.
    duration_s : float
        Length of the span, s.
    roti_tecu_min : float
        ROTI of the fluctuations, TECU/min.
    sats : tuple of str
        Affected satellites (e.g. ``("G05", "G12")``); empty: every satellite.
    """

    start_s: float = _required(Number(lo=0.0, unit="s"))
    duration_s: float = _required(Number(lo=0.0, lo_open=True, unit="s"))
    roti_tecu_min: float = _required(Number(lo=0.0, lo_open=True, unit="TECU/min"))
    sats: tuple[str, ...] = option(
        (), Tuple(Text(pattern=r"[GE]\d{2}", what="a satellite such as G05"))
    )

    def __post_init__(self) -> None:
        if not (self.start_s >= 0 and self.duration_s > 0 and self.roti_tecu_min > 0):
            raise InputError(
                "an ionospheric disturbance needs start_s >= 0 s, duration_s > 0 s and "
                f"roti_tecu_min > 0; got {self.start_s}, {self.duration_s}, {self.roti_tecu_min}"
            )


@dataclass(frozen=True)
class MultipathModel:
    """Per-signal carrier-phase error: mapped Gauss-Markov + white noise (+ reflections).

    The error of one signal is ``m(el) * (GM + WN) + sum of reflections``
    with ``m(el) = a + b exp(-el^2 / (2 c^2))`` (thesis mapping), GM a
    first-order Gauss-Markov process (``sigma_gm_m``, ``tau_s``) and WN white
    noise (``sigma_wn_m`` per sample), independent per signal and satellite.

    Parameters
    ----------
    sigma_gm_m : float
        Gauss-Markov standard deviation at zenith scale, m, in [0, 0.05].
    tau_s : float
        Gauss-Markov time constant, s, in (0, 86400].
    sigma_wn_m : float
        White-noise standard deviation per sample at zenith scale, m, in [0, 0.05].
    a, b : float
        Dimensionless mapping coefficients, ``0 < a <= 1000``, ``0 <= b <= 10000``.
    c_deg : float
        Mapping width, degrees, in (0, 90].
    reflections : tuple of Reflection
        Deterministic reflectors, exact formula ``atan2(alpha sin psi,
        1 + alpha cos psi)``.

    Raises
    ------
    OptionError
        A value of the wrong type or outside its range.
    """

    sigma_gm_m: float = option(0.003, Number(lo=0.0, hi=MAX_MULTIPATH_M, unit="m"))
    tau_s: float = option(30.0, Number(lo=0.0, lo_open=True, hi=86400.0, unit="s"))
    sigma_wn_m: float = option(0.001, Number(lo=0.0, hi=MAX_MULTIPATH_M, unit="m"))
    a: float = option(1.0, Number(lo=0.0, lo_open=True, hi=1e3))
    b: float = option(9.0, Number(lo=0.0, hi=1e4))
    c_deg: float = option(15.0, Number(lo=0.0, lo_open=True, hi=90.0, unit="deg"))
    reflections: tuple[Reflection, ...] = ()

    def __post_init__(self) -> None:
        for f in fields(self):
            if (spec := f.metadata.get("spec")) is not None:
                object.__setattr__(
                    self, f.name, _check(f.name, getattr(self, f.name), spec, f.name)
                )
        refl = self.reflections
        if not isinstance(refl, list | tuple) or not all(isinstance(r, Reflection) for r in refl):
            raise InputError(f"reflections must be a tuple of Reflection, got {refl!r}")
        object.__setattr__(self, "reflections", tuple(refl))

    def factor(self, elevation_deg: float) -> float:
        """Return the mapping ``m(el) = a + b exp(-el^2 / (2 c^2))`` at an elevation in degrees."""
        return self.a + self.b * math.exp(-(elevation_deg**2) / (2.0 * self.c_deg**2))

    @classmethod
    def from_spec(
        cls, text: str, *, base: MultipathModel | None = None, label: str = "--multipath"
    ) -> MultipathModel:
        """Parse ``"key=value,..."`` (the command line's ``--multipath``) onto a base model.

        Parameters
        ----------
        text : str
            Comma-separated ``key=value`` items, any subset of ``sigma_gm_m``
            (m), ``tau_s`` (s), ``sigma_wn_m`` (m), ``a``, ``b``, ``c_deg``
            (degrees) and ``mapping=a,b,c`` (c in degrees), e.g.
            :data:`MULTIPATH_SPEC_EXAMPLE`. Spaces around items are allowed.
        base : MultipathModel, optional
            Values of the keys not given (default :class:`MultipathModel`'s).
        label : str, default "--multipath"
            How messages name the option.

        Returns
        -------
        MultipathModel

        Raises
        ------
        InputError
            Empty text, an item without ``=``, an unknown or repeated key, a
            value that is not a number or outside its range (an
            :class:`OptionError` naming ``label``, the key and what is allowed).
        """
        base = cls() if base is None else base
        hint = f"expected comma-separated key=value items, e.g. {MULTIPATH_SPEC_EXAMPLE!r}"
        if not isinstance(text, str) or not text.strip():
            raise InputError(f"{label} is empty; {hint}")
        items: list[tuple[str, list[str]]] = []
        for token in (t.strip() for t in text.split(",")):
            if "=" in token:
                key, _, value = token.partition("=")
                items.append((key.strip(), [value.strip()]))
            elif items and items[-1][0] == "mapping":
                items[-1][1].append(token)
            else:
                raise InputError(f"{label}: item {token!r} has no '='; {hint}")
        keys = [f.name for f in fields(cls) if f.name != "reflections"]
        changes: dict[str, Any] = {}
        for key, values in items:
            if key not in (*keys, "mapping"):
                raise InputError(
                    f"{label}: unknown key {key!r}; expected any of {', '.join(keys)} or "
                    f"mapping=a,b,c (c in degrees), e.g. {MULTIPATH_SPEC_EXAMPLE!r}"
                )
            names = ("a", "b", "c_deg") if key == "mapping" else (key,)
            if key == "mapping" and len(values) != 3:
                raise OptionError(
                    "mapping",
                    ",".join(values),
                    "three numbers a,b,c (c in degrees)",
                    label=f"{label} mapping",
                )
            for name, raw in zip(names, values, strict=True):
                if name in changes:
                    raise InputError(
                        f"{label}: {name} given twice (mapping=a,b,c sets a, b, c_deg)"
                    )
                what = f"{label} {key}" + (f" {name}" if key == "mapping" else "")
                changes[name] = _check(name, _number(raw), spec_of(cls, name), what)
        return replace(base, **changes)


def _number(text: str) -> Any:
    """Return ``text`` as a float when it reads as one, else unchanged (the spec rejects it)."""
    try:
        return float(text)
    except ValueError:
        return text


def _check(name: str, value: Any, spec: Spec | None, label: str, path: str | None = None) -> Any:
    """Check one value against its spec; the error names ``label`` (and the quarter-wave limit)."""
    if spec is None:
        return value
    try:
        return spec(name, value)
    except OptionError as exc:
        big = isinstance(value, float) and value > MAX_MULTIPATH_M and name in _SIGMAS
        detail = _QUARTER_WAVE if big else exc.detail
        raise OptionError(
            name, value, exc.expected, detail=detail, item=exc.item, label=label, path=path
        ) from None


_NAME = r"[A-Za-z0-9][A-Za-z0-9._-]*"
_START = r"\d{4}-\d{2}-\d{2}T\d{2}:\d{2}(:\d{2}(\.\d+)?)?"


def _check_start(text: str) -> None:
    if re.fullmatch(_START, text) is None:
        raise ValueError("")
    _dt.datetime.fromisoformat(text)  # a ValueError names the bad field (month, day, ...)


def _num(
    default: float,
    lo: float | None = None,
    hi: float | None = None,
    unit: str = "",
    lo_open: bool = False,
    hi_open: bool = False,
) -> Any:
    return option(default, Number(lo=lo, hi=hi, unit=unit, lo_open=lo_open, hi_open=hi_open))


@dataclass(frozen=True)
class Scenario:
    """Everything that defines a simulated data set (with the seed).

    Every field is checked when the scenario is built (type and range).

    Parameters
    ----------
    name : str
        File-name stem (letters, digits, ``.``, ``_``, ``-``).
    lat_deg, lon_deg, height_m : float
        Antenna A position (WGS84): degrees in [-90, 90] and [-180, 360], metres.
    start_gps : str
        Start epoch, ISO calendar label in GPS time (``"2020-11-24T14:00:00"``).
    duration_s, interval_s : float
        Span (at most 366 days) and sampling interval (at most 3600 s), seconds.
    systems : str
        ``"G"`` (GPS L1C/L2W), ``"E"`` or ``"GE"`` (plus Galileo L1C/L5Q).
    nav_path : str or None
        Navigation file for the geometry; None uses the nominal constellation.
    elevation_mask_deg : float
        Satellites are tracked above this elevation, degrees.
    multipath : MultipathModel
        The injected error model.
    receiver_noise_m : float
        Extra white phase noise per signal, metres (part of the truth error;
        added after the mapping, so it is not scaled by ``m(el)``), at most 0.05 m.
    code_noise_m : float
        Code noise at zenith, metres (scaled by the mapping).
    vtec_day_tecu, vtec_night_tecu : float
        Smooth diurnal vertical TEC (peak at 14 h local time), TECU.
    tid_amplitude_tecu, tid_period_s : float
        A travelling-disturbance term (per-satellite phase), TECU and seconds.
    disturbances : tuple of IonoDisturbance
        Spans of fast ionospheric fluctuations with a chosen ROTI (written to
        the truth JSON; drawn from their own random stream, so adding them
        changes nothing else).
    zenith_tropo_m : float
        Zenith tropospheric delay, metres (1/sin(el) mapping).
    slip_rate_per_h : float
        Cycle slips per satellite per hour (one carrier, 1-3 cycles).
    slip_lli_fraction : float
        Fraction of slips the receiver flags with the LLI bit.
    gap_rate_per_h, gap_max_s : float
        Tracking gaps per satellite per hour and their maximum length, s.
    dual_antenna : bool
        Also write antenna B.
    baseline_enu_m : tuple of float
        Antenna B minus antenna A, east/north/up metres.
    header_error_enu_m : tuple of float
        Error of antenna B's ``APPROX POSITION XYZ`` in the written header
        (header minus truth), east/north/up metres; the phases use the truth.
    common_fraction : float
        Fraction of the multipath variance common to both antennas (it
        cancels in the dual-antenna difference).
    receiver_clock_s : tuple of float
        Receiver clock offsets of antennas A and B at the start, seconds.
    seed : int
        Seed of every random draw (>= 0).

    Raises
    ------
    OptionError, InputError
        A value of the wrong type or outside its range, more than 2e6 epochs.
    """

    name: str = option(
        "sim", Text(pattern=_NAME, what="a file-name stem (letters, digits, '.', '_', '-')")
    )
    lat_deg: float = option(41.84, Number(unit="deg"))  # range checked with its own message
    lon_deg: float = _num(-87.63, -180.0, 360.0, "deg")
    height_m: float = _num(180.0, -1e3, 1e5, "m")
    start_gps: str = option(
        "2020-11-24T14:00:00",
        Text(validate=_check_start, what="an ISO date-time 'YYYY-MM-DDTHH:MM:SS' (GPS time)"),
    )
    duration_s: float = _num(4 * 3600.0, 0.0, 366 * 86400.0, "s", lo_open=True)
    interval_s: float = _num(1.0, 0.0, 3600.0, "s", lo_open=True)
    systems: str = option("G", Text(pattern="G|E|GE|EG", what="'G', 'E' or 'GE'"))
    nav_path: str | None = option(None, Text(optional=True, paths=True, what="a file path"))
    elevation_mask_deg: float = _num(5.0, 0.0, 90.0, "deg", hi_open=True)
    multipath: MultipathModel = field(default_factory=MultipathModel)
    receiver_noise_m: float = _num(0.0005, 0.0, MAX_MULTIPATH_M, "m")
    code_noise_m: float = _num(0.3, 0.0, 100.0, "m")
    vtec_day_tecu: float = _num(25.0, 0.0, 1000.0, "TECU")
    vtec_night_tecu: float = _num(5.0, 0.0, 1000.0, "TECU")
    tid_amplitude_tecu: float = _num(0.3, 0.0, 1000.0, "TECU")
    tid_period_s: float = _num(3600.0, 0.0, 1e6, "s", lo_open=True)
    disturbances: tuple[IonoDisturbance, ...] = ()
    zenith_tropo_m: float = _num(2.4, 0.0, 10.0, "m")
    slip_rate_per_h: float = _num(0.2, 0.0, 3600.0, "per h")
    slip_lli_fraction: float = _num(0.5, 0.0, 1.0)
    gap_rate_per_h: float = _num(0.2, 0.0, 3600.0, "per h")
    gap_max_s: float = _num(120.0, 0.0, 86400.0, "s", lo_open=True)
    dual_antenna: bool = option(True, Boolean())
    baseline_enu_m: tuple[float, float, float] = option(
        (5.0, 0.0, 0.0),
        Tuple(Number(lo=-1e4, hi=1e4), lengths=(3,), what="three numbers: east, north, up in m"),
    )
    header_error_enu_m: tuple[float, float, float] = option(
        (0.0, 0.0, 0.0),
        Tuple(Number(lo=-1e3, hi=1e3), lengths=(3,), what="three numbers: east, north, up in m"),
    )
    common_fraction: float = _num(0.3, 0.0, 1.0)
    receiver_clock_s: tuple[float, float] = option(
        (2.5e-4, -4.0e-4),
        Tuple(Number(lo=-1.0, hi=1.0), lengths=(2,), what="two clock offsets (A, B) in s"),
    )
    seed: int = option(1, Number(lo=0, hi=2**63 - 1, integer=True))

    def __post_init__(self) -> None:
        check_fields(self)
        if not -90.0 <= self.lat_deg <= 90.0:  # an OptionError: the command line names its flag
            raise OptionError("lat_deg", self.lat_deg, "within [-90, 90] deg", label="latitude")
        if self.duration_s / self.interval_s > 2_000_000:
            raise InputError("more than 2e6 epochs requested; shorten or decimate")
        if not isinstance(self.multipath, MultipathModel):
            raise InputError(f"multipath must be a MultipathModel, got {self.multipath!r}")
        dist = self.disturbances
        if not isinstance(dist, list | tuple) or not all(
            isinstance(d, IonoDisturbance) for d in dist
        ):
            raise InputError(f"disturbances must be a tuple of IonoDisturbance, got {dist!r}")
        object.__setattr__(self, "disturbances", tuple(dist))

    def to_dict(self) -> dict[str, Any]:
        """All parameters as JSON-compatible data."""
        return json.loads(json.dumps(asdict(self)))

    def digest(self) -> str:
        """SHA-256 of the parameters (identifies a data set).

        Parameters added after a data set was published enter only when set,
        so existing data sets (the demo) keep their identity.
        """
        d = self.to_dict()
        if not any(self.header_error_enu_m):
            d.pop("header_error_enu_m", None)
        blob = json.dumps(d, sort_keys=True).encode()
        return hashlib.sha256(blob).hexdigest()

    def replace(self, **changes: Any) -> Scenario:
        """Return a copy with some parameters changed."""
        return replace(self, **changes)

    # ------------------------------------------------------------- text forms
    @classmethod
    def from_dict(
        cls, data: Mapping[str, Any], *, base: Scenario | None = None, source: str | None = None
    ) -> Scenario:
        """Build from TOML-like data: :class:`Scenario` keys, a ``multipath`` table.

        Parameters
        ----------
        data : mapping
            Field names to values; ``multipath`` a table of
            :class:`MultipathModel` fields (or ``mapping = [a, b, c_deg]``)
            with ``reflections`` a list of tables; ``disturbances`` a list of
            tables of :class:`IonoDisturbance` fields.
        base : Scenario, optional
            Values of the keys not given (default ``Scenario()``); a
            ``multipath`` table changes only the keys it holds.
        source : str, optional
            The file the data came from (named in messages).

        Returns
        -------
        Scenario

        Raises
        ------
        InputError
            An unknown key or a bad value (the message names the key and file).
        """
        base = cls() if base is None else base
        if not isinstance(data, Mapping):
            raise InputError("a scenario must be a table of key = value", path=source)
        names = [f.name for f in fields(cls)]
        changes: dict[str, Any] = {}
        for key, value in data.items():
            if key not in names:
                raise InputError(
                    f"unknown key {key!r}; expected one of {', '.join(names)}", path=source
                )
            if key == "multipath":
                changes[key] = _multipath_from_table(value, base.multipath, source)
            elif key == "disturbances":
                changes[key] = _tables(IonoDisturbance, value, "disturbances", source)
            else:
                changes[key] = _check(key, value, spec_of(cls, key), key, source)
        try:
            return replace(base, **changes)
        except OptionError as exc:
            raise exc.relabel(exc.label, path=source) from None
        except InputError as exc:
            raise InputError(exc.reason, path=source) from None

    @classmethod
    def from_toml(cls, path: str | os.PathLike[str], *, base: Scenario | None = None) -> Scenario:
        """Read a scenario TOML file (see the module docstring and :meth:`from_dict`).

        A relative ``nav_path`` is taken relative to the file's folder.

        Parameters
        ----------
        path : str or path-like
            The TOML file.
        base : Scenario, optional
            Values of the keys the file does not give (default ``Scenario()``).

        Returns
        -------
        Scenario

        Raises
        ------
        InputError
            Missing or unreadable file, invalid TOML, an unknown key or a bad
            value (the message names the file and the key).
        """
        p = Path(path)
        data = read_toml(p, what="scenario file")
        nav = data.get("nav_path")
        if isinstance(nav, str) and nav.strip() and not Path(nav).is_absolute():
            data["nav_path"] = str(p.parent / nav)
        return cls.from_dict(data, base=base, source=str(p))

    def to_toml(self) -> str:
        """Return the scenario as TOML text that :meth:`from_toml` reads back equal.

        Returns
        -------
        str
            Every field (``nav_path`` only when set), units as in the field names.
        """
        lines = ["# psdbound simulation scenario (psdbound.simulate.Scenario.from_toml)"]
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name not in ("multipath", "disturbances") and value is not None:
                lines.append(f"{f.name} = {_toml_value(value)}")
        lines += ["", "[multipath]"]
        for f in fields(self.multipath):
            if f.name != "reflections":
                lines.append(f"{f.name} = {_toml_value(getattr(self.multipath, f.name))}")
        for r in self.multipath.reflections:
            lines += ["", "[[multipath.reflections]]"]
            lines += [f"{k} = {_toml_value(v)}" for k, v in asdict(r).items()]
        for d in self.disturbances:
            lines += ["", "[[disturbances]]"]
            lines += [f"{k} = {_toml_value(v)}" for k, v in asdict(d).items()]
        return "\n".join(lines) + "\n"


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    return "[" + ", ".join(_toml_value(x) for x in v) + "]"


def _tables(cls: type, value: Any, where: str, source: str | None) -> tuple[Any, ...]:
    """Build a tuple of ``cls`` from a list of tables ``[[where]]``."""
    if not isinstance(value, list) or not all(isinstance(v, Mapping) for v in value):
        raise InputError(f"{where} must be a list of tables ([[{where}]])", path=source)
    specs = {f.name: f.metadata["spec"] for f in fields(cls)}
    out = []
    for i, table in enumerate(value, start=1):
        args = {}
        for key, v in table.items():
            if key not in specs:
                raise InputError(
                    f"unknown key {key!r} in [[{where}]] item {i}; expected one of "
                    f"{', '.join(specs)}",
                    path=source,
                )
            args[key] = _check(key, v, specs[key], f"[[{where}]] item {i} {key}", source)
        missing = [f.name for f in fields(cls) if f.name not in args and f.default is MISSING]
        if missing:
            raise InputError(f"[[{where}]] item {i} lacks {', '.join(missing)}", path=source)
        try:
            out.append(cls(**args))
        except InputError as exc:
            raise InputError(f"[[{where}]] item {i}: {exc.reason}", path=source) from None
    return tuple(out)


def _multipath_from_table(value: Any, base: MultipathModel, source: str | None) -> MultipathModel:
    """Build the ``[multipath]`` table onto ``base`` (``mapping = [a, b, c_deg]`` accepted)."""
    if not isinstance(value, Mapping):
        raise InputError("multipath must be a table ([multipath])", path=source)
    names = [f.name for f in fields(MultipathModel)]
    changes: dict[str, Any] = {}
    for key, v in value.items():
        if key == "mapping":
            if not isinstance(v, list) or len(v) != 3:
                raise OptionError(
                    "mapping",
                    v,
                    "three numbers [a, b, c_deg]",
                    label="[multipath] mapping",
                    path=source,
                )
            for name, x in zip(("a", "b", "c_deg"), v, strict=True):
                if name in value:
                    raise InputError(
                        f"[multipath] sets {name} twice (mapping and {name})", path=source
                    )
                spec = spec_of(MultipathModel, name)
                changes[name] = _check(name, x, spec, f"[multipath] mapping {name}", source)
        elif key == "reflections":
            changes[key] = _tables(Reflection, v, "multipath.reflections", source)
        elif key in names:
            spec = spec_of(MultipathModel, key)
            changes[key] = _check(key, v, spec, f"[multipath] {key}", source)
        else:
            raise InputError(
                f"unknown key {key!r} in [multipath]; expected one of "
                f"{', '.join(names)} or mapping",
                path=source,
            )
    return replace(base, **changes)


#: Named scenarios. ``demo``: 4 h at 1 Hz, GPS, two antennas 5 m apart on a
#: Chicago rooftop on the thesis's collection day, nominal constellation.
PRESETS: dict[str, Scenario] = {
    "demo": Scenario(name="psdbound-demo", seed=2020),
    "short": Scenario(name="psdbound-short", duration_s=2 * 3600.0, seed=7),
}


def preset(name: str) -> Scenario:
    """Return a named scenario (see :data:`PRESETS`)."""
    try:
        return PRESETS[name]
    except KeyError:
        raise InputError(f"unknown preset {name!r}; available: {', '.join(PRESETS)}") from None
