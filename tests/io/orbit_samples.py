"""Synthetic observations that follow an orbit, for the orbit-coverage tests.

The phases are the geometric ranges (plus a constant) of the satellites of a
nominal constellation seen from a receiver near ESBC, present only while the
satellite is above 5 degrees: arcs then get elevations exactly where the
orbit gives positions.
"""

from __future__ import annotations

import numpy as np

from psdbound.io import ObsHeader
from psdbound.io.geometry import satellite_azel, signal_path
from psdbound.io.nominal import nominal_navigation
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import wavelength_m
from psdbound.io.timescales import calendar_to_gps_s

RX = np.array([3582105.291, 532589.7313, 5232754.8054])
CODES = {"G": ("L1C", "L2W"), "E": ("L1C", "L5Q")}
T2020 = float(calendar_to_gps_s(2020, 6, 25, 6, 0, 0.0))
T2022 = float(calendar_to_gps_s(2022, 11, 11, 17, 0, 0.0))


def geometric_observations(
    nav,
    systems: str = "GE",
    t0: float = T2020,
    hours: float = 2.0,
    interval_s: float = 30.0,
    path: str = "synthetic.rnx",
    drop_code: str | None = None,
) -> Observations:
    """Observations of every satellite of ``nav`` above 5 deg (NaN elsewhere).

    ``drop_code`` (e.g. ``"L2W"``) leaves that signal untracked.
    """
    t = t0 + interval_s * np.arange(int(hours * 3600 / interval_s))
    blocks = {}
    for system in systems:
        sats = list(nav.ephemerides[system].satellites)
        codes = CODES[system]
        v = np.full((t.size, len(sats), 2), np.nan)
        for i, sat in enumerate(sats):
            rho, _, _ = signal_path(nav, sat, t, RX)
            _, el = satellite_azel(nav, sat, t, RX)
            up = el > 5.0
            for k, code in enumerate(codes):
                v[up, i, k] = rho[up] / wavelength_m(sat, code) + 1000.0 * (k + 1)
        if drop_code in codes:
            v[:, :, codes.index(drop_code)] = np.nan
        seen = np.isfinite(v).any(axis=(0, 2))
        v = v[:, seen]
        sats = [s for s, keep in zip(sats, seen, strict=True) if keep]
        lli = np.where(np.isfinite(v), 0, -1).astype(np.int8)
        blocks[system] = SystemBlock(system, tuple(sats), codes, v, lli, lli.copy())
    header = ObsHeader(
        version=3.04,
        file_system="M" if len(systems) > 1 else systems,
        marker_name="SYNT",
        receiver_type="SYNTH",
        antenna_type="NONE",
        approx_position_m=RX.copy(),
        antenna_delta_hen_m=np.zeros(3),
        interval_s=interval_s,
        time_system="GPS",
        obs_types={s: CODES[s] for s in systems},
    )
    return Observations(path, header, t, np.zeros(t.size, np.int8), blocks)


def nominal(systems: str, t0: float = T2020, hours: float = 2.0, path: str = "brdc.rnx"):
    """Nominal broadcast records around ``[t0, t0 + hours]``, with a file name."""
    from dataclasses import replace
    from pathlib import Path

    nav = nominal_navigation(t0, t0 + hours * 3600, systems=systems)
    return replace(nav, path=Path(path))
