"""Configuration of a ``fit`` run: every option, settable from TOML or the CLI.

A :class:`FitConfig` composes the small frozen options dataclasses that live
next to their stages (:class:`~psdbound.arcs.ArcOptions`,
:class:`~psdbound.ionosphere.CutoffOptions`,
:class:`~psdbound.isolation.HighPass`,
:class:`~psdbound.stationarity.MappingOptions`,
:class:`~psdbound.stationarity.StationarityOptions`,
:class:`~psdbound.spectra.SpectraOptions`,
:class:`~psdbound.spectra.BoundOptions`,
:class:`~psdbound.screening.ScreeningOptions`,
:class:`~psdbound.validation.ValidationOptions`,
:class:`~psdbound.pipeline.verdict.VerdictOptions`,
:class:`~psdbound.aviation.options.CodeMultipathOptions`); the inputs and output
sections are defined here.
``FitConfig.from_toml(path)`` reads the same names (sections ``[inputs]``,
``[arcs]``, ``[cutoff]``, ``[filter]``, ``[screening]``, ``[mapping]``, ``[stationarity]``,
``[spectra]``, ``[bound]``, ``[validation]``, ``[verdict]``, ``[code_multipath]``,
``[output]``); unknown names
are errors. The effective configuration is saved with every result.

Checking
--------
Every option has one schema (:mod:`psdbound.common.options`): its type,
range and unit are checked when a section is built, whether the value comes
from TOML, the command line or the library, before anything is read. A bad
value raises :class:`~psdbound.common.options.OptionError` naming the option
(``[filter] order must be an integer from 1 to 20, got 4.5``).

Rules between options (conflicts, options the chosen method would ignore)
are checked by :meth:`FitConfig.check` once the configuration is complete:
conflicting options are an error, never a silent choice.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from psdbound.arcs.options import ArcOptions
from psdbound.aviation.options import CodeMultipathOptions
from psdbound.common.options import (
    Boolean,
    Choice,
    Number,
    OptionError,
    Spec,
    Text,
    Tuple,
    check_fields,
    option,
    show_value,
    spec_of,
)
from psdbound.common.tomlfile import read_toml
from psdbound.errors import InputError
from psdbound.io.archive import zip_members
from psdbound.ionosphere.policy import CUTOFF_SOURCES, CutoffOptions
from psdbound.isolation import HighPass
from psdbound.isolation.names import BASELINE_MODES, BASELINE_TOLERANCE_M
from psdbound.pipeline.verdict import VerdictOptions
from psdbound.screening import ScreeningOptions
from psdbound.spectra.options import BoundOptions, SpectraOptions, check_estimator_options
from psdbound.stationarity.options import MappingOptions, StationarityOptions
from psdbound.validation.options import ValidationOptions

__all__ = [
    "CUTOFF_RANGE_HZ",
    "FitConfig",
    "InputsConfig",
    "Label",
    "OutputConfig",
    "default_label",
    "section_spec",
]

#: Cutoff frequencies accepted before the data are read, Hz (the Nyquist frequency of
#: the data is checked when the filter is applied).
CUTOFF_RANGE_HZ = (1e-6, 10.0)

#: Systems a fit can use (RINEX letters).
_SYSTEMS = ("G", "E", "R", "C", "J", "S", "I")
_PHASE_CODE = r"L[1-9][A-Z]?"


class _Position(Spec):
    """An ECEF position ``[x, y, z]`` in metres near the Earth's surface (or None if optional)."""

    def __init__(self, optional: bool = False) -> None:
        self.optional = optional

    def describe(self) -> str:
        """Describe what is allowed."""
        return "an ECEF position [x, y, z] in m, 6200 to 6500 km from the Earth's centre"

    def check(self, value: Any) -> Any:
        """Check and normalise ``value``."""
        if value is None and self.optional:
            return None
        xyz = Tuple(Number(), lengths=(3,)).check(value)
        r = math.sqrt(sum(x * x for x in xyz))
        if not 6.2e6 <= r <= 6.5e6:
            raise ValueError(f"{r / 1000:.1f} km from the centre")
        return xyz


