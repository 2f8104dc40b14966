"""Configuration of a ``fit`` run: every option, settable from TOML or the CLI.

A :class:`FitConfig` composes the small frozen options dataclasses that live
next to their stages (:class:`~psdbound.io.ArcOptions`,
:class:`~psdbound.ionosphere.CutoffOptions`,
:class:`~psdbound.isolation.HighPass`,
:class:`~psdbound.stationarity.MappingOptions`,
:class:`~psdbound.stationarity.StationarityOptions`,
:class:`~psdbound.spectra.SpectraOptions`,
:class:`~psdbound.spectra.BoundOptions`,
:class:`~psdbound.screening.ScreeningOptions`,
:class:`~psdbound.validation.ValidationOptions`,
:class:`~psdbound.pipeline.verdict.VerdictOptions`); the inputs and output
sections are defined here.
``FitConfig.from_toml(path)`` reads the same names (sections ``[inputs]``,
``[arcs]``, ``[cutoff]``, ``[filter]``, ``[screening]``, ``[mapping]``, ``[stationarity]``,
``[spectra]``, ``[bound]``, ``[validation]``, ``[verdict]``, ``[output]``); unknown names
are errors. The effective configuration is saved with every result.
"""

from __future__ import annotations

import tomllib
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from psdbound.errors import InputError
from psdbound.io.options import ArcOptions
from psdbound.ionosphere.policy import CutoffOptions
from psdbound.isolation import HighPass
from psdbound.pipeline.verdict import VerdictOptions
from psdbound.screening import ScreeningOptions
from psdbound.spectra.options import BoundOptions, SpectraOptions
from psdbound.stationarity.options import MappingOptions, StationarityOptions
from psdbound.validation.options import ValidationOptions

__all__ = [
    "FitConfig",
    "InputsConfig",
    "OutputConfig",
]


@dataclass(frozen=True)
class InputsConfig:
    """Input files and what to take from them.

    ``obs``: one file (dual-frequency) or two (dual-antenna); empty runs the
    demo. ``method``: ``auto`` (DF for one file, DA for two), ``df`` or
    ``da``. ``signals``: DF phase pair (default per system, GPS L1C-L2W);
    ``da_signal``: DA phase code. ``receiver_xyz_m``: ECEF position(s),
    else the header's.
    """

    obs: tuple[str, ...] = ()
    nav: str | None = None
    method: str = "auto"
    system: str = "G"
    signals: tuple[str, ...] = ()
    da_signal: str = "L1C"
    receiver_xyz_m: tuple[tuple[float, float, float], ...] = ()


@dataclass(frozen=True)
class OutputConfig:
    """Outputs: folder (default ``reports/<name>``), run name, PDF on/off."""

    out: str | None = None
    name: str | None = None
    pdf: bool = True


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
    "output": OutputConfig,
}


@dataclass(frozen=True)
class FitConfig:
    """Every option of a ``fit`` run, by stage (see the module docstring)."""

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
    output: OutputConfig = field(default_factory=OutputConfig)

    def to_dict(self) -> dict[str, Any]:
        """Return the configuration as plain data (for result files)."""
        return asdict(self)

    def updated(self, section: str, **values: Any) -> FitConfig:
        """Return a copy with some options of one section changed (None = unchanged)."""
        values = {k: v for k, v in values.items() if v is not None}
        if not values:
            return self
        return replace(self, **{section: _build(section, values, getattr(self, section))})

    @classmethod
    def from_dict(cls, data: dict[str, Any], *, source: str = "configuration") -> FitConfig:
        """Build from nested dicts; unknown sections or names raise InputError."""
        out = cls()
        for section, values in data.items():
            if section not in _SECTIONS:
                raise InputError(
                    f"{source}: unknown section [{section}]; expected one of {', '.join(_SECTIONS)}"
                )
            if not isinstance(values, dict):
                raise InputError(f"{source}: [{section}] must be a table of options")
            out = replace(out, **{section: _build(section, values, getattr(out, section), source)})
        return out

    @classmethod
    def from_toml(cls, path: str | Path) -> FitConfig:
        """Read a TOML configuration file."""
        p = Path(path)
        if not p.is_file():
            raise InputError("configuration file not found", path=p)
        try:
            data = tomllib.loads(p.read_text())
        except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
            raise InputError(f"not valid TOML: {exc}", path=p) from None
        return cls.from_dict(data, source=str(p))


def _build(section: str, values: dict[str, Any], base: Any, source: str = "option") -> Any:
    cls = _SECTIONS[section]
    names = {f.name: f for f in fields(cls)}
    for k in values:
        if k not in names:
            raise InputError(
                f"{source}: unknown option {section}.{k}; expected one of {', '.join(names)}"
            )
    clean = {}
    for k, v in values.items():
        default = getattr(base, k)
        if isinstance(default, tuple) and isinstance(v, list | tuple):
            v = tuple(tuple(x) if isinstance(x, list) else x for x in v)
        elif isinstance(default, float) and isinstance(v, int) and not isinstance(v, bool):
            v = float(v)
        clean[k] = v
    return replace(base, **clean)
