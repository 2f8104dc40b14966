"""GPS almanacs in YUMA format: reader, writer, propagation.

A YUMA almanac is the text form of the GPS almanac that the U.S. Coast Guard
Navigation Center and most planning tools publish: one block per satellite,
one ``Label: value`` line per field::

    ******** Week 109 almanac for PRN-01 ********
    ID:                         01
    Health:                     000
    Eccentricity:               0.1059055328E-001
    Time of Applicability(s):  405504.0000
    Orbital Inclination(rad):   0.9880042076
    Rate of Right Ascen(r/s):  -0.7611745400E-008
    SQRT(A)  (m 1/2):           5153.626465
    Right Ascen at Week(rad):  -0.1536497474E+001
    Argument of Perigee(rad):   0.732259750
    Mean Anom(rad):            -0.1062670946E+001
    Af0(s):                     0.5483627319E-003
    Af1(s/s):                   0.3637978807E-011
    week:                        109

The week is usually broadcast modulo 1024; :func:`read_yuma` resolves the
rollover to the era nearest a reference time (the dates being simulated).
Positions follow the IS-GPS-200 almanac user algorithm (table 20-IV with
the almanac parameters: no harmonic corrections, no mean-motion correction,
inclination given in full).

Almanacs are meant for planning: positions are good to a few km over weeks
and degrade slowly over months, which is ample for elevation/azimuth
geometry.
"""

from __future__ import annotations

import os
import re
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.common import atomic_write_text
from psdbound.constants import GM_GPS_M3_S2, OMEGA_E_RAD_S
from psdbound.errors import InputError
from psdbound.io.ephemeris import solve_kepler
from psdbound.io.timescales import SECONDS_PER_WEEK

__all__ = ["Almanac", "read_yuma", "write_yuma", "almanac_from_navigation"]

_FIELDS = {
    "id": "prn",
    "health": "health",
    "eccentricity": "e",
    "time of applicability(s)": "toa_sow_s",
    "orbital inclination(rad)": "i0_rad",
    "rate of right ascen(r/s)": "omega_dot_rad_s",
    "sqrt(a) (m 1/2)": "sqrt_a",
    "right ascen at week(rad)": "omega0_rad",
    "argument of perigee(rad)": "omega_rad",
    "mean anom(rad)": "m0_rad",
    "af0(s)": "af0_s",
    "af1(s/s)": "af1",
    "week": "week",
}
_HEADER_RE = re.compile(r"^\*+\s*week\s+(\d+)\s+almanac\s+for\s+prn-?\s*(\d+)", re.IGNORECASE)


