"""Does an orbit file cover the observations? :func:`orbit_coverage`.

An orbit that does not match the observations (a navigation file of another
day, one without the observed system, an SP3 file that ends before the
observations) gives no satellite position, so no elevation and no arc. This
module says so plainly, before anything downstream reports a misleading
symptom.

For every observed satellite the orbit is evaluated at its observation epochs
(at most ``max_samples`` of them, evenly spread): a satellite is *covered*
when the orbit gives a position at all of them, *partly covered* at some and
*missing* at none. Broadcast ephemerides give positions within their validity
window of a healthy record (4 h for GPS, Galileo, BeiDou and QZSS, 30 min for
GLONASS; see :mod:`psdbound.io.ephemeris` and :mod:`psdbound.io.glonass`);
SP3 files within the span of their epochs.

:meth:`OrbitCoverage.problem` gives the reason when no observed satellite of
a system has a position (the orbit file is of another day, or lacks the
system), :meth:`OrbitCoverage.require` raises it as an
:class:`~psdbound.errors.InputError`, and :meth:`OrbitCoverage.warnings` lists
the satellites without a position when only some lack one.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from psdbound.errors import InputError
from psdbound.io.navigation import Navigation
from psdbound.io.obs import SYSTEM_NAMES, Observations, SystemBlock
from psdbound.io.sp3 import PreciseOrbit
from psdbound.io.timescales import gps_s_to_datetime64

__all__ = ["OrbitCoverage", "SystemCoverage", "orbit_coverage", "MAX_SAMPLES"]

#: Observation epochs per satellite at which the orbit is evaluated (at most).
MAX_SAMPLES = 200


def _name(system: str) -> str:
    """``'Galileo (E)'``."""
    return f"{SYSTEM_NAMES.get(system, system)} ({system})"


def _share(fraction: float) -> str:
    """Format a fraction strictly between 0 and 1 as a percentage never reading 0 or 100 %."""
    for digits in range(4):
        text = f"{100 * fraction:.{digits}f}"
        if 0 < float(text) < 100:
            return f"{text} %"
    return f"{100 * fraction:.4g} %"


def _when(t_gps_s: float) -> str:
    """``'2020-06-25 00:00'`` (GPS time label, minutes)."""
    return str(gps_s_to_datetime64(t_gps_s).astype("datetime64[m]")).replace("T", " ")


def _duration(seconds: float) -> str:
    """``'4 h'``, ``'30 min'``."""
    return f"{seconds / 3600:g} h" if seconds >= 3600 else f"{seconds / 60:g} min"


@dataclass(frozen=True)
class SystemCoverage:
    """How well an orbit covers the observed satellites of one system.

    Attributes
    ----------
    system : str
        System letter.
    in_orbit : bool
        The orbit file has ephemerides (orbits) of this system at all.
    observed : tuple of str
        Satellites with at least one observation, sorted.
    covered : tuple of str
        Satellites with a position at every sampled observation epoch.
    partial : dict of str to float
        Satellites with a position at only some of their sampled epochs, and
        that fraction (0 < f < 1).
    missing : tuple of str
        Satellites with no position at any of their observation epochs
        inside the orbit's span.
    outside : tuple of str
        Satellites observed only outside the orbit's span (see
        ``epochs_outside``).
    span_gps_s : tuple of float or None
        First and last reference time of the system's healthy records
        (broadcast: toe or GLONASS tb; SP3: first and last epoch), GPS
        seconds; None when unknown or the system is absent.
    validity_s : float
        How far from a reference time the orbit is used, s (0 for SP3).
    epochs : int
        Observation epochs with an observation of the examined satellites.
    epochs_outside : int
        How many of them lie outside ``span_gps_s`` (widened by
        ``validity_s``): no satellite of the system has a position there.
        Satellites are rated (covered, partial, missing) on the other epochs.

    """

    system: str
    in_orbit: bool
    observed: tuple[str, ...]
    covered: tuple[str, ...]
    partial: dict[str, float] = field(default_factory=dict)
    missing: tuple[str, ...] = ()
    outside: tuple[str, ...] = ()
    span_gps_s: tuple[float, float] | None = None
    validity_s: float = 0.0
    epochs: int = 0
    epochs_outside: int = 0

    @property
    def usable(self) -> tuple[str, ...]:
        """Satellites with a position at some of their epochs at least, sorted."""
        return tuple(sorted((*self.covered, *self.partial)))


@dataclass(frozen=True)
class OrbitCoverage:
    """Coverage of an observation file's satellites and epochs by an orbit file.

    Attributes
    ----------
    orbit_path : str
        The orbit file (``'<nominal>'`` or ``''`` for built orbits).
    kind : str
        ``'navigation file'``, ``'SP3 file'`` or ``'orbit'`` (other sources).
    orbit_systems : tuple of str or None
        System letters with ephemerides in the orbit (None when unknown).
    orbit_span_gps_s : tuple of float or None
        First and last reference time over all systems, GPS seconds.
    obs_path : str
        The observation file.
    obs_systems : tuple of str
        System letters of the observation file.
    obs_span_gps_s : tuple of float
        First and last observation epoch, GPS seconds.
    systems : dict of str to SystemCoverage
        Per examined observed system.

    """

    orbit_path: str
    kind: str
    orbit_systems: tuple[str, ...] | None
    orbit_span_gps_s: tuple[float, float] | None
    obs_path: str
    obs_systems: tuple[str, ...]
    obs_span_gps_s: tuple[float, float]
    systems: dict[str, SystemCoverage]

    def _things(self) -> str:
        return "orbits" if self.kind == "SP3 file" else "ephemerides"

    def _a_kind(self) -> str:
        return ("an " if self.kind[0] in "aeiouS" else "a ") + self.kind

    def _day_hint(self) -> str:
        d0, d1 = (gps_s_to_datetime64(t).astype("datetime64[D]") for t in self.obs_span_gps_s)
        doy = int((d0 - d0.astype("datetime64[Y]")).astype(np.int64)) + 1
        if d0 == d1:
            return f"use {self._a_kind()} of the observation day ({d0}, day of year {doy:03d})"
        return f"use {self.kind}s of the observation days ({d0} to {d1})"

    def problem(self, system: str) -> str:
        """Why no observed satellite of a system gets a position ('' when some do).

        Parameters
        ----------
        system : str
            System letter.

        Returns
        -------
        str
            The reason (without the file name prefix), or ``''`` when at least
            one observed satellite has a position or the system was not
            examined or has no observed satellite.

        """
        sc = self.systems.get(system)
        if sc is None or not sc.observed or sc.usable:
            return ""
        name, things = _name(system), self._things()
        observed = ", ".join(self.obs_systems)
        obs_name = Path(self.obs_path).name
        if not sc.in_orbit:
            has = ", ".join(_name(s) for s in self.orbit_systems or ()) or "nothing usable"
            hint = ""
            if system == "R" and self.kind == "navigation file":
                hint = " (a mixed 'MN' file or a RINEX 2 GLONASS '.g' file)"
            seen = (
                f"observed systems: {observed}: "
                if self.obs_systems != (system,)
                else ""  # read for this system only: 'psdbound inspect' lists the file's systems
            )
            return (
                f"the {self.kind} has no {name} {things} (it has {has}); {seen}give "
                f"{self._a_kind()} with {name} {things}{hint} or choose another system"
            )
        o0, o1 = self.obs_span_gps_s
        end = _when(o1)
        obs_span = f"{_when(o0)} to {end[11:] if end[:10] == _when(o0)[:10] else end}"
        if sc.span_gps_s is not None and _outside(sc, self.obs_span_gps_s):
            s0, s1 = sc.span_gps_s
            used = ""
            if sc.validity_s:
                used = (
                    f" ({name} ephemeris reference times, each used up to "
                    f"{_duration(sc.validity_s)} away)"
                )
            return (
                f"the {self.kind} covers {_when(s0)} to {_when(s1)} GPS time{used}; the "
                f"observations of {obs_name} run from {obs_span} GPS time: " + self._day_hint()
            )
        head = (
            f"none of the {len(sc.observed)} {name} satellites observed in {obs_name} "
            f"({' '.join(sc.observed)})"
        )
        if self.kind == "orbit":
            return f"{head} gets a position from the orbit at its observation epochs ({obs_span})"
        if sc.span_gps_s is None:
            return f"{head} has a position: the {self.kind} has no healthy {name} record"
        one = "ephemeris" if things == "ephemerides" else "orbit"
        return (
            f"{head} has a usable {one} in the {self.kind} at its observation epochs "
            f"({obs_span} GPS time); the file's {name} {things} run from "
            f"{_when(sc.span_gps_s[0])} to {_when(sc.span_gps_s[1])} GPS time{_unsupported(sc)}"
        )

    def require(self, system: str) -> None:
        """Raise :class:`~psdbound.errors.InputError` with :meth:`problem`, if any.

        Parameters
        ----------
        system : str
            System letter.

        Raises
        ------
        InputError
            When no observed satellite of the system gets a position; the
            message names the orbit file and says what is wrong.

        """
        reason = self.problem(system)
        if reason:
            raise InputError(reason, path=self.orbit_path or None)

    def warnings(self, system: str | None = None) -> tuple[str, ...]:
        """Satellites without a position when others have one (messages, no file prefix).

        Parameters
        ----------
        system : str, optional
            Only this system (all examined systems by default).

        Returns
        -------
        tuple of str
            One message per system with missing or partly covered satellites
            (none for a system that :meth:`problem` rejects).

        """
        out = []
        for s, sc in self.systems.items():
            if (system is not None and s != system) or not sc.usable:
                continue
            if sc.epochs_outside and sc.span_gps_s is not None:
                a, b = sc.span_gps_s[0] - sc.validity_s, sc.span_gps_s[1] + sc.validity_s
                only = ""
                if sc.outside:
                    only = f"; {' '.join(sc.outside)} observed only then"
                out.append(
                    f"the {self.kind} covers {_when(a)} to {_when(b)} GPS time for {_name(s)}: "
                    f"{sc.epochs_outside} of the {sc.epochs} observation epochs "
                    f"({100 * sc.epochs_outside / max(sc.epochs, 1):.1f} %) lie outside and get "
                    f"no position (no elevation; left out of the arcs){only}"
                )
            if not (sc.missing or sc.partial):
                continue
            parts = []
            if sc.missing:
                parts.append(
                    f"no usable {_name(s)} position for {len(sc.missing)} of the "
                    f"{len(sc.observed)} observed satellites ({' '.join(sc.missing)})"
                )
            if sc.partial:
                few = ", ".join(f"{k} {_share(v)}" for k, v in sorted(sc.partial.items()))
                parts.append(f"positions at only part of their sampled observation epochs ({few})")
            out.append(
                f"the {self.kind} gives " + " and ".join(parts) + f"{_unsupported(sc)}: their "
                "epochs without a position get no elevation and are left out of the arcs"
            )
        return tuple(out)

    def summary(self, *, reasons: bool = True) -> str:
        """Describe the coverage in a few lines (systems, span, satellites without orbit).

        Parameters
        ----------
        reasons : bool, default True
            Add the full reason (:meth:`problem`) under each system without
            any position; False leaves the short one in parentheses only.

        Returns
        -------
        str
            A header line (orbit file, its systems and span) and one line per
            observed system, indented.

        """
        name = Path(self.orbit_path).name or "orbit"
        systems = " ".join(self.orbit_systems) if self.orbit_systems is not None else "?"
        span = ""
        if self.orbit_span_gps_s is not None:
            span = f"; {_when(self.orbit_span_gps_s[0])} to {_when(self.orbit_span_gps_s[1])} GPS"
        lines = [f"orbit {name} ({self.kind}): systems {systems or 'none'}{span}"]
        for s, sc in self.systems.items():
            if not sc.observed:
                continue
            head = (
                f"  {_name(s)}: {len(sc.usable)} of {len(sc.observed)} observed satellites "
                "with a position"
            )
            reason = self.problem(s)
            if reason:
                lines.append(f"{head} ({self._tag(sc)})")
                if reasons:
                    lines.append(f"    -> {reason}")
                continue
            if sc.missing:
                head += f"; none for {' '.join(sc.missing)}"
            if sc.partial:
                head += "; part of the epochs only for " + ", ".join(
                    f"{k} ({_share(v)})" for k, v in sorted(sc.partial.items())
                )
            if sc.epochs_outside:
                head += f"; {sc.epochs_outside} of {sc.epochs} epochs outside the orbit's span"
            lines.append(head)
        return "\n".join(lines)

    def _tag(self, sc: SystemCoverage) -> str:
        """Short reason for a system without any position."""
        if not sc.in_orbit:
            return f"no {sc.system} {self._things()} in the file"
        if _outside(sc, self.obs_span_gps_s):
            return "observations outside the file's time span"
        return "no usable record at the observation epochs"


def _outside(sc: SystemCoverage, obs_span: tuple[float, float]) -> bool:
    """Tell whether the observations lie wholly outside the system's orbit span."""
    if sc.span_gps_s is None:
        return False
    s0, s1 = sc.span_gps_s
    return obs_span[1] < s0 - sc.validity_s or obs_span[0] > s1 + sc.validity_s


