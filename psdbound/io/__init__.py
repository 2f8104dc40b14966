"""Reading and geometry: RINEX observations, orbits, satellite geometry.

Public surface:

* :func:`read_obs` -> :class:`Observations` (RINEX 2.1x/3.0x/4.0x observation files)
* :func:`read_orbit` -> :class:`Navigation` or :class:`PreciseOrbit`
  (also :func:`read_nav`, :func:`read_sp3`); GLONASS broadcast records are
  :class:`GlonassEphemerides`
* :func:`orbit_coverage` -> :class:`OrbitCoverage`: does an orbit cover the
  observed satellites and epochs, and if not why
* :func:`satellite_azel`, :func:`azimuth_elevation`, :func:`ecef_to_geodetic`

Tracking arcs are the next stage's (:mod:`psdbound.arcs`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from psdbound.common.lazy import lazy_exports

if TYPE_CHECKING:  # the names below, for type checkers; imported on first use
    from psdbound.io.coverage import OrbitCoverage, SystemCoverage, orbit_coverage
    from psdbound.io.geometry import azimuth_elevation, ecef_to_geodetic, satellite_azel
    from psdbound.io.glonass import GlonassEphemerides
    from psdbound.io.nav import Navigation, read_nav
    from psdbound.io.obs import Observations, ObsHeader, SystemBlock, read_obs
    from psdbound.io.orbits import read_orbit
    from psdbound.io.sp3 import PreciseOrbit, read_sp3

__all__ = [
    "GlonassEphemerides",
    "Navigation",
    "ObsHeader",
    "Observations",
    "OrbitCoverage",
    "PreciseOrbit",
    "SystemBlock",
    "SystemCoverage",
    "azimuth_elevation",
    "ecef_to_geodetic",
    "orbit_coverage",
    "read_nav",
    "read_obs",
    "read_orbit",
    "read_sp3",
    "satellite_azel",
]

#: Where each public name lives (imported on first use: importing the package stays cheap).
_EXPORTS = {
    "OrbitCoverage": ("psdbound.io.coverage", "OrbitCoverage"),
    "SystemCoverage": ("psdbound.io.coverage", "SystemCoverage"),
    "orbit_coverage": ("psdbound.io.coverage", "orbit_coverage"),
    "azimuth_elevation": ("psdbound.io.geometry", "azimuth_elevation"),
    "ecef_to_geodetic": ("psdbound.io.geometry", "ecef_to_geodetic"),
    "satellite_azel": ("psdbound.io.geometry", "satellite_azel"),
    "GlonassEphemerides": ("psdbound.io.glonass", "GlonassEphemerides"),
    "Navigation": ("psdbound.io.nav", "Navigation"),
    "read_nav": ("psdbound.io.nav", "read_nav"),
    "Observations": ("psdbound.io.obs", "Observations"),
    "ObsHeader": ("psdbound.io.obs", "ObsHeader"),
    "SystemBlock": ("psdbound.io.obs", "SystemBlock"),
    "read_obs": ("psdbound.io.obs", "read_obs"),
    "read_orbit": ("psdbound.io.orbits", "read_orbit"),
    "PreciseOrbit": ("psdbound.io.sp3", "PreciseOrbit"),
    "read_sp3": ("psdbound.io.sp3", "read_sp3"),
}

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