@dataclass(frozen=True, eq=False)
class Almanac:
    """GPS almanac: one Keplerian element set per satellite.

    Implements :class:`psdbound.io.geometry.OrbitSource`.

    Attributes
    ----------
    sats : tuple of str
        Satellite ids (``'G01'`` ...), one per row.
    toa_gps_s : ndarray of float64
        Time of applicability, GPS seconds (week rollover resolved).
    e, sqrt_a, i0_rad, omega_dot_rad_s, omega0_rad, omega_rad, m0_rad : ndarray
        Keplerian elements (eccentricity, sqrt of semi-major axis in
        m^0.5, inclination, rate of right ascension, longitude of the node
        at the start of the week, argument of perigee, mean anomaly at toa).
    af0_s, af1 : ndarray of float64
        Clock bias (s) and drift (s/s).
    health : ndarray of int64
        Health word (0 = healthy).
    path : str
        Source file, or a description when built in memory.
    """

    sats: tuple[str, ...]
    toa_gps_s: NDArray[np.float64]
    e: NDArray[np.float64]
    sqrt_a: NDArray[np.float64]
    i0_rad: NDArray[np.float64]
    omega_dot_rad_s: NDArray[np.float64]
    omega0_rad: NDArray[np.float64]
    omega_rad: NDArray[np.float64]
    m0_rad: NDArray[np.float64]
    af0_s: NDArray[np.float64]
    af1: NDArray[np.float64]
    health: NDArray[np.int64]
    path: str = "<memory>"
    _index: dict[str, int] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self._index.update({s: i for i, s in enumerate(self.sats)})

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of the healthy satellites."""
        return tuple(sorted(s for s, h in zip(self.sats, self.health, strict=True) if h == 0))

    @property
    def source_id(self) -> str:
        """Short identifier of the orbit source, used in cache keys and results."""
        return f"yuma:{Path(self.path).name}:toa={float(np.median(self.toa_gps_s)):.0f}"

    @property
    def description(self) -> str:
        """What this almanac is (recorded with results)."""
        return f"YUMA almanac {self.path} ({len(self.satellites)} healthy GPS satellites)"

    def positions_ecef_m(self, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
        """ECEF positions of one satellite from its almanac elements.

        Parameters
        ----------
        sat : str
            Satellite id such as ``'G05'``.
        t_gps_s : array_like of float
            Times, GPS seconds (scalar or 1-D).

        Returns
        -------
        ndarray of float64, shape (n, 3)
            ECEF coordinates, m; NaN for a satellite absent or unhealthy.
        """
        t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
        j = self._index.get(str(sat))
        if j is None or self.health[j] != 0:
            return np.full((t.shape[0], 3), np.nan)
        a = self.sqrt_a[j] ** 2
        n0 = np.sqrt(GM_GPS_M3_S2 / a**3)
        tk = t - self.toa_gps_s[j]
        m = self.m0_rad[j] + n0 * tk
        ecc = self.e[j]
        ea = solve_kepler(m, ecc)
        nu = np.arctan2(np.sqrt(1.0 - ecc * ecc) * np.sin(ea), np.cos(ea) - ecc)
        phi = nu + self.omega_rad[j]
        r = a * (1.0 - ecc * np.cos(ea))
        toa_sow = self.toa_gps_s[j] - np.floor(self.toa_gps_s[j] / SECONDS_PER_WEEK) * (
            SECONDS_PER_WEEK
        )
        node = (
            self.omega0_rad[j]
            + (self.omega_dot_rad_s[j] - OMEGA_E_RAD_S) * tk
            - OMEGA_E_RAD_S * toa_sow
        )
        xp, yp = r * np.cos(phi), r * np.sin(phi)
        ci, si = np.cos(self.i0_rad[j]), np.sin(self.i0_rad[j])
        cn, sn = np.cos(node), np.sin(node)
        return np.stack([xp * cn - yp * ci * sn, xp * sn + yp * ci * cn, yp * si], axis=-1)


def _resolve_week(week: int, toa_sow: float, near_gps_s: float | None) -> float:
    if week >= 1024:
        return week * SECONDS_PER_WEEK + toa_sow
    ref = near_gps_s
    if ref is None:
        ref = time.time() - 315964800.0 + 18.0  # now, roughly in GPS seconds
    era = np.round((ref / SECONDS_PER_WEEK - week) / 1024.0)
    full = week + 1024 * max(int(era), 0)
    return full * SECONDS_PER_WEEK + toa_sow


def _check_header(line: str, p: Path, i: int) -> None:
    """Refuse a block header line (starting with '*') not in the YUMA layout."""
    if not _HEADER_RE.match(line):
        raise InputError(
            f"expected a block header like '******** Week 109 almanac for PRN-01 "
            f"********', got {line[:60]!r}",
            path=p,
            line=i,
        )


def _field(line: str, p: Path, i: int) -> tuple[str, float] | None:
    """Return the field name and value of a 'Label: value' line (None: a label not used)."""
    label, value = line.split(":", 1)
    key = _FIELDS.get(re.sub(r"\s+", " ", label.strip().lower()))
    if key is None:
        return None
    try:
        return key, float(value.strip())
    except ValueError:
        raise InputError(
            f"cannot read {label.strip()!r}: {value.strip()!r} is not a number", path=p, line=i
        ) from None


def _yuma_blocks(lines: list[str], p: Path) -> list[dict[str, float]]:
    """Return the fields of every PRN block, each checked complete."""
    blocks: list[dict[str, float]] = []
    current: dict[str, float] | None = None
    start_line = 0
    for i, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("*"):
            if current is not None:
                blocks.append(_check_block(current, p, start_line))
            _check_header(line, p, i)
            current, start_line = {}, i
            continue
        if current is None or ":" not in line:
            raise InputError(
                f"expected a YUMA almanac 'Label: value' line inside a PRN block, got "
                f"{line[:60]!r}",
                path=p,
                line=i,
            )
        item = _field(line, p, i)
        if item is not None:
            current[item[0]] = item[1]
    if current is not None:
        blocks.append(_check_block(current, p, start_line))
    return blocks


def read_yuma(path: str | os.PathLike[str], *, near_gps_s: float | None = None) -> Almanac:
    """Read a YUMA almanac file.

    Parameters
    ----------
    path : str or path-like
        YUMA text file.
    near_gps_s : float, optional
        GPS seconds near which the almanac applies; a week number below 1024
        (broadcast modulo 1024) is put in the 1024-week era closest to it.
        Default: the current date.

    Returns
    -------
    Almanac

    Raises
    ------
    InputError
        If the file cannot be read, a value cannot be parsed, a block misses
        a field, or no satellite block is found. The message names the line.
    """
    p = Path(path)
    try:
        lines = p.read_text(encoding="latin-1").splitlines()
    except OSError as exc:
        raise InputError(f"cannot read the almanac file: {exc.strerror}", path=p) from None
    blocks = _yuma_blocks(lines, p)
    if not blocks:
        raise InputError("no satellite block found; is this a YUMA almanac?", path=p)
    sats = tuple(f"G{int(b['prn']):02d}" for b in blocks)
    toa = np.array(
        [_resolve_week(int(b["week"]), b["toa_sow_s"], near_gps_s) for b in blocks], dtype=float
    )

    def col(k: str) -> NDArray[np.float64]:
        return np.array([b[k] for b in blocks], dtype=np.float64)

    return Almanac(
        sats=sats,
        toa_gps_s=toa,
        e=col("e"),
        sqrt_a=col("sqrt_a"),
        i0_rad=col("i0_rad"),
        omega_dot_rad_s=col("omega_dot_rad_s"),
        omega0_rad=col("omega0_rad"),
        omega_rad=col("omega_rad"),
        m0_rad=col("m0_rad"),
        af0_s=col("af0_s"),
        af1=col("af1"),
        health=col("health").astype(np.int64),
        path=str(p),
    )


def _check_block(block: dict[str, float], path: Path, line: int) -> dict[str, float]:
    missing = [k for k in _FIELDS.values() if k not in block]
    if missing:
        raise InputError(
            f"the almanac block starting here lacks {', '.join(missing)}", path=path, line=line
        )
    return block


def write_yuma(almanac: Almanac, path: str | os.PathLike[str]) -> Path:
    """Write an almanac as a YUMA text file (full week numbers, not modulo 1024).

    Parameters
    ----------
    almanac : Almanac
        What to write.
    path : str or path-like
        Output file; written atomically (temporary name, then rename).

    Returns
    -------
    pathlib.Path
        The file written.
    """
    p = Path(path)
    out = []
    for j, sat in enumerate(almanac.sats):
        week = int(np.floor(almanac.toa_gps_s[j] / SECONDS_PER_WEEK))
        toa = almanac.toa_gps_s[j] - week * SECONDS_PER_WEEK
        prn = int(sat[1:])
        out += [
            f"******** Week {week % 1024} almanac for PRN-{prn:02d} ********",
            f"ID:                         {prn:02d}",
            f"Health:                     {int(almanac.health[j]):03d}",
            f"Eccentricity:               {almanac.e[j]:.10E}",
            f"Time of Applicability(s):  {toa:.4f}",
            f"Orbital Inclination(rad):   {almanac.i0_rad[j]:.10f}",
            f"Rate of Right Ascen(r/s):  {almanac.omega_dot_rad_s[j]:.10E}",
            f"SQRT(A)  (m 1/2):           {almanac.sqrt_a[j]:.6f}",
            f"Right Ascen at Week(rad):  {almanac.omega0_rad[j]:.10E}",
            f"Argument of Perigee(rad):   {almanac.omega_rad[j]:.9f}",
            f"Mean Anom(rad):            {almanac.m0_rad[j]:.10E}",
            f"Af0(s):                     {almanac.af0_s[j]:.10E}",
            f"Af1(s/s):                   {almanac.af1[j]:.10E}",
            f"week:                        {week}",
            "",
        ]
    return atomic_write_text(p, "\n".join(out), encoding="ascii")


def almanac_from_navigation(nav, t_gps_s: float, *, system: str = "G") -> Almanac:  # noqa: ANN001
    """Almanac elements from the broadcast ephemerides nearest a time.

    For each GPS satellite, the healthy record whose time of ephemeris is
    nearest ``t_gps_s`` gives the elements. The mean-motion correction
    ``delta_n`` is folded into ``sqrt(A)`` (so the propagated mean motion
    matches the broadcast one, which matters over weeks); harmonic
    corrections and the inclination rate are dropped.

    Parameters
    ----------
    nav : psdbound.io.nav.Navigation
        Broadcast navigation.
    t_gps_s : float
        Reference time, GPS seconds.
    system : str, default "G"
        System letter whose records are converted.

    Returns
    -------
    Almanac

    Raises
    ------
    InputError
        If the navigation holds no healthy record of that system.
    """
    eph = nav.ephemerides.get(system)
    if eph is None or not np.any(eph.health == 0):
        raise InputError(
            f"no healthy {system} broadcast ephemeris to build an almanac from", path=nav.path
        )
    rows = []
    for sat in eph.satellites:
        idx = np.flatnonzero((eph.sat == sat) & (eph.health == 0))
        if idx.size:
            rows.append(idx[np.argmin(np.abs(eph.toe_gps_s[idx] - t_gps_s))])
    r = np.array(rows)
    n = np.sqrt(GM_GPS_M3_S2 / eph.sqrt_a[r] ** 6) + eph.delta_n_rad_s[r]
    sqrt_a = (GM_GPS_M3_S2 / n**2) ** (1.0 / 6.0)
    return Almanac(
        sats=tuple(str(s) for s in eph.sat[r]),
        toa_gps_s=eph.toe_gps_s[r].astype(np.float64),
        e=eph.e[r],
        sqrt_a=sqrt_a,
        i0_rad=eph.i0_rad[r],
        omega_dot_rad_s=eph.omega_dot_rad_s[r],
        omega0_rad=eph.omega0_rad[r],
        omega_rad=eph.omega_rad[r],
        m0_rad=eph.m0_rad[r],
        af0_s=eph.af0_s[r],
        af1=eph.af1[r],
        health=np.zeros(r.size, dtype=np.int64),
        path=f"almanac from {nav.path}",
    )
