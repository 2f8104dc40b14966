"""One front for satellite orbits: broadcast navigation or SP3 precise orbits."""

from __future__ import annotations

import os
from pathlib import Path

from psdbound.io._source import read_bytes
from psdbound.io.nav import Navigation, read_nav
from psdbound.io.sp3 import PreciseOrbit, read_sp3

__all__ = ["read_orbit"]


def read_orbit(path: str | os.PathLike[str]) -> Navigation | PreciseOrbit:
    """Read an orbit file: RINEX navigation (2/3) or SP3-c/d, detected from content.

    Parameters
    ----------
    path : str or path-like
        Navigation or SP3 file, plain or compressed.

    Returns
    -------
    Navigation or PreciseOrbit
        Both provide ``positions_ecef_m(sat, t_gps_s)`` and ``satellites``.

    See Also
    --------
    read_obs : The observations the orbits serve.
    psdbound.io.orbit_coverage : Whether the orbits cover the observed systems and epochs.

    References
    ----------
    .. [1] IS-GPS-200 (Navstar GPS Space Segment / Navigation User Interfaces),
       Table 20-IV (broadcast ephemeris to ECEF).
    .. [2] Hilla, S. (2016). The Extended Standard Product 3 Orbit Format (SP3-d).
    .. [3] GLONASS ICD, edition 5.1 (2008), appendix A.3.1.2 (numerical integration).

    Examples
    --------
    >>> from psdbound.simulate import demo_data
    >>> nav = read_orbit(demo_data().nav_path)
    >>> type(nav).__name__
    'Navigation'
    """
    p = Path(path)
    if read_bytes(p)[:2] in (b"#c", b"#d", b"#a", b"#b"):
        return read_sp3(p)
    return read_nav(p)