@dataclass(frozen=True)
class InputsConfig:
    """Input files and what to take from them.

    ``obs``: one file (dual-frequency) or two (dual-antenna); empty runs the
    demo (a single name is one file). ``nav``: navigation (RINEX 2/3/4) or SP3
    file(s), needed with observation files; several (e.g. of consecutive days,
    or a zip archive of them) are joined into one orbit. ``method``: ``auto`` (DF for one
    file, DA for two), ``df`` or ``da``. ``system``: satellite system letter.
    ``signals``: DF phase pair (default per system, GPS L1C-L2W);
    ``da_signal``: DA phase code. ``pair``: the two antennas of a
    dual-antenna pair, A then B, each a station (marker) name or an
    observation file. ``position_a_m``, ``position_b_m``: ECEF antenna
    positions in m (default the header's); ``receiver_xyz_m`` is the older
    list form of the same (one per antenna). ``baseline``: ``auto`` (the
    baseline estimated from the double differences replaces antenna B's
    position when the correction exceeds ``baseline_tolerance_m`` and three
    standard errors), ``estimate`` (always) or ``given`` (keep the positions).
    """

    obs: tuple[str, ...] = option(
        (),
        Tuple(
            Text(what="a file name", paths=True),
            max_len=100,
            what="a list of observation file names",
        ),
    )
    nav: tuple[str, ...] = option(
        (),
        Tuple(
            Text(what="a file name", paths=True),
            max_len=100,
            what="a list of navigation or SP3 file names",
        ),
    )
    method: str = option("auto", Choice(("auto", "df", "da"), noun="isolation method"))
    system: str = option("G", Choice(_SYSTEMS, noun="satellite system"))
    signals: tuple[str, ...] = option(
        (),
        Tuple(
            Text(_PHASE_CODE, what="a phase code such as 'L1C'"),
            lengths=(0, 2),
            split=",",
            distinct=True,
            what="two phase codes such as 'L1C,L2W'",
        ),
    )
    da_signal: str = option("L1C", Text(_PHASE_CODE, what="a phase code such as 'L1C'"))
    receiver_xyz_m: tuple[tuple[float, float, float], ...] = option(
        (), Tuple(_Position(), max_len=2, what="a list of ECEF positions [x, y, z] in m")
    )
    pair: tuple[str, ...] = option(
        (),
        Tuple(
            Text(what="a station name or observation file", paths=True),
            lengths=(0, 2),
            what="two stations or files: antenna A, antenna B",
        ),
    )
    position_a_m: tuple[float, float, float] | None = option(None, _Position(optional=True))
    position_b_m: tuple[float, float, float] | None = option(None, _Position(optional=True))
    baseline: str = option("auto", Choice(BASELINE_MODES, noun="baseline mode"))
    baseline_tolerance_m: float = option(BASELINE_TOLERANCE_M, Number(lo=0.0, hi=1000.0, unit="m"))

    def __post_init__(self) -> None:
        check_fields(self)


@dataclass(frozen=True)
class OutputConfig:
    """Outputs: folder (default ``reports/<name>``), name, reports, PDF, overwrite, series.

    ``report``: write ``report.html`` (and ``report.pdf`` unless ``pdf`` is
    off); without it only ``result.json`` is written, and ``psdbound report``
    renders the reports later from it alone.
    ``overwrite``: also write into an existing folder that is not a previous
    psdbound output (psdbound's files are replaced, nothing else is touched).
    ``series``: also write ``series.csv.gz``, every isolated sample with its
    direction, screening and window (:mod:`psdbound.results.series_table`).
    """

    out: str | None = option(None, Text(what="a folder name", paths=True, optional=True))
    name: str | None = option(
        None,
        Text(
            r"(?!\.\.?$)[A-Za-z0-9._+-]+",
            optional=True,
            what="a run name of letters, digits and . _ + -",
        ),
    )
    pdf: bool = option(True, Boolean())
    report: bool = option(True, Boolean())
    overwrite: bool = option(False, Boolean())
    series: bool = option(False, Boolean())

    def __post_init__(self) -> None:
        check_fields(self)


_SECTIONS = {
    "inputs": InputsConfig,
    "arcs": ArcOptions,
    "cutoff": CutoffOptions,
    "filter": HighPass,
    "screening": ScreeningOptions,
    "mapping": MappingOptions,
    "stationarity": StationarityOptions,
    "spectra": SpectraOptions,
    "bound": BoundOptions,
    "validation": ValidationOptions,
    "verdict": VerdictOptions,
    "code_multipath": CodeMultipathOptions,
    "output": OutputConfig,
}

