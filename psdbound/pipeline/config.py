"""Configuration of a ``fit`` run: every option, settable from TOML or the CLI.

A :class:`FitConfig` is a tree of small frozen dataclasses, one per stage.
``FitConfig.from_toml(path)`` reads the same names (sections ``[inputs]``,
``[arcs]``, ``[cutoff]``, ``[filter]``, ``[mapping]``, ``[stationarity]``,
``[spectra]``, ``[bound]``, ``[validation]``, ``[output]``); unknown names
are errors. The effective configuration is saved with every result.
"""

from __future__ import annotations

import tomllib
from dataclasses import asdict, dataclass, field, fields, replace
from pathlib import Path
from typing import Any

from psdbound.errors import InputError

__all__ = [
    "FitConfig",
    "InputsConfig",
    "ArcsConfig",
    "CutoffConfig",
    "FilterConfig",
    "MappingConfig",
    "StationarityConfig",
    "SpectraConfig",
    "BoundConfig",
    "ValidationConfig",
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
class ArcsConfig:
    """Arc building: minimum length (s), elevation mask (deg), slip threshold (m)."""

    min_length_s: float = 1800.0
    elevation_mask_deg: float = 10.0
    slip_threshold_m: float = 0.04


@dataclass(frozen=True)
class CutoffConfig:
    """Ionosphere high-pass cutoff.

    ``source``: ``auto`` (``given`` if ``f_c_hz`` is set, else the thesis's
    Chicago 2020 value 9.55e-4 Hz with a warning that also quotes the map),
    ``given``, ``map`` (nearest of the 20 stations of the shipped 2020 map)
    or ``computed`` (PyIRI at the receiver for the data's year, ~20 s).
    """

    f_c_hz: float | None = None
    source: str = "auto"


@dataclass(frozen=True)
class FilterConfig:
    """High-pass filter: kind (butter, cheby2, fir), IIR order, edge (trim, pad)."""

    kind: str = "butter"
    order: int = 4
    edge: str = "trim"


@dataclass(frozen=True)
class MappingConfig:
    """Elevation mapping: ``thesis`` (1, 29, 10 deg), ``fit``, or ``fixed`` with a, b, c."""

    kind: str = "thesis"
    a: float = 1.0
    b: float = 29.0
    c_deg: float = 10.0


@dataclass(frozen=True)
class StationarityConfig:
    """Windowing: significance level, slide/trim coefficients, minimum window (s)."""

    alpha: float = 0.05
    p_slide: float = 1.2
    p_trim: float = 0.8
    min_window_s: float = 600.0
    levene_center: str = "mean"


@dataclass(frozen=True)
class SpectraConfig:
    """PSD estimator (multitaper, welch, blackman-tukey) and its options."""

    estimator: str = "multitaper"
    options: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class BoundConfig:
    """Bound fit: objective (variance, area), target (point, upper), confidence level."""

    objective: str = "variance"
    target: str = "point"
    level: float = 0.95


@dataclass(frozen=True)
class ValidationConfig:
    """Cutoff validation: reflection geometries, amplitude ratio alpha, threshold."""

    geometries: tuple[str, ...] = ("wall:d=25", "ground:h=1.5")
    alpha: float = 0.1
    threshold: float = 0.10
    rate: str = "orbit"


@dataclass(frozen=True)
class OutputConfig:
    """Outputs: folder (default ``reports/<name>``), run name, PDF on/off."""

    out: str | None = None
    name: str | None = None
    pdf: bool = True


_SECTIONS = {
    "inputs": InputsConfig,
    "arcs": ArcsConfig,
    "cutoff": CutoffConfig,
    "filter": FilterConfig,
    "mapping": MappingConfig,
    "stationarity": StationarityConfig,
    "spectra": SpectraConfig,
    "bound": BoundConfig,
    "validation": ValidationConfig,
    "output": OutputConfig,
}


@dataclass(frozen=True)
class FitConfig:
    """Every option of a ``fit`` run, by stage (see the module docstring)."""

    inputs: InputsConfig = field(default_factory=InputsConfig)
    arcs: ArcsConfig = field(default_factory=ArcsConfig)
    cutoff: CutoffConfig = field(default_factory=CutoffConfig)
    filter: FilterConfig = field(default_factory=FilterConfig)
    mapping: MappingConfig = field(default_factory=MappingConfig)
    stationarity: StationarityConfig = field(default_factory=StationarityConfig)
    spectra: SpectraConfig = field(default_factory=SpectraConfig)
    bound: BoundConfig = field(default_factory=BoundConfig)
    validation: ValidationConfig = field(default_factory=ValidationConfig)
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
