"""Helpers of the dual-antenna isolation: epochs, satellites, positions, clocks, references.

Internal to :mod:`psdbound.isolation` (see :mod:`psdbound.isolation.dual_antenna`
for the method).
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.errors import InputError
from psdbound.io.geometry import (
    SPEED_OF_LIGHT_M_S,
    OrbitSource,
    azimuth_elevation,
    ecef_to_geodetic,
    enu_rotation,
    signal_path,
)
from psdbound.io.obs import Observations
from psdbound.io.signals import RINEX2_TO_RINEX3
from psdbound.io.timescales import gps_s_to_datetime64

#: Two epochs of the two files are the same epoch when closer than this, s. A receiver
#: whose clock is left to drift tags its epochs away from the nominal second (GSI's
#: Trimble 5700s of 2005-04-02 in RTKLIB's test data: +5 ms and -4 ms within an hour,
#: 12 of 120 epochs within 1 ms); the geometry of each receiver is computed at its own
#: clock-corrected receive time, so such epochs are the same measurement epoch. 50 ms
#: keeps epochs of different samplings (half a 1 Hz interval apart) apart.
EPOCH_TOLERANCE_S = 0.05

__all__ = [
    "EPOCH_TOLERANCE_S",
    "SDArc",
    "antenna_position",
    "any_above",
    "check_not_same",
    "clock_code",
    "common_satellites",
    "estimate_receiver_clock",
    "geometric_range_m",
    "geometry_all",
    "match_epochs",
    "reference_periods",
    "resolve_pair",
    "span",
]


@dataclass
class SDArc:
    """A single-difference arc on the common epoch axis."""

    sat: str
    ci: NDArray[np.intp]  # indices into the common epochs, increasing
    sd_m: NDArray[np.float64]
    el_deg: NDArray[np.float64]
    los: NDArray[np.float64]  # unit line-of-sight vectors, ECEF, shape (n, 3)


def check_not_same(obs1: Observations, obs2: Observations, files: str) -> None:
    same = obs1 is obs2
    if not same:
        try:
            same = os.path.samefile(obs1.path, obs2.path)
        except OSError:
            same = os.path.abspath(obs1.path) == os.path.abspath(obs2.path)
    if same:
        raise InputError(
            f"the same observation file given twice ({files}): dual-antenna isolation "
            "needs the files of two receivers"
        )


def antenna_position(
    obs: Observations, given: ArrayLike | None, name: str
) -> tuple[NDArray[np.float64], str]:
    if given is not None:
        pos = np.asarray(given, dtype=np.float64).reshape(-1)
        if pos.shape != (3,) or not np.all(np.isfinite(pos)):
            raise InputError(f"{name} must be three finite ECEF coordinates in metres, got {given}")
        return pos, "user"
    marker = obs.header.approx_position_m
    if marker is None:
        raise InputError(
            f"no antenna position: the header has no APPROX POSITION XYZ; give {name}",
            path=obs.path,
        )
    marker = np.asarray(marker, dtype=np.float64)
    hen = np.asarray(obs.header.antenna_delta_hen_m, dtype=np.float64)
    if np.any(hen != 0.0):
        lat, lon, _ = ecef_to_geodetic(marker)
        enu = np.array([hen[1], hen[2], hen[0]])
        return marker + enu_rotation(lat, lon).T @ enu, "header APPROX POSITION XYZ + DELTA H/E/N"
    return marker, "header APPROX POSITION XYZ"


def resolve_pair(
    obs1: Observations, obs2: Observations, system: str, code: str, what: str
) -> tuple[str, str]:
    out, missing = [], []
    for obs in (obs1, obs2):
        try:
            out.append(obs.resolve_code(system, code))
        except InputError:
            missing.append(obs)
    if missing:
        have = "; ".join(f"{o.path} has {' '.join(o.codes(system))}" for o in (obs1, obs2))
        raise InputError(
            f"{what} {code!r} missing from {' and '.join(o.path for o in missing)} "
            f"(system {system}); {have}"
        )
    return out[0], out[1]


def span(obs: Observations) -> str:
    if obs.t_gps_s.size == 0:
        return "no epochs"
    lab = gps_s_to_datetime64(obs.t_gps_s[[0, -1]]).astype("datetime64[ms]")
    a, b = (str(x).replace("T", " ") for x in lab)
    return f"{a} to {b} GPST"


def match_epochs(
    obs1: Observations, obs2: Observations, files: str
) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """Return the indices of the common epochs in both files (within :data:`EPOCH_TOLERANCE_S`)."""
    t1, t2 = obs1.t_gps_s, obs2.t_gps_s
    i1 = i2 = np.zeros(0, dtype=np.intp)
    if t1.size and t2.size:
        order = np.argsort(t2, kind="stable")
        ts = t2[order]
        j = np.searchsorted(ts, t1)
        jl = np.clip(j - 1, 0, ts.size - 1)
        jr = np.clip(j, 0, ts.size - 1)
        dl, dr = np.abs(t1 - ts[jl]), np.abs(ts[jr] - t1)
        jb = np.where(dr < dl, jr, jl)
        ok = np.minimum(dl, dr) <= EPOCH_TOLERANCE_S
        i1 = np.flatnonzero(ok)
        i2 = order[jb[ok]]
        _, first = np.unique(i2, return_index=True)
        keep = np.sort(first)
        i1, i2 = i1[keep], i2[keep]
    if i1.size == 0:
        hint = ""
        if t1.size and t2.size:
            d1 = gps_s_to_datetime64(t1[[0, -1]]).astype("datetime64[D]")
            d2 = gps_s_to_datetime64(t2[[0, -1]]).astype("datetime64[D]")
            if d1[0] != d2[0] and d1[-1] != d2[-1]:
                hint = " (files from different days)"
        raise InputError(
            f"no common epochs{hint}: {obs1.path} spans {span(obs1)}, "
            f"{obs2.path} spans {span(obs2)}"
        )
    return i1, i2


def common_satellites(
    obs1: Observations,
    obs2: Observations,
    system: str,
    code1: str,
    code2: str,
    i1: NDArray[np.intp],
    i2: NDArray[np.intp],
    files: str,
) -> list[str]:
    b1, b2 = obs1.blocks[system], obs2.blocks[system]
    k1, k2 = b1.codes.index(code1), b2.codes.index(code2)
    out = []
    for s in sorted(set(b1.sats) & set(b2.sats)):
        v1 = b1.values[i1, b1.sats.index(s), k1]
        v2 = b2.values[i2, b2.sats.index(s), k2]
        if np.any(np.isfinite(v1) & np.isfinite(v2) & (v1 != 0.0) & (v2 != 0.0)):
            out.append(s)
    if not out:
        raise InputError(
            f"no common satellites tracked on {code1} at common epochs in {files}: "
            f"{obs1.path} has {' '.join(b1.sats) or 'none'}, "
            f"{obs2.path} has {' '.join(b2.sats) or 'none'}"
        )
    return out


def any_above(
    obs: Observations,
    sat: str,
    code: str,
    slip: str | None,
    el: NDArray[np.float64],
    mask_deg: float,
) -> bool:
    """Whether ``find_arcs`` would find any epoch of ``sat`` above the mask.

    Works around a satellite whose tracked epochs are all below the mask.
    """
    ok = np.isfinite(obs.phase_m(sat, code))
    if slip is not None:
        ok &= np.isfinite(obs.phase_m(sat, slip))
    return bool(ok.sum() >= 2 and np.any(el[ok] >= mask_deg))


# --------------------------------------------------------------------------- geometry


def geometric_range_m(
    orbit: OrbitSource, sat: str, t_rx_gps_s: NDArray[np.float64], rx_m: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Range (m), travel time (s) and transmit position (m); see :func:`signal_path`."""
    return signal_path(orbit, sat, t_rx_gps_s, rx_m)