def _unsupported(sc: SystemCoverage) -> str:
    """Return a note when missing satellites are BeiDou GEOs (no broadcast model here)."""
    from psdbound.io.ephemeris import is_beidou_geo

    geo = [s for s in sc.missing if is_beidou_geo(s)]
    if not geo:
        return ""
    if len(geo) == 1:
        return f" (the BeiDou GEO satellite {geo[0]} has no broadcast orbit model here)"
    return f" (the BeiDou GEO satellites {' '.join(geo)} have no broadcast orbit model here)"


def _orbit_facts(
    orbit: object, system: str
) -> tuple[bool | None, tuple[float, float] | None, float]:
    """(system in orbit or None if unknown, reference-time span, validity s)."""
    if isinstance(orbit, Navigation):
        t = orbit.reference_times_gps_s(system)
        span = (float(t[0]), float(t[-1])) if t.size else None
        return system in orbit.systems, span, orbit.validity_s(system)
    if isinstance(orbit, PreciseOrbit):
        t = orbit.t_gps_s
        span = (float(t[0]), float(t[-1])) if t.size else None
        return system in orbit.systems, span, 0.0
    return None, None, 0.0


def _sample(mask: NDArray[np.bool_], max_samples: int) -> NDArray[np.intp]:
    idx = np.flatnonzero(mask)
    if idx.size > max_samples:
        idx = np.unique(idx[np.linspace(0, idx.size - 1, max_samples).round().astype(np.intp)])
    return idx


