"""The products of the fit stages: small frozen dataclasses that pickle.

Each carries what its stage computed and the warnings it raised; a campaign
ships them between Dask workers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from psdbound.arcs import ArcSet
from psdbound.io import Observations
from psdbound.isolation import MultipathSeries
from psdbound.screening import Screening
from psdbound.stationarity import ElevationMapping, WindowSet

__all__ = ["CodeOverbound", "InputData", "Isolated", "Screened", "Validated", "Windowed"]


@dataclass(frozen=True)
class InputData:
    """What :func:`read_inputs` read.

    Attributes
    ----------
    method : {"df", "da"}
        Isolation method.
    observations : tuple of Observations
        One (DF) or two (DA) observation files, read.
    orbit : object
        Broadcast ephemerides or precise orbits.
    files : tuple of dict
        Every input file: role, name, path, SHA-256.
    receiver_xyz_m : tuple
        Per observation file, an ECEF position (m) or None (header position).
    lat_deg, lon_deg : float or None
        Geodetic position of the (first) receiver, degrees.
    year : int
        Year of the first epoch.
    demo : dict or None
        The demo's truth metadata when the embedded demo was used.
    warnings : tuple of str
        What the readers skipped or corrected (e.g. a duplicated epoch).
    """

    method: str
    observations: tuple[Observations, ...]
    orbit: Any
    files: tuple[dict[str, str], ...]
    receiver_xyz_m: tuple[tuple[float, float, float] | None, ...]
    lat_deg: float | None
    lon_deg: float | None
    year: int
    demo: dict[str, Any] | None = None
    warnings: tuple[str, ...] = ()

    @property
    def interval_s(self) -> float:
        """Sampling interval of the first observation file, s."""
        return self.observations[0].interval_s

    @property
    def t_ref_gps_s(self) -> float:
        """First epoch, GPS seconds."""
        return float(self.observations[0].t_gps_s[0])


@dataclass(frozen=True)
class Isolated:
    """The isolated multipath series and how it was obtained.

    Attributes
    ----------
    series : MultipathSeries
        Multipath per arc, metres.
    arcs : ArcSet or None
        The tracking arcs (dual-frequency only).
    details : dict
        Isolation details for the result document (signals, scaling,
        filter, arc breaks, filter safety check, DA baseline...).
    warnings : tuple of str
    """

    series: MultipathSeries
    arcs: ArcSet | None
    details: dict[str, Any]
    warnings: tuple[str, ...] = ()


@dataclass(frozen=True)
class Screened:
    """The isolated series after screening, and what was excluded.

    Attributes
    ----------
    screening : Screening
        Kept series, excluded spans with reasons, the plausibility limit.
    mapping : ElevationMapping or None
        The provisional elevation mapping the screening scaled its fixed
        threshold with (fitted on the series before screening; the bound's
        mapping is fitted again on what the screening kept, see
        :class:`Windowed`).
    warnings : tuple of str
    """

    screening: Screening
    mapping: ElevationMapping | None = None
    warnings: tuple[str, ...] = ()

    @property
    def series(self) -> MultipathSeries:
        """The kept multipath series."""
        return self.screening.series


@dataclass(frozen=True)
class Windowed:
    """Stationary windows of the elevation-mapped series.

    Attributes
    ----------
    mapping : ElevationMapping
    windows : WindowSet
    warnings : tuple of str
    """

    mapping: ElevationMapping
    windows: WindowSet
    warnings: tuple[str, ...] = ()


@dataclass(frozen=True)
class Validated:
    """The cutoff validation (None-valued report when not applicable).

    Attributes
    ----------
    report : ValidationReport or None
        The Jacobi-Anger/direct check (None for dual-antenna).
    summary : dict
        Verdict and fractions for the result document.
    warnings : tuple of str
    """

    report: Any
    summary: dict[str, Any]
    warnings: tuple[str, ...] = ()


@dataclass(frozen=True)
class CodeOverbound:
    """Code multipath by carrier levelling and its Gaussian overbound (optional stage).

    Attributes
    ----------
    series : MultipathSeries or None
        Code multipath per arc, metres (None when no arc was long enough).
    overbound : OverboundResult or None
        Per-elevation-bin overbound (None when no bin held enough samples).
    details : dict
        The ``code_multipath`` section of the result document.
    warnings : tuple of str
    """

    series: MultipathSeries | None
    overbound: Any
    details: dict[str, Any]
    warnings: tuple[str, ...] = ()
