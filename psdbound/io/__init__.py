"""Reading and geometry: RINEX observations, orbits, satellite geometry, arcs."""

from __future__ import annotations

from psdbound.io.obs import Observations, ObsHeader, SystemBlock, read_obs

__all__ = ["Observations", "ObsHeader", "SystemBlock", "read_obs"]