# CutoffOptions lives in psdbound.ionosphere and is checked here
_CUTOFF_SPECS: dict[str, Spec] = {
    "f_c_hz": Number(lo=CUTOFF_RANGE_HZ[0], hi=CUTOFF_RANGE_HZ[1], unit="Hz", optional=True),
    "source": Choice(CUTOFF_SOURCES, noun="cutoff source"),
    "mp_sigma_m": Number(lo=0.0, hi=1.0, lo_open=True, unit="m"),
    "margin_db": Number(lo=0.0, hi=200.0, unit="dB"),
}


def section_spec(section: str, name: str) -> Spec | None:
    """Return the schema entry of an option: ``[section] name`` of a fit (None: no such option).

    Parameters
    ----------
    section : str
        A section of :class:`FitConfig` (``"filter"``).
    name : str
        An option of it (``"order"``).

    Returns
    -------
    Spec or None
    """
    if section == "cutoff":
        return _CUTOFF_SPECS.get(name)
    cls = _SECTIONS.get(section)
    return None if cls is None else spec_of(cls, name)


#: How an option is named in messages: ``label(section, name)``.
Label = Callable[[str, str], str]


def default_label(section: str, name: str) -> str:
    """Name an option as in the TOML file: ``[filter] order``."""
    return f"[{section}] {name}"


def _relabel(exc: OptionError, section: str, source: str | None) -> OptionError:
    return exc.relabel(default_label(section, exc.name), section=section, path=source)


@dataclass(frozen=True)
class FitConfig:
    """Every option of a ``fit`` run, by stage (see the module docstring).

    Raises
    ------
    OptionError
        When built with a value outside its schema (also from
        :meth:`updated`, :meth:`from_dict` and :meth:`from_toml`).
    """

    inputs: InputsConfig = field(default_factory=InputsConfig)
    arcs: ArcOptions = field(default_factory=ArcOptions)
    cutoff: CutoffOptions = field(default_factory=CutoffOptions)
    filter: HighPass = field(default_factory=HighPass)
    screening: ScreeningOptions = field(default_factory=ScreeningOptions)
    mapping: MappingOptions = field(default_factory=MappingOptions)
    stationarity: StationarityOptions = field(default_factory=StationarityOptions)
    spectra: SpectraOptions = field(default_factory=SpectraOptions)
    bound: BoundOptions = field(default_factory=BoundOptions)
    validation: ValidationOptions = field(default_factory=ValidationOptions)
    verdict: VerdictOptions = field(default_factory=VerdictOptions)
    code_multipath: CodeMultipathOptions = field(default_factory=CodeMultipathOptions)
    output: OutputConfig = field(default_factory=OutputConfig)

    def __post_init__(self) -> None:
        for name, cls in _SECTIONS.items():
            if not isinstance(getattr(self, name), cls):
                raise InputError(
                    f"FitConfig.{name} must be a {cls.__name__}, got {type(getattr(self, name))}"
                )
        normal = {}
        for name, spec in _CUTOFF_SPECS.items():
            if hasattr(self.cutoff, name):
                try:
                    value = spec(name, getattr(self.cutoff, name))
                except OptionError as exc:
                    raise _relabel(exc, "cutoff", None) from None
                if value is not getattr(self.cutoff, name):
                    normal[name] = value  # e.g. an integer given for a float
        if normal:
            object.__setattr__(self, "cutoff", replace(self.cutoff, **normal))

    def to_dict(self) -> dict[str, Any]:
        """Return the configuration as plain data (for result files)."""
        return asdict(self)

    def updated(self, section: str, **values: Any) -> FitConfig:
        """Return a copy with some options of one section changed (None = unchanged).

        Raises
        ------
        InputError
            An unknown section or option name.
        OptionError
            A value outside the option's schema (named ``[section] name``).
        """
        values = {k: v for k, v in values.items() if v is not None}
        if not values:
            return self
        return _with(self, section, _build(section, values, self._section(section)), None)

    @classmethod
    def from_dict(cls, data: dict[str, Any], *, source: str = "configuration") -> FitConfig:
        """Build from nested dicts; unknown sections or names and bad values raise InputError."""
        out = cls()
        for section, values in data.items():
            if section not in _SECTIONS:
                raise InputError(
                    f"{source}: unknown section [{section}]; expected one of {', '.join(_SECTIONS)}"
                )
            if not isinstance(values, dict):
                raise InputError(f"{source}: [{section}] must be a table of options")
            built = _build(section, values, getattr(out, section), source)
            out = _with(out, section, built, source)
        return out

    @classmethod
    def from_toml(cls, path: str | Path) -> FitConfig:
        """Read a TOML configuration file (values are checked; see the module docstring)."""
        return cls.from_dict(read_toml(path, what="configuration file"), source=str(path))

    def check(self, label: Label = default_label) -> FitConfig:
        """Check the rules between options; return ``self``.

        Parameters
        ----------
        label : callable, optional
            ``label(section, name)`` names an option in messages (default
            ``[section] name``; the command line passes its flags).

        Returns
        -------
        FitConfig
            ``self``, unchanged.

        Raises
        ------
        InputError
            Conflicting options, options the chosen method would ignore, extra
            observation files, a missing navigation file, estimator options
            of another estimator.
        """
        for rule in _RULES:
            rule(self, label)
        return self

    def _section(self, section: str) -> Any:
        if section not in _SECTIONS:
            raise InputError(f"unknown section {section!r}; expected one of {', '.join(_SECTIONS)}")
        return getattr(self, section)


