"""Ionosphere high-pass cutoff selection (docs/method/cutoff.rst).

Pipeline: satellite geometry (navigation, SP3, YUMA almanac, or a nominal
constellation) -> slant ionospheric delay from PyIRI electron density (the
L1-L2 difference every 30 s by default) -> one-day series per satellite ->
cutoff by the time-domain **residual** criterion (default, issue #16: the
lowest f_c above which the fit's own high-pass leaves the ionosphere 40 dB
below a 1 mm multipath reference) or by the thesis's periodogram criteria
(7-sidereal-day replication, Lomb-Scargle PSD, upper envelope, 40 dB
relative or absolute) -> per-station summary (recommended = max) -> the
world map (20 reference stations + a grid, solar-minimum and solar-maximum
layers) that ``fit`` uses by default.

Public surface:

* geometry: :func:`nominal_constellation` -> :class:`NominalConstellation`;
  :func:`read_yuma` / :func:`write_yuma` / :func:`almanac_from_navigation`
  -> :class:`Almanac`
* delays: :func:`simulate_slant_delay` -> :class:`SlantDelay`
  (:mod:`~psdbound.ionosphere.slant`, density from
  :mod:`~psdbound.ionosphere.iri`)
* spectrum (from :mod:`psdbound.periodogram`): :func:`lomb_scargle`,
  :func:`frequency_grid`, :func:`to_one_sided_density`
* residual criterion (:mod:`~psdbound.ionosphere.residual`):
  :func:`residual_cutoffs` / :func:`residual_cutoff` -> :class:`ResidualCutoff`,
  :func:`residual_rms`, :func:`residual_threshold_m`
* periodogram criteria: :func:`fit_envelope` -> :class:`Envelope`,
  :func:`relative_cutoff`, :func:`absolute_cutoff`, :func:`one_day_series`,
  :func:`series_cutoff` -> :class:`SeriesCutoff`
* batch: :class:`CutoffSettings` and :data:`SETTING_OPTIONS`
  (:mod:`~psdbound.ionosphere.settings`),
  :func:`station_cutoffs` -> :class:`StationCutoffs`, :func:`map_cutoffs`
  -> :class:`CutoffMap` (:mod:`~psdbound.ionosphere.results`),
  :func:`select_days`, :func:`default_cache_dir`; station-day tasks and
  their cache in :mod:`~psdbound.ionosphere.tasks` (run by
  :mod:`psdbound.compute`)
* whole runs and files: :func:`run_cutoff` -> :class:`CutoffOutcome`,
  :func:`write_cutoff_outputs` (:mod:`~psdbound.ionosphere.outputs`);
  figures in :mod:`psdbound.ionosphere.figures`
* stations: :data:`MAP_STATIONS`, :data:`CHICAGO`, :func:`nearest_station`,
  :func:`validate_station`
* world map (:mod:`~psdbound.ionosphere.worldmap`): :func:`compute_world_map`,
  :func:`load_map`, :func:`interpolate_map`, :class:`MapLayer`; solar flux of a
  date in :mod:`~psdbound.ionosphere.solar`
* cutoff policy for a fit (:mod:`~psdbound.ionosphere.policy`):
  :func:`choose_cutoff`, :class:`CutoffOptions` -> :class:`CutoffChoice`,
  :func:`cutoff_from_map`, :func:`cutoff_computed`,
  :data:`THESIS_CUTOFF_HZ`, :data:`CUTOFF_SOURCES`
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.ionosphere.almanac import Almanac, almanac_from_navigation, read_yuma, write_yuma
    from psdbound.ionosphere.batch import (
        default_cache_dir,
        map_cutoffs,
        select_days,
        station_cutoffs,
    )
    from psdbound.ionosphere.constellation import (
        NominalConstellation,
        nominal_constellation,
    )
    from psdbound.ionosphere.cutoff import (
        CRITERIA,
        SeriesCutoff,
        absolute_cutoff,
        one_day_series,
        relative_cutoff,
        series_cutoff,
    )
    from psdbound.ionosphere.envelope import Envelope, fit_envelope, local_maxima
    from psdbound.ionosphere.iri import DEFAULT_F107_SFU
    from psdbound.ionosphere.names import THESIS_CHICAGO_2020_HZ
    from psdbound.ionosphere.outputs import write_cutoff_outputs
    from psdbound.ionosphere.policy import (
        CUTOFF_SOURCES,
        THESIS_CUTOFF_HZ,
        CutoffChoice,
        CutoffOptions,
        choose_cutoff,
        cutoff_computed,
        cutoff_from_map,
    )
    from psdbound.ionosphere.residual import (
        ResidualCutoff,
        residual_cutoff,
        residual_cutoffs,
        residual_rms,
        residual_threshold_m,
    )
    from psdbound.ionosphere.results import CutoffMap, StationCutoffs
    from psdbound.ionosphere.settings import SETTING_OPTIONS, CutoffSettings
    from psdbound.ionosphere.slant import FREQUENCIES_HZ, SlantDelay, simulate_slant_delay
    from psdbound.ionosphere.stations import (
        CHICAGO,
        MAP_STATIONS,
        Station,
        nearest_station,
        validate_station,
    )
    from psdbound.ionosphere.workflow import CutoffOutcome, run_cutoff, run_world_map
    from psdbound.ionosphere.worldmap import (
        MapLayer,
        compute_world_map,
        interpolate_map,
        load_map,
    )
    from psdbound.periodogram import frequency_grid, lomb_scargle, to_one_sided_density

__all__ = [
    "CHICAGO",
    "CRITERIA",
    "CUTOFF_SOURCES",
    "DEFAULT_F107_SFU",
    "FREQUENCIES_HZ",
    "MAP_STATIONS",
    "SETTING_OPTIONS",
    "THESIS_CHICAGO_2020_HZ",
    "THESIS_CUTOFF_HZ",
    "Almanac",
    "CutoffChoice",
    "CutoffMap",
    "CutoffOptions",
    "CutoffOutcome",
    "CutoffSettings",
    "Envelope",
    "MapLayer",
    "NominalConstellation",
    "ResidualCutoff",
    "SeriesCutoff",
    "SlantDelay",
    "Station",
    "StationCutoffs",
    "absolute_cutoff",
    "almanac_from_navigation",
    "choose_cutoff",
    "compute_world_map",
    "cutoff_computed",
    "cutoff_from_map",
    "default_cache_dir",
    "fit_envelope",
    "frequency_grid",
    "interpolate_map",
    "load_map",
    "local_maxima",
    "lomb_scargle",
    "map_cutoffs",
    "nearest_station",
    "nominal_constellation",
    "one_day_series",
    "read_yuma",
    "relative_cutoff",
    "residual_cutoff",
    "residual_cutoffs",
    "residual_rms",
    "residual_threshold_m",
    "run_cutoff",
    "run_world_map",
    "select_days",
    "series_cutoff",
    "simulate_slant_delay",
    "station_cutoffs",
    "to_one_sided_density",
    "validate_station",
    "write_cutoff_outputs",
    "write_yuma",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "Almanac": ("psdbound.ionosphere.almanac", "Almanac"),
    "almanac_from_navigation": ("psdbound.ionosphere.almanac", "almanac_from_navigation"),
    "read_yuma": ("psdbound.ionosphere.almanac", "read_yuma"),
    "write_yuma": ("psdbound.ionosphere.almanac", "write_yuma"),
    "default_cache_dir": ("psdbound.ionosphere.batch", "default_cache_dir"),
    "map_cutoffs": ("psdbound.ionosphere.batch", "map_cutoffs"),
    "select_days": ("psdbound.ionosphere.batch", "select_days"),
    "station_cutoffs": ("psdbound.ionosphere.batch", "station_cutoffs"),
    "NominalConstellation": ("psdbound.ionosphere.constellation", "NominalConstellation"),
    "nominal_constellation": ("psdbound.ionosphere.constellation", "nominal_constellation"),
    "CRITERIA": ("psdbound.ionosphere.cutoff", "CRITERIA"),
    "SeriesCutoff": ("psdbound.ionosphere.cutoff", "SeriesCutoff"),
    "absolute_cutoff": ("psdbound.ionosphere.cutoff", "absolute_cutoff"),
    "one_day_series": ("psdbound.ionosphere.cutoff", "one_day_series"),
    "relative_cutoff": ("psdbound.ionosphere.cutoff", "relative_cutoff"),
    "series_cutoff": ("psdbound.ionosphere.cutoff", "series_cutoff"),
    "Envelope": ("psdbound.ionosphere.envelope", "Envelope"),
    "fit_envelope": ("psdbound.ionosphere.envelope", "fit_envelope"),
    "local_maxima": ("psdbound.ionosphere.envelope", "local_maxima"),
    "DEFAULT_F107_SFU": ("psdbound.ionosphere.iri", "DEFAULT_F107_SFU"),
    "write_cutoff_outputs": ("psdbound.ionosphere.outputs", "write_cutoff_outputs"),
    "CUTOFF_SOURCES": ("psdbound.ionosphere.policy", "CUTOFF_SOURCES"),
    "THESIS_CUTOFF_HZ": ("psdbound.ionosphere.policy", "THESIS_CUTOFF_HZ"),
    "CutoffChoice": ("psdbound.ionosphere.policy", "CutoffChoice"),
    "CutoffOptions": ("psdbound.ionosphere.policy", "CutoffOptions"),
    "choose_cutoff": ("psdbound.ionosphere.policy", "choose_cutoff"),
    "cutoff_computed": ("psdbound.ionosphere.policy", "cutoff_computed"),
    "cutoff_from_map": ("psdbound.ionosphere.policy", "cutoff_from_map"),
    "ResidualCutoff": ("psdbound.ionosphere.residual", "ResidualCutoff"),
    "residual_cutoff": ("psdbound.ionosphere.residual", "residual_cutoff"),
    "residual_cutoffs": ("psdbound.ionosphere.residual", "residual_cutoffs"),
    "residual_rms": ("psdbound.ionosphere.residual", "residual_rms"),
    "residual_threshold_m": ("psdbound.ionosphere.residual", "residual_threshold_m"),
    "CutoffMap": ("psdbound.ionosphere.results", "CutoffMap"),
    "StationCutoffs": ("psdbound.ionosphere.results", "StationCutoffs"),
    "SETTING_OPTIONS": ("psdbound.ionosphere.settings", "SETTING_OPTIONS"),
    "CutoffSettings": ("psdbound.ionosphere.settings", "CutoffSettings"),
    "FREQUENCIES_HZ": ("psdbound.ionosphere.slant", "FREQUENCIES_HZ"),
    "SlantDelay": ("psdbound.ionosphere.slant", "SlantDelay"),
    "simulate_slant_delay": ("psdbound.ionosphere.slant", "simulate_slant_delay"),
    "CHICAGO": ("psdbound.ionosphere.stations", "CHICAGO"),
    "MAP_STATIONS": ("psdbound.ionosphere.stations", "MAP_STATIONS"),
    "THESIS_CHICAGO_2020_HZ": ("psdbound.ionosphere.names", "THESIS_CHICAGO_2020_HZ"),
    "Station": ("psdbound.ionosphere.stations", "Station"),
    "nearest_station": ("psdbound.ionosphere.stations", "nearest_station"),
    "validate_station": ("psdbound.ionosphere.stations", "validate_station"),
    "CutoffOutcome": ("psdbound.ionosphere.workflow", "CutoffOutcome"),
    "run_cutoff": ("psdbound.ionosphere.workflow", "run_cutoff"),
    "run_world_map": ("psdbound.ionosphere.workflow", "run_world_map"),
    "MapLayer": ("psdbound.ionosphere.worldmap", "MapLayer"),
    "compute_world_map": ("psdbound.ionosphere.worldmap", "compute_world_map"),
    "interpolate_map": ("psdbound.ionosphere.worldmap", "interpolate_map"),
    "load_map": ("psdbound.ionosphere.worldmap", "load_map"),
    "frequency_grid": ("psdbound.periodogram", "frequency_grid"),
    "lomb_scargle": ("psdbound.periodogram", "lomb_scargle"),
    "to_one_sided_density": ("psdbound.periodogram", "to_one_sided_density"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