def _sort_satellites(
    orbit: object,
    block: SystemBlock,
    keep: list[int],
    seen: NDArray[np.bool_],
    usable: NDArray[np.bool_],
    t: NDArray[np.float64],
    present: bool | None,
    max_samples: int,
) -> tuple[list[str], list[str], list[str], list[str], dict[str, float]]:
    """Return the observed satellites: covered, missing, outside, and partly covered (fraction)."""
    observed, covered, missing, outside = [], [], [], []
    partial: dict[str, float] = {}
    for i in keep:
        sat = block.sats[i]
        if not seen[:, i].any():
            continue
        observed.append(sat)
        idx = _sample(seen[:, i] & usable, max_samples)
        if present is False:
            missing.append(sat)
            continue
        if idx.size == 0:
            outside.append(sat)
            continue
        pos = np.asarray(orbit.positions_ecef_m(sat, t[idx]))  # type: ignore[attr-defined]
        frac = float(np.isfinite(pos).all(axis=1).mean())
        if frac == 1.0:
            covered.append(sat)
        elif frac == 0.0:
            missing.append(sat)
        else:
            partial[sat] = frac
    return observed, covered, missing, outside, partial


def _system_coverage(
    orbit: object,
    obs: Observations,
    system: str,
    satellites: Sequence[str] | None,
    max_samples: int,
) -> tuple[SystemCoverage, tuple[float, float] | None]:
    """Return how the orbit covers one system's observed satellites, and its span (GPS s)."""
    t = obs.t_gps_s
    block = obs.blocks[system]
    present, span, validity = _orbit_facts(orbit, system)
    seen = np.isfinite(block.values).any(axis=2)  # (epoch, sat)
    keep = [i for i, sat in enumerate(block.sats) if satellites is None or sat in satellites]
    any_seen = seen[:, keep].any(axis=1)
    inside = np.ones(t.shape[0], dtype=bool)
    if span is not None:
        inside = (t >= span[0] - validity) & (t <= span[1] + validity)
    observed, covered, missing, outside, partial = _sort_satellites(
        orbit, block, keep, seen, inside, t, present, max_samples
    )
    cov = SystemCoverage(
        system=system,
        in_orbit=present is not False,
        observed=tuple(sorted(observed)),
        covered=tuple(sorted(covered)),
        partial=partial,
        missing=tuple(sorted(missing)),
        outside=tuple(sorted(outside)),
        span_gps_s=span,
        validity_s=validity,
        epochs=int(any_seen.sum()),
        epochs_outside=int((any_seen & ~inside).sum()) if present is not False else 0,
    )
    return cov, span