def _with(cfg: FitConfig, section: str, value: Any, source: str | None) -> FitConfig:
    try:
        return replace(cfg, **{section: value})
    except OptionError as exc:
        path = None if source in (None, "option", "configuration") else source
        raise _relabel(exc, section, path) from None


def _build(section: str, values: dict[str, Any], base: Any, source: str = "option") -> Any:
    cls = _SECTIONS[section]
    names = {f.name for f in fields(cls)}
    for k in values:
        if k not in names:
            raise InputError(
                f"{source}: unknown option {section}.{k}; expected one of {', '.join(names)}"
            )
    path = None if source in ("option", "configuration") else source
    try:
        return replace(base, **values)
    except OptionError as exc:
        raise _relabel(exc, section, path) from None
    except (TypeError, ValueError) as exc:  # a section class without a schema
        bad = ", ".join(f"{k} = {show_value(v)}" for k, v in values.items())
        raise InputError(f"[{section}] {bad}: {exc}", path=path) from None


# ----------------------------------------------------------------- rules between options


def _show(label: str, value: Any) -> str:
    """``--cutoff-hz 0.001`` for a flag, ``[cutoff] f_c_hz = 0.001`` otherwise."""
    if label.startswith("-"):
        text = show_value(value)
        return f"{label} {text[1:-1] if isinstance(value, str) else text}"
    return f"{label} = {show_value(value)}"


def _changed(obj: Any) -> dict[str, Any]:
    """Return the options of a section that differ from their defaults."""
    default = type(obj)()
    return {
        f.name: getattr(obj, f.name)
        for f in fields(obj)
        if getattr(obj, f.name) != getattr(default, f.name)
    }


def _method(cfg: FitConfig) -> str:
    """Return the isolation method the inputs lead to (``demo``, ``df``, ``da`` or ``auto``).

    With ``method = "auto"`` and several files the method depends on how many
    antennas the files hold (consecutive files of one station are merged,
    two stations make a dual-antenna pair), known only once they are read:
    ``"auto"`` then, and the method-specific checks wait for the data.
    """
    n = _n_files(cfg.inputs)
    if n == 0:
        return "demo"
    if cfg.inputs.pair:
        return "da"
    if cfg.inputs.method == "auto":
        return "df" if n == 1 else "auto"
    return cfg.inputs.method


def _n_files(inp: InputsConfig) -> int:
    """Observation files given: the list plus ``pair`` members that are files."""
    listed = {Path(p).resolve() for p in inp.obs}
    extra = {Path(p).resolve() for p in inp.pair if Path(p).is_file()} - listed
    return len(inp.obs) + len(extra)


def _holds_observations(path: str) -> bool:
    """Whether a file given as navigation is a RINEX observation file (by its first line)."""
    from psdbound.io.archive import file_kind

    try:
        return file_kind(path) == "obs"
    except (OSError, ValueError, EOFError):
        return False  # a missing or unreadable file: its reader names the problem


def _rule_demo_inputs(inp: InputsConfig, label: Label) -> None:
    """No observation file (the demo): file options are errors."""
    if inp.nav:
        observations = [n for n in inp.nav if _holds_observations(n)]
        if observations:
            raise InputError(
                f"{observations[0]} is an observation file given after "
                f"{label('inputs', 'nav')}, which takes every file after it: observation "
                "files go before --nav"
            )
        raise InputError(
            f"{_show(label('inputs', 'nav'), ' '.join(inp.nav))} given without observation "
            "files: the demo uses its own navigation file; give the observation files too"
        )
    for key in ("receiver_xyz_m", "position_a_m", "position_b_m"):
        if getattr(inp, key):
            raise InputError(
                f"{label('inputs', key)} given without observation files "
                "(the demo knows its positions)"
            )


