"""Stationarity: elevation mapping, Levene/K-S tests, slide/trim windowing."""

from __future__ import annotations

from psdbound.stationarity.mapping import THESIS_MAPPING, ElevationMapping, fit_mapping
from psdbound.stationarity.options import (
    MAPPING_KINDS,
    MappingOptions,
    StationarityOptions,
    choose_mapping,
)
from psdbound.stationarity.spectral import (
    SpectralHomogeneityTest,
    min_samples,
    test_spectral_homogeneity,
)
from psdbound.stationarity.tests import StationarityTest, test_stationarity
from psdbound.stationarity.windowing import (
    Window,
    WindowSet,
    find_stationary_windows,
    window_arc,
)

__all__ = [
    "min_samples",
    "MAPPING_KINDS",
    "THESIS_MAPPING",
    "MappingOptions",
    "StationarityOptions",
    "choose_mapping",
    "ElevationMapping",
    "SpectralHomogeneityTest",
    "StationarityTest",
    "Window",
    "WindowSet",
    "find_stationary_windows",
    "fit_mapping",
    "test_spectral_homogeneity",
    "test_stationarity",
    "window_arc",
]