def _whole_spans(orbit: object) -> list[tuple[float, float]]:
    """Return the time spans (GPS s) of all the orbit's epochs or reference times, per system."""
    spans = []
    if isinstance(orbit, PreciseOrbit) and orbit.t_gps_s.size:
        spans.append((float(orbit.t_gps_s[0]), float(orbit.t_gps_s[-1])))
    elif isinstance(orbit, Navigation):
        for s in orbit.systems:
            tr = orbit.reference_times_gps_s(s)
            if tr.size:
                spans.append((float(tr[0]), float(tr[-1])))
    return spans


def orbit_coverage(
    orbit: object,
    obs: Observations,
    systems: str | Sequence[str] | None = None,
    *,
    satellites: Sequence[str] | None = None,
    max_samples: int = MAX_SAMPLES,
) -> OrbitCoverage:
    """Tell which observed satellites an orbit gives positions for, at their epochs.

    Parameters
    ----------
    orbit : Navigation, PreciseOrbit or OrbitSource
        Anything with ``positions_ecef_m(sat, t_gps_s)``; broadcast and SP3
        orbits also give their systems and time span for the messages.
    obs : Observations
        The observations.
    systems : str or sequence of str, optional
        Observed systems to examine (``'G'``, ``'GE'``); all by default.
        Letters the observations lack are ignored.
    satellites : sequence of str, optional
        Examine only these satellites.
    max_samples : int, optional
        Observation epochs per satellite at which the orbit is evaluated.

    Returns
    -------
    OrbitCoverage
        Per-system counts, with :meth:`~OrbitCoverage.problem`,
        :meth:`~OrbitCoverage.require`, :meth:`~OrbitCoverage.warnings` and
        :meth:`~OrbitCoverage.summary`.

    Examples
    --------
    >>> cov = orbit_coverage(read_orbit(nav_path), read_obs(obs_path), "G")  # doctest: +SKIP
    >>> cov.require("G")  # InputError when the file is of another day  # doctest: +SKIP

    """
    t = obs.t_gps_s
    wanted = obs.systems if systems is None else tuple(s for s in systems if s in obs.blocks)
    orbit_systems: tuple[str, ...] | None = None
    if isinstance(orbit, (Navigation, PreciseOrbit)):
        orbit_systems = orbit.systems
    per: dict[str, SystemCoverage] = {}
    spans = []
    for system in wanted:
        per[system], span = _system_coverage(orbit, obs, system, satellites, max_samples)
        if span is not None:
            spans.append(span)
    spans += _whole_spans(orbit)
    kind = {Navigation: "navigation file", PreciseOrbit: "SP3 file"}.get(type(orbit), "orbit")
    path = getattr(orbit, "path", "")
    return OrbitCoverage(
        orbit_path=str(path) if path else "",
        kind=kind,
        orbit_systems=orbit_systems,
        orbit_span_gps_s=(min(s[0] for s in spans), max(s[1] for s in spans)) if spans else None,
        obs_path=str(obs.path),
        obs_systems=obs.systems,
        obs_span_gps_s=(float(t[0]), float(t[-1])) if t.size else (float("nan"),) * 2,
        systems=per,
    )