def _rule_inputs(cfg: FitConfig, label: Label) -> None:
    inp = cfg.inputs
    n = _n_files(inp)
    lab = label("inputs", "obs")
    if inp.pair and n == 0:
        raise InputError(
            f"{_show(label('inputs', 'pair'), ' '.join(inp.pair))} names stations but no "
            f"observation file is given: give the files ({lab}) or name the files in the pair"
        )
    if inp.pair and inp.method == "df":
        raise InputError(
            f"{label('inputs', 'pair')} names a dual-antenna pair but "
            f"{_show(label('inputs', 'method'), 'df')} asks for dual-frequency: drop one"
        )
    if inp.receiver_xyz_m and (inp.position_a_m or inp.position_b_m):
        raise InputError(
            f"{label('inputs', 'receiver_xyz_m')} and {label('inputs', 'position_a_m')}/"
            f"{label('inputs', 'position_b_m')} both give antenna positions: use one form"
        )
    if inp.method == "da" and n < 2:
        raise InputError(
            f"{_show(label('inputs', 'method'), 'da')} needs the observation files of two "
            f"antennas, got {n} file(s)"
        )
    if n == 0:
        _rule_demo_inputs(inp, label)
        return
    if not inp.nav and not any(zip_members(p) for p in inp.obs):  # an archive may hold it
        raise InputError(
            f"a navigation (or SP3) file is needed for elevations with {lab}: give "
            f"{label('inputs', 'nav')}"
        )
    if len(inp.receiver_xyz_m) > n:
        raise InputError(
            f"{label('inputs', 'receiver_xyz_m')} gives {len(inp.receiver_xyz_m)} positions for "
            f"{n} observation file(s)"
        )


def _rule_method_options(cfg: FitConfig, label: Label) -> None:
    """Options one isolation method would ignore are errors with the other."""
    method = _method(cfg)
    inp = cfg.inputs
    if method == "da":
        ignored = [("inputs", "signals", inp.signals)] if inp.signals else []
        for section in ("cutoff", "filter", "validation"):
            ignored += [(section, k, v) for k, v in _changed(getattr(cfg, section)).items()]
        roti = ("roti_threshold_tecu_min", "roti_cap_tecu_min", "elevation_scaled", "ionosphere")
        ignored += [("screening", k, v) for k, v in _changed(cfg.screening).items() if k in roti]
        if ignored:
            sec, k, v = ignored[0]
            what = "the dual-frequency phase pair" if k == "signals" else "a dual-frequency option"
            raise InputError(
                f"{_show(label(sec, k), v)} is {what}, but the run is dual-antenna "
                "(a pair of antennas), which applies no high-pass filter and no ionosphere "
                "screening; remove it, or give one station's files for dual-frequency"
            )
    elif method in ("df", "demo"):
        _rule_no_da_options(cfg, label)
    if method == "df" and not inp.signals:
        from psdbound.arcs import DEFAULT_SIGNALS

        if inp.system not in DEFAULT_SIGNALS:
            system = _show(label("inputs", "system"), inp.system)
            raise InputError(
                f"no default dual-frequency signal pair for {system}; give "
                f"{label('inputs', 'signals')} (defaults exist for {', '.join(DEFAULT_SIGNALS)})"
            )


def _rule_no_da_options(cfg: FitConfig, label: Label) -> None:
    """Dual-antenna options are errors in a dual-frequency run."""
    inp, default = cfg.inputs, InputsConfig()
    if inp.da_signal != default.da_signal:
        raise InputError(
            f"{_show(label('inputs', 'da_signal'), inp.da_signal)} is a dual-antenna option but "
            "the run is dual-frequency (one observation file); use "
            f"{label('inputs', 'signals')} for the phase pair"
        )
    for key in ("position_b_m", "baseline", "baseline_tolerance_m"):
        if getattr(inp, key) != getattr(default, key):
            raise InputError(
                f"{_show(label('inputs', key), getattr(inp, key))} is a dual-antenna option but "
                "the run is dual-frequency (one station); name the pair with "
                f"{label('inputs', 'pair')} or remove it"
            )


