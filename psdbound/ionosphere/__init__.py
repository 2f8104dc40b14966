"""Ionosphere high-pass cutoff selection (method.md section 2).

Pipeline: satellite geometry (navigation, SP3, YUMA almanac, or a nominal
constellation) -> slant ionospheric delay from PyIRI electron density every
12 s -> one-day series per satellite replicated over 7 sidereal days ->
Lomb-Scargle PSD -> upper envelope (local maxima + high-quantile regression
in log-log) -> cutoff by the 40 dB relative or the absolute criterion ->
per-station summary (recommended = max) and a worldwide station map.

Public surface:

* geometry: :func:`nominal_constellation` -> :class:`NominalConstellation`;
  :func:`read_yuma` / :func:`write_yuma` / :func:`almanac_from_navigation`
  -> :class:`Almanac`
* delays: :func:`simulate_slant_delay` -> :class:`SlantDelay`
* spectrum: :func:`lomb_scargle`, :func:`frequency_grid`,
  :func:`to_one_sided_density`
* envelope and criteria: :func:`fit_envelope` -> :class:`Envelope`,
  :func:`relative_cutoff`, :func:`absolute_cutoff`, :func:`one_day_series`,
  :func:`series_cutoff` -> :class:`SeriesCutoff`
* batch: :func:`station_cutoffs` -> :class:`StationCutoffs`,
  :func:`map_cutoffs` -> :class:`CutoffMap`, :class:`CutoffSettings`,
  :func:`select_days`
* stations: :data:`MAP_STATIONS`, :data:`CHICAGO`, :func:`nearest_station`
* figures: :mod:`psdbound.ionosphere.figures`
"""

from __future__ import annotations

from psdbound.ionosphere.almanac import Almanac, almanac_from_navigation, read_yuma, write_yuma
from psdbound.ionosphere.batch import (
    CutoffMap,
    CutoffSettings,
    StationCutoffs,
    default_cache_dir,
    map_cutoffs,
    select_days,
    station_cutoffs,
)
from psdbound.ionosphere.constellation import (
    SIDEREAL_DAY_S,
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
from psdbound.ionosphere.iri import (
    DEFAULT_F107_SFU,
    FREQUENCIES_HZ,
    SlantDelay,
    simulate_slant_delay,
)
from psdbound.ionosphere.lombscargle import frequency_grid, lomb_scargle, to_one_sided_density
from psdbound.ionosphere.stations import CHICAGO, MAP_STATIONS, Station, nearest_station

__all__ = [
    "CHICAGO",
    "CRITERIA",
    "DEFAULT_F107_SFU",
    "FREQUENCIES_HZ",
    "MAP_STATIONS",
    "SIDEREAL_DAY_S",
    "Almanac",
    "CutoffMap",
    "CutoffSettings",
    "Envelope",
    "NominalConstellation",
    "SeriesCutoff",
    "SlantDelay",
    "Station",
    "StationCutoffs",
    "absolute_cutoff",
    "almanac_from_navigation",
    "default_cache_dir",
    "fit_envelope",
    "frequency_grid",
    "local_maxima",
    "lomb_scargle",
    "map_cutoffs",
    "nearest_station",
    "nominal_constellation",
    "one_day_series",
    "read_yuma",
    "relative_cutoff",
    "select_days",
    "series_cutoff",
    "simulate_slant_delay",
    "station_cutoffs",
    "to_one_sided_density",
    "write_yuma",
]
