"""The broadcast records a simulation is computed from, checked before anything is written.

Either the nominal constellation over the simulated span, or the scenario's
navigation file (``nav_path``, ``--nav``). A file must hold healthy records
of every simulated system, valid (within
:meth:`~psdbound.io.nav.Navigation.validity_s`, 4 h, of their reference
time) during at least part of the simulation; otherwise the simulation
would have no satellite to simulate, and :func:`scenario_navigation`
refuses it with one line naming the file, what it holds, the simulation's
span and what to do. A file that covers only part of the span, or holds
systems that are not simulated, is used with a warning.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from psdbound.common.notices import warn
from psdbound.errors import InputError
from psdbound.io.nav import Navigation, read_nav
from psdbound.io.nominal import nominal_navigation
from psdbound.io.obs import SYSTEM_NAMES
from psdbound.io.timescales import gps_s_to_datetime64
from psdbound.simulate.scenario import Scenario

__all__ = ["scenario_navigation"]

#: The systems the simulator writes (signals of GPS L1C/L2W and Galileo L1C/L5Q).
SIMULATED_SYSTEMS = ("G", "E")
_HOUR_S = 3600.0
_DAY_S = 86400.0


def scenario_navigation(sc: Scenario, t_gps_s: NDArray[np.float64]) -> Navigation:
    """Return the broadcast records the scenario is simulated from, checked against its span.

    Parameters
    ----------
    sc : Scenario
        The scenario (``systems``, ``nav_path``, ``seed``).
    t_gps_s : ndarray of float64
        The simulated epochs, GPS seconds (ascending).

    Returns
    -------
    Navigation
        The nominal constellation of ``sc.systems`` over the epochs when
        ``sc.nav_path`` is None, else the file's records.

    Raises
    ------
    InputError
        The file cannot be read, has no record of a simulated system, or
        none of its records of a simulated system is healthy and valid at
        any simulated epoch. Nothing is written by this check.

    Warns
    -----
    PsdboundWarning
        When the file holds systems that are not simulated, or its records
        of a simulated system leave some epochs without a valid record (no
        satellite of that system is simulated there).
    """
    t0, t_end = float(t_gps_s[0]), float(t_gps_s[-1])
    if sc.nav_path is None:
        return nominal_navigation(t0, t_end, systems=sc.systems, clock_seed=sc.seed)
    nav = read_nav(sc.nav_path)
    _check_systems(sc, nav)
    for system in sc.systems:
        _check_coverage(sc, nav, system, t_gps_s)
    return nav


def _names(systems: str | tuple[str, ...]) -> str:
    return ", ".join(SYSTEM_NAMES.get(s, s) for s in systems) or "no system"


def _check_systems(sc: Scenario, nav: Navigation) -> None:
    """Refuse a file without records of a simulated system; warn about systems not simulated."""
    missing = [s for s in sc.systems if s not in nav.ephemerides]
    if missing:
        usable = "".join(s for s in SIMULATED_SYSTEMS if s in nav.ephemerides)
        instead = (
            f'simulate what it holds (systems = "{usable}" in a --scenario file), '
            if usable
            else ""
        )
        raise InputError(
            f"the navigation file has no {_names(tuple(missing))} ephemerides, but the "
            f"simulation is of {_names(sc.systems)} (the file holds {_names(nav.systems)}); "
            f"give a navigation file with {_names(tuple(missing))} records, {instead}or leave "
            "out --nav to simulate the nominal constellation (nothing was written)",
            path=sc.nav_path,
        )
    others = [s for s in nav.systems if s not in sc.systems]
    if others:
        warn(
            f"its {_names(tuple(others))} records are not simulated: the simulation is of "
            f"{_names(sc.systems)} (the simulator does GPS and Galileo, chosen by systems in "
            "a --scenario file)",
            path=sc.nav_path,
        )


def _label(t_gps_s: float) -> str:
    """Return the ISO label of a GPS time, to the second (``2024-05-06T00:00:00``)."""
    return str(gps_s_to_datetime64(t_gps_s).astype("datetime64[s]"))


def _covered(
    toe: NDArray[np.float64], t: NDArray[np.float64], validity_s: float
) -> NDArray[np.bool_]:
    """Return True where a time of ``toe`` (sorted, not empty) lies within ``validity_s``, s."""
    k = np.searchsorted(toe, t)
    before = np.abs(t - toe[np.clip(k - 1, 0, toe.size - 1)])
    after = np.abs(toe[np.clip(k, 0, toe.size - 1)] - t)
    return np.minimum(before, after) <= validity_s


def _records_text(toe: NDArray[np.float64], validity_s: float) -> str:
    """Return ``2024-05-06 (reference times A to B GPS, each valid 4 h)``: the file's span."""
    days, counts = np.unique(np.floor(toe / _DAY_S), return_counts=True)
    day = _label(days[np.argmax(counts)] * _DAY_S)[:10]
    return (
        f"{day} (reference times {_label(toe[0])} to {_label(toe[-1])} GPS, each valid "
        f"{validity_s / _HOUR_S:g} h)"
    )


def _suggested_start(toe: NDArray[np.float64], validity_s: float) -> str:
    """Return a start the file covers: midnight of its main day, or its first valid whole hour."""
    days, counts = np.unique(np.floor(toe / _DAY_S), return_counts=True)
    first = np.ceil((toe[0] - validity_s) / _HOUR_S) * _HOUR_S
    return _label(max(days[np.argmax(counts)] * _DAY_S, first))


def _check_coverage(sc: Scenario, nav: Navigation, system: str, t: NDArray[np.float64]) -> None:
    """Refuse records of ``system`` valid at no simulated epoch; warn when only at some."""
    name = SYSTEM_NAMES[system]
    toe = nav.reference_times_gps_s(system)
    span = f"{_label(t[0])} to {_label(t[-1])} GPS"
    if toe.size == 0:
        raise InputError(
            f"the navigation file has no healthy {name} record (all "
            f"{len(nav.ephemerides[system].sat)} are flagged unhealthy); give another "
            "navigation file, or leave out --nav to simulate the nominal constellation "
            "(nothing was written)",
            path=sc.nav_path,
        )
    validity = nav.validity_s(system)
    covered = _covered(toe, t, validity)
    if covered.all():
        return
    held = _records_text(toe, validity)
    if not covered.any():
        raise InputError(
            f"the navigation file has no {name} record valid during the simulation ({span}): "
            f"its records are of {held}; give a --start the file covers (e.g. --start "
            f"{_suggested_start(toe, validity)}) or a navigation file of {_label(t[0])[:10]} "
            "(nothing was written)",
            path=sc.nav_path,
        )
    warn(
        f"its {name} records, of {held}, are valid at only {100 * covered.mean():.1f} % of the "
        f"simulated epochs ({span}): no {name} satellite is simulated at the other "
        f"{int((~covered).sum())} epochs; give a --start and --duration-h the file covers, or a "
        "navigation file of the whole span",
        path=sc.nav_path,
    )