def _rule_cutoff(cfg: FitConfig, label: Label) -> None:
    f_c = getattr(cfg.cutoff, "f_c_hz", None)
    source = getattr(cfg.cutoff, "source", "auto")
    if source == "given" and f_c is None:
        raise InputError(
            f"{_show(label('cutoff', 'source'), source)} needs {label('cutoff', 'f_c_hz')}"
        )
    if source not in ("auto", "given") and f_c is not None:
        raise InputError(
            f"{_show(label('cutoff', 'source'), source)} and "
            f"{_show(label('cutoff', 'f_c_hz'), f_c)} conflict: the {source} cutoff would "
            "replace the given one; give one or the other"
        )


def _rule_filter(cfg: FitConfig, label: Label) -> None:
    hp, changed = cfg.filter, _changed(cfg.filter)
    if hp.kind == "fir" and "order" in changed:
        raise InputError(
            f"{_show(label('filter', 'order'), hp.order)} is not used by "
            f"{_show(label('filter', 'kind'), 'fir')} (the FIR length is 4 / f_c)"
        )
    if hp.kind != "cheby2" and "stopband_db" in changed:
        raise InputError(
            f"{_show(label('filter', 'stopband_db'), hp.stopband_db)} is only used by "
            f"{_show(label('filter', 'kind'), 'cheby2')}, not {hp.kind}"
        )


def _rule_mapping(cfg: FitConfig, label: Label) -> None:
    mp = cfg.mapping
    set_ = [k for k in ("a", "b", "c_deg") if k in _changed(mp)]
    if mp.kind != "fixed" and set_:
        raise InputError(
            f"{_show(label('mapping', set_[0]), getattr(mp, set_[0]))} is only used with "
            f"{_show(label('mapping', 'kind'), 'fixed')}, but the mapping is {mp.kind!r}"
        )


def _rule_spectra(cfg: FitConfig, label: Label) -> None:
    try:
        check_estimator_options(cfg.spectra.estimator, cfg.spectra.options)
    except OptionError as exc:
        raise exc.relabel(label("spectra", exc.name)) from None
    b = cfg.bound
    if b.target != "upper" and "level" in _changed(b):
        raise InputError(
            f"{_show(label('bound', 'level'), b.level)} is only used with "
            f"{_show(label('bound', 'target'), 'upper')}"
        )
    envelope_only = [k for k in ("target", "level") if k in _changed(b)]
    if b.rule == "pooled" and envelope_only:
        raise InputError(
            f"{_show(label('bound', envelope_only[0]), getattr(b, envelope_only[0]))} is only "
            f"used with {_show(label('bound', 'rule'), 'envelope')}; the pooled rule states "
            f"its confidence with {label('bound', 'confidence_level')}"
        )
    pooled_only = [
        k
        for k in ("confidence_level", "coverage", "shape_alpha", "bands_per_decade", "tau_max_s")
        if k in _changed(b)
    ]
    if b.rule == "envelope" and pooled_only:
        raise InputError(
            f"{_show(label('bound', pooled_only[0]), getattr(b, pooled_only[0]))} is only "
            f"used with {_show(label('bound', 'rule'), 'pooled')}"
        )
    if b.rule == "pooled" and cfg.stationarity.windows != "disjoint":
        raise InputError(
            f"{_show(label('bound', 'rule'), 'pooled')} needs "
            f"{_show(label('stationarity', 'windows'), 'disjoint')} (overlapping windows' "
            f"spectra are not independent); use {_show(label('bound', 'rule'), 'envelope')} "
            "with the slide rule"
        )


def _rule_windows(cfg: FitConfig, label: Label) -> None:
    """Refuse the slide rule's coefficients for disjoint windows (they are not used)."""
    st = cfg.stationarity
    slide_only = [k for k in ("p_slide", "p_trim") if k in _changed(st)]
    if st.windows == "disjoint" and slide_only:
        raise InputError(
            f"{_show(label('stationarity', slide_only[0]), getattr(st, slide_only[0]))} is only "
            f"used with {_show(label('stationarity', 'windows'), 'slide')} (the thesis's "
            "overlapping windows); disjoint windows start where the last one ended"
        )


_RULES = (
    _rule_inputs,
    _rule_method_options,
    _rule_cutoff,
    _rule_filter,
    _rule_mapping,
    _rule_spectra,
    _rule_windows,
)
