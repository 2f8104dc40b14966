"""Settings of a cutoff run, built and checked in one place.

:class:`CutoffSettings` holds every setting besides station, dates and orbit
source. It is built from keyword arguments, or from a mapping of setting
names (a parsed command line, a cached task) by
:meth:`CutoffSettings.from_mapping`, and hands each stage its options:
:meth:`~CutoffSettings.simulation_options` to
:func:`~psdbound.ionosphere.slant.simulate_slant_delay`,
:meth:`~CutoffSettings.series_options` to
:func:`~psdbound.ionosphere.cutoff.series_cutoff` (the periodogram
criteria), :meth:`~CutoffSettings.residual_options` to
:func:`~psdbound.ionosphere.residual.residual_cutoffs` (the default
time-domain criterion).

Defaults (issue #16): the ``"residual"`` criterion on the L1-L2 difference
the fit filters, sampled at 30 s (the usual RINEX rate), rays every 2 min,
an 11 x 11 horizontal grid, 1 h UT nodes and the coarse altitude nodes, at
a fifth of the cost of 12 s sampling, 1 min rays, 21 x 21 nodes, 30 min
and fine altitudes. On Chicago 2020 they move the station's mean cutoff by
1 % and its maximum by -12 % (docs/method/cutoff.rst gives the table; the maximum
of ~300 series is the statistic most sensitive to the interpolation). :meth:`CutoffSettings.legacy`
gives the issue-#4 defaults (40 dB Lomb-Scargle criterion at L1, 12 s).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from psdbound.common.options import Choice, Number, option
from psdbound.errors import InputError
from psdbound.ionosphere.names import (
    ALT_RESOLUTIONS,
    CRITERIA,
    DEFAULT_DROP_DB,
    DEFAULT_F107_SFU,
    DEFAULT_MARGIN_DB,
    DEFAULT_MP_SIGMA_M,
    DEFAULT_SHELL_HEIGHT_KM,
    DEFAULT_VARIANCE_M2,
    F_MIN_HZ,
    FREQUENCIES_HZ,
    IRI_MODELS,
    METHODS,
    MIN_ARC_S,
    MIN_KEPT_S,
    MIN_SERIES_SAMPLES,
    NOMINAL_SYSTEMS,
    REFERENCES,
)

if TYPE_CHECKING:
    from psdbound.isolation import HighPass

__all__ = ["ALL_CRITERIA", "LEVELS_DB", "SETTING_OPTIONS", "CutoffSettings", "parse_carriers"]

#: Every cutoff criterion: the time-domain residual (default) and the periodogram ones.
ALL_CRITERIA = ("residual", *CRITERIA)
#: Margins (dB below the reference multipath) whose cutoffs every residual run also records.
LEVELS_DB = (20.0, 30.0, 40.0, 50.0)

# settings handed to simulate_slant_delay under the same name
_SIMULATION = (
    "f107_sfu",
    "elevation_mask_deg",
    "method",
    "frequency_hz",
    "second_frequency_hz",
    "sampling_s",
    "iri_model",
    "alt_range_km",
    "alt_resolution",
    "shell_height_km",
    "grid_size",
    "ut_step_h",
    "ray_stride",
)
# settings handed to series_cutoff under the same name (plus sampling_s as dt_s)
_SERIES = (
    "copies",
    "oversample",
    "nyquist_fraction",
    "criterion",
    "drop_db",
    "reference",
    "variance_m2",
    "degree",
    "quantile",
    "envelope_method",
    "bins_per_decade",
)


def parse_carriers(text: str) -> tuple[float, float | None]:
    """Parse a carrier frequency, or a pair of carriers, from text.

    Parameters
    ----------
    text : str
        A name of :data:`~psdbound.ionosphere.slant.FREQUENCIES_HZ` (``L1``,
        ``L2``, ``L5``, ``E1``, ``E5a``, ``E5b``), a value in MHz, or two of
        them joined by ``-`` (``L1-L2``) for the dual-frequency difference.

    Returns
    -------
    frequency_hz : float
        First carrier, Hz.
    second_frequency_hz : float or None
        Second carrier, Hz, for a pair.

    Raises
    ------
    InputError
        For an unknown name, a value outside 100-10000 MHz, or a pair of
        equal frequencies.
    """

    def one(tok: str) -> float:
        tok = tok.strip()
        if tok in FREQUENCIES_HZ:
            return FREQUENCIES_HZ[tok]
        try:
            mhz = float(tok)
        except ValueError:
            raise InputError(
                f"unknown carrier {tok!r}: use {', '.join(FREQUENCIES_HZ)} or a value in MHz"
            ) from None
        if not 100.0 <= mhz <= 10000.0:
            raise InputError(f"carrier frequency {mhz} MHz is outside 100-10000 MHz")
        return mhz * 1e6

    parts = text.split("-") if text.count("-") == 1 and not text.startswith("-") else [text]
    if len(parts) == 2:
        f1, f2 = one(parts[0]), one(parts[1])
        if f1 == f2:
            raise InputError(f"the two carriers of {text!r} are the same frequency")
        return f1, f2
    return one(parts[0]), None


@dataclass(frozen=True)
class CutoffSettings:
    """Every setting of a cutoff run besides station, dates and orbit source.

    Simulation: ``f107_sfu``, ``elevation_mask_deg``, ``method``,
    ``iri_model``, ``frequency_hz``, ``second_frequency_hz``, ``sampling_s``,
    ``alt_range_km``, ``alt_resolution``, ``shell_height_km``, ``grid_size``,
    ``ut_step_h``, ``ray_stride`` (see
    :func:`~psdbound.ionosphere.slant.simulate_slant_delay`). Criterion:
    ``criterion`` (``"residual"``, default, or the periodogram criteria
    ``"relative"`` and ``"absolute"``). Residual criterion
    (:mod:`~psdbound.ionosphere.residual`): ``mp_sigma_m`` (reference
    multipath sigma per carrier, m), ``margin_db`` (how far below it the
    residual must stay), ``filter_kind``, ``filter_order``, ``filter_edge``
    (the fit's :class:`~psdbound.isolation.HighPass`), ``min_kept_s``,
    ``search_top_fraction`` (top of the search, fraction of Nyquist),
    ``points_per_decade``. Periodogram criteria: ``copies``,
    ``oversample``, ``nyquist_fraction``, ``drop_db``, ``reference``,
    ``variance_m2``, ``degree``, ``quantile``, ``envelope_method``,
    ``bins_per_decade`` (see :func:`~psdbound.ionosphere.cutoff.series_cutoff`).
    ``systems`` picks the nominal constellation when no orbit file is given
    (``"E"`` alone also makes E1/E5a the default carriers);
    ``min_arc_s`` drops shorter arcs from each one-day series and
    ``min_samples`` is the shortest one-day series analysed (shorter ones are
    listed as skipped); see :func:`~psdbound.ionosphere.cutoff.one_day_series`.
    """

    f107_sfu: float = option(DEFAULT_F107_SFU, Number(lo=50.0, hi=400.0, unit="sfu"))
    elevation_mask_deg: float = option(10.0, Number(lo=0.0, hi=90.0, hi_open=True, unit="deg"))
    method: str = option("line-of-sight", Choice(METHODS, noun="method"))
    iri_model: str = option("ursi", Choice(IRI_MODELS, noun="IRI model"))
    frequency_hz: float = FREQUENCIES_HZ["L1"]
    second_frequency_hz: float | None = FREQUENCIES_HZ["L2"]
    sampling_s: float = option(30.0, Number(lo=0.0, lo_open=True, unit="s"))
    alt_range_km: tuple[float, float] = (60.0, 2000.0)
    alt_resolution: str = option("coarse", Choice(ALT_RESOLUTIONS, noun="altitude resolution"))
    shell_height_km: float = DEFAULT_SHELL_HEIGHT_KM
    grid_size: int = 11
    ut_step_h: float = 1.0
    ray_stride: int = 4
    systems: str = "G"
    criterion: str = option("residual", Choice(ALL_CRITERIA, noun="criterion"))
    mp_sigma_m: float = option(DEFAULT_MP_SIGMA_M, Number(lo=0.0, lo_open=True, unit="m"))
    margin_db: float = option(DEFAULT_MARGIN_DB, Number(lo=0.0, unit="dB"))
    filter_kind: str = "butter"
    filter_order: int = 4
    filter_edge: str = option("trim", Choice(("trim", "pad"), noun="edge handling"))
    min_kept_s: float = MIN_KEPT_S
    search_top_fraction: float = option(0.5, Number(lo=0.0, lo_open=True, hi=1.0))
    points_per_decade: int = 16
    copies: int = option(7, Number(lo=1, integer=True))
    oversample: float = 1.0
    nyquist_fraction: float = 0.99
    drop_db: float = option(DEFAULT_DROP_DB, Number(lo=0.0, lo_open=True, unit="dB"))
    reference: str = option("psd", Choice(REFERENCES, noun="reference"))
    variance_m2: float = option(DEFAULT_VARIANCE_M2, Number(lo=0.0, lo_open=True, unit="m^2"))
    degree: int = option(3, Number(lo=0, integer=True))
    quantile: float = option(0.99, Number(lo=0.5, hi=1.0))
    envelope_method: str = "quantreg"
    bins_per_decade: float = 20.0
    min_samples: int = 60
    min_arc_s: float = option(MIN_ARC_S, Number(lo=0.0, unit="s"))

    @classmethod
    def legacy(cls, **changes: Any) -> CutoffSettings:
        """Return the issue-#4 defaults: 40 dB Lomb-Scargle criterion, L1, 12 s, fine grids.

        The benchmark times these side by side with the defaults; they also
        reproduce the periodogram numbers quoted in docs/method/cutoff.rst.

        Parameters
        ----------
        **changes
            Fields to change from those settings.

        Returns
        -------
        CutoffSettings
        """
        base = {
            "criterion": "relative",
            "second_frequency_hz": None,
            "sampling_s": 12.0,
            "alt_resolution": "fine",
            "grid_size": 21,
            "ut_step_h": 0.5,
            "ray_stride": 5,
            "min_samples": MIN_SERIES_SAMPLES,
        }
        return cls(**{**base, **changes})

    @classmethod
    def from_mapping(cls, options: Mapping[str, Any]) -> CutoffSettings:
        """Build settings from a mapping of names to values; absent names keep their defaults.

        Parameters
        ----------
        options : mapping
            Field names (see the class notes) to values; None means "not
            given". ``carrier`` (text, see :func:`parse_carriers`) sets
            ``frequency_hz`` and ``second_frequency_hz``; ``systems`` is
            upper-cased; ``alt_range_km`` may be a list. Every name must be
            one of :data:`SETTING_OPTIONS`.

        Returns
        -------
        CutoffSettings
            Checked by :meth:`validate`.

        Raises
        ------
        InputError
            For an unknown name, carrier or setting value.
        """
        given = {k: v for k, v in options.items() if v is not None}
        unknown = sorted(set(given) - set(SETTING_OPTIONS))
        if unknown:
            raise InputError(f"unknown cutoff setting(s) {', '.join(unknown)}")
        carrier = given.pop("carrier", None)
        if carrier is not None:
            given["frequency_hz"], given["second_frequency_hz"] = parse_carriers(str(carrier))
        if "systems" in given:
            given["systems"] = str(given["systems"]).upper()
        if given.get("systems") == "E" and carrier is None and "frequency_hz" not in given:
            # Galileo alone: its own default pair, E1/E5a (not GPS L2, which it has not)
            given["frequency_hz"] = FREQUENCIES_HZ["E1"]
            given["second_frequency_hz"] = FREQUENCIES_HZ["E5a"]
        if "alt_range_km" in given:
            lo, hi = given["alt_range_km"]
            given["alt_range_km"] = (float(lo), float(hi))
        settings = cls(**given)
        settings.validate()
        return settings

    def validate(self) -> None:
        """Raise :class:`InputError` for an unknown choice or an out-of-range number.

        The ranges and choices are the fields' schema (:func:`~psdbound.common.options.option`,
        which the ``cutoff`` command's options are read with, naming the flag); here they keep
        the messages the library has always given.
        """
        from psdbound.isolation.filters import FILTER_KINDS

        checks = [
            (self.method in METHODS, f"method {self.method!r} not in {METHODS}"),
            (self.iri_model in IRI_MODELS, f"iri_model {self.iri_model!r} not in {IRI_MODELS}"),
            (
                self.alt_resolution in ALT_RESOLUTIONS,
                f"alt_resolution {self.alt_resolution!r} not in {ALT_RESOLUTIONS}",
            ),
            (
                self.criterion in ALL_CRITERIA,
                f"criterion {self.criterion!r} not in {ALL_CRITERIA}",
            ),
            (self.mp_sigma_m > 0, f"mp_sigma_m = {self.mp_sigma_m} m must be positive"),
            (self.margin_db >= 0, f"margin_db = {self.margin_db} dB must be non-negative"),
            (
                self.filter_kind in FILTER_KINDS,
                f"filter_kind {self.filter_kind!r} not in {FILTER_KINDS}",
            ),
            (
                0.0 < self.search_top_fraction <= 1.0,
                f"search_top_fraction = {self.search_top_fraction} must be in (0, 1]",
            ),
            (self.points_per_decade >= 2, "points_per_decade must be at least 2"),
            (self.sampling_s > 0, f"sampling_s = {self.sampling_s} s must be positive"),
            (self.reference in REFERENCES, f"reference {self.reference!r} not in {REFERENCES}"),
            (
                50.0 <= self.f107_sfu <= 400.0,
                f"F10.7 = {self.f107_sfu} sfu is outside the plausible range 50-400 sfu",
            ),
            (
                0.0 <= self.elevation_mask_deg < 90.0,
                f"elevation mask {self.elevation_mask_deg} deg is out of range: expected "
                "0 <= mask < 90",
            ),
            (self.copies >= 1, f"copies = {self.copies} must be at least 1"),
            (self.filter_edge in ("trim", "pad"), f"filter_edge {self.filter_edge!r} not trim/pad"),
            (self.drop_db > 0, f"drop_db = {self.drop_db} must be positive"),
            (self.variance_m2 > 0, f"variance_m2 = {self.variance_m2} must be positive"),
            (
                set(self.systems) <= set(NOMINAL_SYSTEMS) and self.systems,
                f"systems {self.systems!r}: expected one or more of {', '.join(NOMINAL_SYSTEMS)}",
            ),
            (self.degree >= 0, f"envelope degree {self.degree} must be non-negative"),
            (0.5 <= self.quantile <= 1.0, f"quantile {self.quantile} must be in [0.5, 1]"),
            (self.min_arc_s >= 0, f"min_arc_s = {self.min_arc_s} must be non-negative"),
        ]
        for ok, message in checks:
            if not ok:
                raise InputError(message)

    def simulation_options(self) -> dict[str, Any]:
        """Return the keyword options of :func:`simulate_slant_delay` for these settings."""
        return {name: getattr(self, name) for name in _SIMULATION}

    def series_options(self) -> dict[str, Any]:
        """Return the keyword options of :func:`series_cutoff` for these settings."""
        opts = {name: getattr(self, name) for name in _SERIES}
        if self.criterion not in CRITERIA:
            opts["criterion"] = "relative"
        return {"dt_s": self.sampling_s, **opts}

    def highpass(self) -> HighPass:
        """Return the fit's high-pass filter these settings describe."""
        from psdbound.isolation import HighPass

        return HighPass(kind=self.filter_kind, order=self.filter_order, edge=self.filter_edge)

    @property
    def residual_scale(self) -> float:
        """Factor from the simulated delay to the fit's series.

        :data:`psdbound.isolation.DF_SCALING` (1/sqrt(2)) for a carrier pair
        (the fit's per-carrier scaling of the DF difference); 1 for one
        carrier (conservative by 6.8 dB at L1 for an L1-L2 fit).
        """
        from psdbound.isolation import DF_SCALING

        return float(DF_SCALING) if self.second_frequency_hz is not None else 1.0

    def margins_db(self) -> list[float]:
        """Return the margins a residual run records: ``margin_db``, then :data:`LEVELS_DB`."""
        return [self.margin_db, *(m for m in LEVELS_DB if m != self.margin_db)]

    def thresholds_m(self) -> list[float]:
        """Return the allowed residuals of :meth:`margins_db`, m."""
        from psdbound.ionosphere.residual import residual_threshold_m

        return [residual_threshold_m(self.mp_sigma_m, m) for m in self.margins_db()]

    def residual_options(self) -> dict[str, Any]:
        """Return the keyword options of :func:`residual_cutoffs` for these settings."""
        return {
            "dt_s": self.sampling_s,
            "thresholds_m": self.thresholds_m(),
            "scale": self.residual_scale,
            "highpass": self.highpass(),
            "min_kept_s": self.min_kept_s,
            "nyquist_fraction": self.search_top_fraction,
            "f_min_hz": F_MIN_HZ,
            "points_per_decade": self.points_per_decade,
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dict of the settings."""
        d = dataclasses.asdict(self)
        d["alt_range_km"] = list(self.alt_range_km)
        return d


#: Names :meth:`CutoffSettings.from_mapping` accepts: every field, and ``carrier``.
SETTING_OPTIONS: tuple[str, ...] = (
    *(f.name for f in dataclasses.fields(CutoffSettings)),
    "carrier",
)
