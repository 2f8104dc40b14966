"""Stationarity: elevation mapping, Levene/K-S tests, slide/trim windowing."""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.stationarity.coverage import covered_time_s
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
    from psdbound.stationarity.thesis_test import StationarityTest, test_stationarity
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
    "covered_time_s",
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

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "covered_time_s": ("psdbound.stationarity.coverage", "covered_time_s"),
    "THESIS_MAPPING": ("psdbound.stationarity.mapping", "THESIS_MAPPING"),
    "ElevationMapping": ("psdbound.stationarity.mapping", "ElevationMapping"),
    "fit_mapping": ("psdbound.stationarity.mapping", "fit_mapping"),
    "MAPPING_KINDS": ("psdbound.stationarity.options", "MAPPING_KINDS"),
    "MappingOptions": ("psdbound.stationarity.options", "MappingOptions"),
    "StationarityOptions": ("psdbound.stationarity.options", "StationarityOptions"),
    "choose_mapping": ("psdbound.stationarity.options", "choose_mapping"),
    "SpectralHomogeneityTest": ("psdbound.stationarity.spectral", "SpectralHomogeneityTest"),
    "min_samples": ("psdbound.stationarity.spectral", "min_samples"),
    "test_spectral_homogeneity": ("psdbound.stationarity.spectral", "test_spectral_homogeneity"),
    "StationarityTest": ("psdbound.stationarity.thesis_test", "StationarityTest"),
    "test_stationarity": ("psdbound.stationarity.thesis_test", "test_stationarity"),
    "Window": ("psdbound.stationarity.windowing", "Window"),
    "WindowSet": ("psdbound.stationarity.windowing", "WindowSet"),
    "find_stationary_windows": ("psdbound.stationarity.windowing", "find_stationary_windows"),
    "window_arc": ("psdbound.stationarity.windowing", "window_arc"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