def geometry_all(
    orbit: OrbitSource, sats: Sequence[str], t_gps_s: NDArray[np.float64], rx_m: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Range, travel time and elevation of every satellite at the nominal epochs."""
    shape = (t_gps_s.size, len(sats))
    rho, tau, el = np.empty(shape), np.empty(shape), np.empty(shape)
    for k, s in enumerate(sats):
        rho[:, k], tau[:, k], sv = geometric_range_m(orbit, s, t_gps_s, rx_m)
        el[:, k] = azimuth_elevation(rx_m, sv)[1]
    return rho, tau, el


def clock_code(obs: Observations, system: str, phase_code: str) -> str:
    """Pseudorange code for the clock estimate: same band, else C1C, P1, any."""
    r3 = RINEX2_TO_RINEX3.get(phase_code, phase_code)
    for c in (f"C{r3[1:]}", "C1C", "C1W", "C1P", "C1X"):
        try:
            return obs.resolve_code(system, c)
        except InputError:
            pass
    for c in obs.codes(system):
        if c[0] in "CP":
            return c
    raise InputError(
        f"no pseudorange to estimate the receiver clock (codes: {' '.join(obs.codes(system))})",
        path=obs.path,
    )


def estimate_receiver_clock(
    obs: Observations,
    orbit: OrbitSource,
    sats: Sequence[str],
    phase_code: str,
    rho_m: NDArray[np.float64],
    tau_s: NDArray[np.float64],
) -> tuple[NDArray[np.float64], str, int]:
    """Receiver clock offset per epoch of ``obs``, seconds.

    Median over satellites of ``(P - rho + c dT) / c``; epochs without any
    usable pseudorange get the value interpolated linearly in time.

    Returns
    -------
    dt_s : ndarray of float64, shape (n_epoch,)
        Clock offset (receiver time minus GPS time), seconds.
    code : str
        The pseudorange code used.
    n_interpolated : int
        Number of epochs with an interpolated value.
    """
    system = sats[0][0]
    code = clock_code(obs, system, phase_code)
    block = obs.blocks[system]
    kc = block.codes.index(code)
    pr = np.full(rho_m.shape, np.nan)
    sat_clock = getattr(orbit, "satellite_clock_s", None)
    for k, s in enumerate(sats):
        if s not in block.sats:
            continue
        p = block.values[:, block.sats.index(s), kc]
        pr[:, k] = np.where(p > 0.0, p, np.nan)
        if sat_clock is not None:
            pr[:, k] += SPEED_OF_LIGHT_M_S * sat_clock(s, obs.t_gps_s - tau_s[:, k])
    x = (pr - rho_m) / SPEED_OF_LIGHT_M_S
    good = np.isfinite(x)
    dt = np.full(obs.t_gps_s.size, np.nan)
    rows = good.any(axis=1)
    if not rows.any():
        raise InputError(
            f"no usable pseudorange ({code}) to estimate the receiver clock", path=obs.path
        )
    dt[rows] = np.nanmedian(x[rows], axis=1)
    n_interp = int((~rows).sum())
    if n_interp:
        dt[~rows] = np.interp(obs.t_gps_s[~rows], obs.t_gps_s[rows], dt[rows])
    return dt, code, n_interp


# --------------------------------------------------------------------------- reference


def reference_periods(sd_arcs: list[SDArc]) -> list[tuple[SDArc, int, int]]:
    """Choose reference arcs and their periods (inclusive common-epoch indices)."""
    starts = np.array([a.ci[0] for a in sd_arcs])
    stops = np.array([a.ci[-1] for a in sd_arcs])
    periods: list[tuple[SDArc, int, int]] = []
    k = int(starts.min())
    last = int(stops.max())
    while k <= last:
        active = np.flatnonzero((starts <= k) & (stops >= k))
        if active.size == 0:
            later = starts[starts > k]
            if later.size == 0:
                break
            k = int(later.min())
            continue

        def elevation_at(a: SDArc, k: int = k) -> float:
            j = min(int(np.searchsorted(a.ci, k)), a.ci.size - 1)
            return float(a.el_deg[j])

        ref = max((sd_arcs[j] for j in active), key=elevation_at)
        periods.append((ref, k, int(ref.ci[-1])))
        k = int(ref.ci[-1]) + 1
    return periods
