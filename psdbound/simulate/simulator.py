"""Carrier-phase and code observation simulator with ground truth (docs/method/isolation.rst).

For antenna ``a``, satellite ``s`` and signal ``f`` (phase in metres)::

    phi = rho + c (dt_rx - dt_sat) + T - I_f + lambda_f N_f + nu_f
    P   = rho + c (dt_rx - dt_sat) + T + I_f + code noise

* ``rho``: geometric range from the broadcast records written to the
  navigation file (light time and Earth rotation, as the reader computes it);
  epochs are receiver-clock labels, the geometry is evaluated at the true
  receive time ``t - dt_rx``.
* ``dt_rx``: receiver clock (offset + drift); ``dt_sat``: satellite clock
  from the records.
* ``T``: zenith delay / sin(el) (common to both carriers).
* ``I_f = 40.3 STEC / f^2``: smooth diurnal vertical TEC (peak 14 h local
  time) plus a travelling disturbance, times a thin-shell (350 km)
  obliquity factor.
* ``N_f``: random integer ambiguity per satellite and carrier, changed by
  cycle slips (1-3 cycles on one carrier; a set fraction flagged by LLI).
* ``nu_f``: the truth error: ``m(el) (GM + WN) + reflections + noise`` (see
  :class:`~psdbound.simulate.scenario.MultipathModel`); with two antennas a
  fraction of the GM+WN variance is common to both.
* SNR, dB-Hz: ``30 + 20 sin(el)`` clipped to 20-55 (3 dB lower on the
  second carrier), plus, per reflection of amplitude ratio ``alpha``,
  ``10 log10(1 + alpha^2 + 2 alpha cos psi)``: the power of the direct and
  reflected signals' sum, with the same phase ``psi`` per carrier as the
  reflection's phase error, so GNSS-IR (:mod:`psdbound.validation.reflectors`)
  sees the reflector the phase has. Signal strength indicators follow the
  direct SNR.

Satellites are tracked above the elevation mask; tracking gaps are drawn at
a set rate. Everything random comes from one seeded generator, so the same
scenario gives byte-identical files.
"""

from __future__ import annotations

import gzip
import json
import math
import os
import shutil
import tempfile
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.signal import lfilter

from psdbound.common.atomic import atomic_write_bytes
from psdbound.constants import SPEED_OF_LIGHT_M_S
from psdbound.errors import InputError, NoDataError
from psdbound.io.geometry import azimuth_elevation, enu_rotation, geodetic_to_ecef, signal_path
from psdbound.io.nav import Navigation, read_nav
from psdbound.io.obs import SYSTEM_NAMES, Observations, ObsHeader, SystemBlock
from psdbound.io.signals import carrier_frequency_hz, wavelength_m
from psdbound.io.write import format_nav_v3, write_obs_v3
from psdbound.screening.plausibility import multipath_limit_m
from psdbound.simulate.navigation import scenario_navigation
from psdbound.simulate.scenario import MultipathModel, Scenario
from psdbound.version import __version__

__all__ = ["SimulationResult", "simulate", "gauss_markov", "multipath_limit_problem"]

SIGNALS = {"G": ("L1C", "L2W"), "E": ("L1C", "L5Q")}
CODES = {"G": ("C1C", "C2W"), "E": ("C1C", "C5Q")}
SNR = {"G": ("S1C", "S2W"), "E": ("S1C", "S5Q")}
_R_EARTH_M = 6371e3
_SHELL_M = 350e3


@dataclass(frozen=True)
class SimulationResult:
    """Files written by :func:`simulate` and the truth in memory.

    Attributes
    ----------
    scenario : Scenario
        The parameters.
    obs_paths : tuple of Path
        RINEX 3 observation file(s): antenna A (and B).
    nav_path : Path
        RINEX 3 navigation file.
    truth_path, truth_json_path : Path
        Truth per epoch, satellite, antenna (CSV, gzip) and parameters (JSON).
    t_gps_s : ndarray
        Epochs, GPS seconds.
    sats : tuple of str
        Satellites (axis 1 of the truth arrays).
    truth_m : ndarray, shape (n_antenna, n_epoch, n_sat, 2)
        Truth error ``nu`` per signal (NaN where not tracked), metres.
    elevation_deg : ndarray, shape (n_antenna, n_epoch, n_sat)
        Elevations, degrees.
    slips : list of dict
        Injected cycle slips (sat, antenna, t_gps_s, signal, cycles, flagged).
    """

    scenario: Scenario
    obs_paths: tuple[Path, ...]
    nav_path: Path
    truth_path: Path
    truth_json_path: Path
    t_gps_s: NDArray[np.float64]
    sats: tuple[str, ...]
    truth_m: NDArray[np.float64]
    elevation_deg: NDArray[np.float64]
    slips: list[dict]


def gauss_markov(
    n: int, sigma: float, tau_s: float, dt_s: float, rng: np.random.Generator, size: int = 1
) -> NDArray[np.float64]:
    """Stationary first-order Gauss-Markov sequences (exact discretisation).

    Parameters
    ----------
    n : int
        Samples per sequence.
    sigma : float
        Standard deviation.
    tau_s, dt_s : float
        Time constant and sampling interval, seconds.
    rng : numpy.random.Generator
        Random source.
    size : int, default 1
        Number of independent sequences.

    Returns
    -------
    ndarray, shape (n, size)
        ``x[k] = phi x[k-1] + w[k]``, ``phi = exp(-dt/tau)``, started in the
        stationary distribution.
    """
    phi = np.exp(-dt_s / tau_s)
    w = rng.normal(0.0, sigma * np.sqrt(1.0 - phi**2), (n, size))
    w[0] = rng.normal(0.0, sigma, size)
    return lfilter([1.0], [1.0, -phi], w, axis=0)


def _start_gps_s(label: str) -> float:
    try:
        t = np.datetime64(label, "ns")
    except ValueError:
        raise InputError(f"start epoch {label!r} is not an ISO date-time") from None
    return float((t - np.datetime64("1980-01-06T00:00:00", "ns")) / np.timedelta64(1, "s"))


def _obliquity(el_deg: NDArray[np.float64]) -> NDArray[np.float64]:
    c = _R_EARTH_M * np.cos(np.radians(el_deg)) / (_R_EARTH_M + _SHELL_M)
    return 1.0 / np.sqrt(1.0 - c**2)


def _reflection_psi(kind: str, d_m: float, el_deg, lam_m):
    """Phase of the reflected signal relative to the direct one, rad.

    Path delay ``2 d sin(el)`` for a ground reflector ``d`` metres below the
    antenna, ``2 d cos(el)`` for a wall ``d`` metres away.
    """
    el = np.radians(el_deg)
    delta = 2.0 * d_m * (np.sin(el) if kind == "ground" else np.cos(el))
    return 2.0 * np.pi * delta / lam_m


def _reflection_m(kind: str, d_m: float, alpha: float, el_deg, lam_m: float):
    psi = _reflection_psi(kind, d_m, el_deg, lam_m)
    return np.arctan2(alpha * np.sin(psi), 1.0 + alpha * np.cos(psi)) * lam_m / (2.0 * np.pi)


def _reflection_snr_db(reflections, el_deg, lams) -> NDArray[np.float64]:
    """SNR change of the reflections per carrier, dB, shape ``el_deg.shape + (2,)``.

    Each reflection multiplies the power by ``|1 + alpha e^{i psi}|^2 = 1 +
    alpha^2 + 2 alpha cos psi`` with the ``psi`` of :func:`_reflection_m`;
    ``el_deg`` is (epochs, sats), ``lams`` (sats, 2) wavelengths in metres.
    """
    out = np.zeros((*np.shape(el_deg), 2))
    for refl in reflections:
        for f in range(2):
            psi = _reflection_psi(refl.kind, refl.distance_m, el_deg, lams[None, :, f])
            out[..., f] += 10.0 * np.log10(1.0 + refl.alpha**2 + 2.0 * refl.alpha * np.cos(psi))
    return out


def _disturbance_tecu(sc: Scenario, t_rel_s: np.ndarray, sats: list[str]) -> np.ndarray:
    """Slant-TEC random walks of the scenario's disturbances, TECU, shape (epochs, sats)."""
    out = np.zeros((t_rel_s.size, len(sats)))
    if not sc.disturbances:
        return out
    rng = np.random.default_rng([sc.seed, 0x10])  # own stream: other draws unchanged
    for d in sc.disturbances:
        inside = (t_rel_s >= d.start_s) & (t_rel_s < d.start_s + d.duration_s)
        step = 0.5 * d.roti_tecu_min * np.sqrt(sc.interval_s / 30.0)
        for j, sat in enumerate(sats):
            if d.sats and sat not in d.sats:
                continue
            inc = np.where(inside, rng.normal(0.0, step, t_rel_s.size), 0.0)
            out[:, j] += np.cumsum(inc)
    return out


def _below(mp: MultipathModel, ratio: float) -> str:
    """Where the mapping exceeds ``ratio`` (limit / zenith sigma): 'below X deg' or 'at every'."""
    if ratio <= mp.a:
        return "at every elevation"
    if mp.b <= 0 or ratio >= mp.a + mp.b:
        return ""
    return f"below {mp.c_deg * math.sqrt(2.0 * math.log(mp.b / (ratio - mp.a))):.1f} deg"


def multipath_limit_problem(sc: Scenario, label: str = "multipath") -> str:
    """Say whether the injected multipath breaks the carrier-multipath limit at low elevation.

    The standard deviation of the injected error of a signal is
    ``m(el) sqrt(sigma_gm^2 + sigma_wn^2)``; carrier multipath cannot exceed a
    quarter of the wavelength (:func:`psdbound.screening.multipath_limit_m`).
    It is checked at the elevation mask, the lowest simulated elevation,
    against the shortest carrier simulated (L1: 4.76 cm).

    Parameters
    ----------
    sc : Scenario
        The scenario to simulate.
    label : str, default "multipath"
        How the message names the option that set the multipath.

    Returns
    -------
    str
        One line naming ``label``, the elevation and the value against the
        limit, and what to do; ``''`` when the multipath is within the limit.
    """
    mp = sc.multipath
    el = sc.elevation_mask_deg
    sigma = mp.factor(el) * math.hypot(mp.sigma_gm_m, mp.sigma_wn_m)
    limit, system, code = min(
        (multipath_limit_m([wavelength_m(f"{s}01", c)], 1.0), s, c)
        for s in sc.systems
        for c in SIGNALS[s]
    )
    if not sigma > limit:
        return ""
    where = _below(mp, limit / math.hypot(mp.sigma_gm_m, mp.sigma_wn_m))
    return (
        f"{label}: at {el:g} deg elevation (the elevation mask) the mapped multipath sigma is "
        f"{100 * sigma:.2f} cm, beyond the carrier-multipath limit {100 * limit:.2f} cm (a "
        f"quarter of the {SYSTEM_NAMES[system]} {code} wavelength); {where} the simulated "
        "carrier error is not physical multipath: lower sigma_gm_m/sigma_wn_m or the mapping, "
        "or raise elevation_mask_deg"
    )


def simulate(scenario: Scenario, out_dir: str | os.PathLike[str]) -> SimulationResult:
    """Simulate a data set and write it as real files.

    Every input is checked before anything is written (the navigation file
    against the simulated systems and span);
    the files are built in a hidden folder inside ``out_dir`` and moved in
    when all are complete, so a failure leaves ``out_dir`` as it was.

    Parameters
    ----------
    scenario : Scenario
        All parameters, including the seed.
    out_dir : str or path-like
        Destination folder (created). Files: ``<name>-A_MO.rnx.gz``
        (``-B`` for the second antenna), ``<name>_MN.rnx.gz``,
        ``<name>_truth.csv.gz`` and ``<name>_truth.json``; files of those
        names already there are replaced (and an earlier ``<name>-B`` file
        removed when only antenna A is simulated), nothing else is touched.

    Returns
    -------
    SimulationResult
        Paths and the truth arrays.

    Raises
    ------
    InputError
        A start epoch that cannot be read, a duration shorter than the
        sampling interval, a navigation file without usable records of a
        simulated system during the simulation, or no satellite of a
        simulated system tracked at any epoch (nothing is written).

    See Also
    --------
    psdbound.simulate.preset : The named scenarios (``demo``, ``short``).
    psdbound.simulate.compare_to_truth : A fit against the injected truth.

    References
    ----------
    .. [1] docs/method/isolation.rst (the observation equations simulated).

    Examples
    --------
    >>> import tempfile
    >>> from psdbound.simulate import preset
    >>> sc = preset("demo").replace(name="tiny", duration_s=600.0, dual_antenna=False)
    >>> out = simulate(sc, tempfile.mkdtemp())
    >>> [p.name for p in out.obs_paths]
    ['tiny-A_MO.rnx.gz']
    """
    sc = scenario
    t = _epochs(sc)
    nav_src = scenario_navigation(sc, t)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{sc.name}-simulate-", dir=out))
    try:
        res = _simulate_into(sc, nav_src, t, tmp)
        for name in sorted(os.listdir(tmp)):
            os.replace(tmp / name, out / name)
        if not sc.dual_antenna:  # an earlier dual-antenna run's B is not of this simulation
            (out / f"{sc.name}-B_MO.rnx.gz").unlink(missing_ok=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return replace(
        res,
        obs_paths=tuple(out / p.name for p in res.obs_paths),
        nav_path=out / res.nav_path.name,
        truth_path=out / res.truth_path.name,
        truth_json_path=out / res.truth_json_path.name,
    )


def _epochs(sc: Scenario) -> NDArray[np.float64]:
    """Return the simulated epochs (receiver-clock labels), GPS seconds."""
    t0 = _start_gps_s(sc.start_gps)
    n = int(round(sc.duration_s / sc.interval_s))
    if n < 1:
        raise InputError(
            f"the duration ({sc.duration_s:g} s) is shorter than the sampling interval "
            f"({sc.interval_s:g} s): no epoch to simulate; lengthen --duration-h or shorten "
            "--interval-s"
        )
    return t0 + sc.interval_s * np.arange(n)


def _simulate_into(
    sc: Scenario, nav_src: Navigation, t: NDArray[np.float64], out: Path
) -> SimulationResult:
    """Simulate from the checked records ``nav_src`` at epochs ``t``; write the files in ``out``."""
    rng = np.random.default_rng(sc.seed)
    nav_path, nav = _write_navigation(sc, out, nav_src)
    sim = _Simulation.start(sc, nav, t, float(t[0]), rng)
    sim.geometry(nav)
    sim.add_gaps(rng)
    sim.check_tracked()
    sim.add_truth_error(rng)
    sim.add_atmosphere(rng)
    slips = sim.add_ambiguities(rng)

    # assemble observations per antenna
    obs_paths = []
    for a in range(len(sim.antennas)):
        p = out / f"{sc.name}-{'AB'[a]}_MO.rnx.gz"
        write_obs_v3(p, sim.observations(a, rng, str(out)), program=f"psdbound {__version__}")
        obs_paths.append(p)
        sim.truth[a][~sim.tracked] = np.nan
        sim.el[a][~sim.tracked] = np.nan

    truth_path = out / f"{sc.name}_truth.csv.gz"
    _write_truth_csv(truth_path, t, sim.sats, sim.truth, sim.el)
    truth_json = out / f"{sc.name}_truth.json"
    meta = {
        "scenario": sc.to_dict(),
        "seed": sc.seed,
        "digest": sc.digest(),
        "psdbound_version": __version__,
        "signals": {s: list(SIGNALS[s]) for s in sc.systems},
        "truth_definition": "nu = m(el) (GM + WN) + reflections + receiver noise, per signal, m",
        "df_truth": "(nu_1 - nu_2) / sqrt(2)",
        "da_truth": "((nu_A,i - nu_B,i) - (nu_A,r - nu_B,r)) / 2",
        "antenna_positions_m": [list(map(float, p)) for p in sim.antennas],
        "receiver_clock_drift_s_s": [float(d) for d in sim.drift],
        "slips": slips,
        "files": {
            "obs": [p.name for p in obs_paths],
            "nav": nav_path.name,
            "truth": truth_path.name,
        },
    }
    _write_gz(truth_json, json.dumps(meta, indent=1, sort_keys=True) + "\n", compress=False)
    return SimulationResult(
        scenario=sc,
        obs_paths=tuple(obs_paths),
        nav_path=nav_path,
        truth_path=truth_path,
        truth_json_path=truth_json,
        t_gps_s=t,
        sats=sim.sats,
        truth_m=sim.truth,
        elevation_deg=sim.el,
        slips=slips,
    )


def _write_navigation(sc: Scenario, out: Path, nav_src: Navigation) -> tuple[Path, Navigation]:
    """Write the navigation file and read it back: the simulation uses what readers see."""
    nav_path = out / f"{sc.name}_MN.rnx.gz"
    text = format_nav_v3(nav_src, program=f"psdbound {__version__}")
    _write_gz(nav_path, text)
    return nav_path, read_nav(nav_path)


@dataclass
class _Simulation:
    """The simulated quantities, filled stage by stage (metres, seconds, degrees).

    Array axes: antenna, epoch, satellite, signal (as many as apply).
    """

    sc: Scenario
    t: NDArray[np.float64]
    t0: float
    antennas: list[NDArray[np.float64]]
    header_error: NDArray[np.float64]
    sats: tuple[str, ...]
    clock0: NDArray[np.float64]
    drift: NDArray[np.float64]
    lams: NDArray[np.float64]
    rho: NDArray[np.float64] = field(init=False)
    el: NDArray[np.float64] = field(init=False)
    dts: NDArray[np.float64] = field(init=False)
    tracked: NDArray[np.bool_] = field(init=False)
    m_el: NDArray[np.float64] = field(init=False)
    truth: NDArray[np.float64] = field(init=False)
    iono: NDArray[np.float64] = field(init=False)
    tropo: NDArray[np.float64] = field(init=False)
    amb_t: NDArray[np.float64] = field(init=False)
    lli: NDArray[np.int8] = field(init=False)

    @classmethod
    def start(
        cls,
        sc: Scenario,
        nav: Navigation,
        t: NDArray[np.float64],
        t0: float,
        rng: np.random.Generator,
    ) -> _Simulation:
        """Place the antennas, choose the satellites, draw the receiver clock drifts."""
        rx_a = geodetic_to_ecef(sc.lat_deg, sc.lon_deg, sc.height_m)
        rot_t = enu_rotation(sc.lat_deg, sc.lon_deg).T
        rx_b = rx_a + rot_t @ np.asarray(sc.baseline_enu_m, float)
        antennas = [rx_a, rx_b] if sc.dual_antenna else [rx_a]
        header_error = enu_rotation(sc.lat_deg, sc.lon_deg).T @ np.asarray(
            sc.header_error_enu_m, float
        )
        sats = tuple(s for s in nav.satellites if s[0] in sc.systems)
        clock0 = np.asarray(sc.receiver_clock_s, float)
        drift = rng.uniform(-2e-10, 2e-10, 2)
        lams = np.array(
            [[SPEED_OF_LIGHT_M_S / carrier_frequency_hz(s, c) for c in SIGNALS[s[0]]] for s in sats]
        )
        return cls(sc, t, t0, antennas, header_error, sats, clock0, drift, lams)

    def geometry(self, nav: Navigation) -> None:
        """Ranges and elevations at the true receive times, satellite clocks, tracked epochs."""
        t, t0, sats = self.t, self.t0, self.sats
        n_ant, n, ns = len(self.antennas), t.size, len(sats)
        self.rho = np.full((n_ant, n, ns), np.nan)
        self.el = np.full((n_ant, n, ns), np.nan)
        self.dts = np.full((n, ns), np.nan)
        for a, rx in enumerate(self.antennas):
            t_true = t - (self.clock0[a] + self.drift[a] * (t - t0))
            for j, s in enumerate(sats):
                r, tau, sv = signal_path(nav, s, t_true, rx)
                self.rho[a, :, j] = r
                self.el[a, :, j] = azimuth_elevation(rx, sv)[1]
                if a == 0:
                    self.dts[:, j] = nav.satellite_clock_s(s, t_true - tau)
        self.tracked = self.el[0] >= self.sc.elevation_mask_deg
        for a in range(1, n_ant):
            self.tracked &= self.el[a] >= self.sc.elevation_mask_deg

    def add_gaps(self, rng: np.random.Generator) -> None:
        """Tracking gaps: per satellite, Poisson count over the span, random lengths."""
        sc = self.sc
        n = self.t.size
        for j in range(len(self.sats)):
            k = rng.poisson(sc.gap_rate_per_h * sc.duration_s / 3600.0)
            for _ in range(k):
                i0 = rng.integers(0, n)
                length = max(1, int(rng.uniform(sc.interval_s, sc.gap_max_s) / sc.interval_s))
                self.tracked[i0 : i0 + length, j] = False

    def check_tracked(self) -> None:
        """Refuse a simulation in which a simulated system is tracked at no epoch.

        Raises
        ------
        NoDataError
            No satellite of a simulated system above the elevation mask
            (outside the tracking gaps) at any epoch: its observation file
            would hold nothing.
        """
        sc = self.sc
        for system in sc.systems:
            cols = [j for j, s in enumerate(self.sats) if s[0] == system]
            if cols and self.tracked[:, cols].any():
                continue
            source = f"of {sc.nav_path} " if sc.nav_path else ""
            raise NoDataError(
                f"no {SYSTEM_NAMES[system]} satellite {source}is above the elevation mask "
                f"({sc.elevation_mask_deg:g} deg) of the antennas at {sc.lat_deg:g}, "
                f"{sc.lon_deg:g} deg at any epoch from {sc.start_gps} for {sc.duration_s:g} s; "
                "lengthen --duration-h, change --start or lower elevation_mask_deg (nothing "
                "was written)"
            )

    def add_truth_error(self, rng: np.random.Generator) -> None:
        """Truth error per antenna, epoch, satellite and signal, metres."""
        sc, mp, el = self.sc, self.sc.multipath, self.el
        n_ant, n, ns = len(self.antennas), self.t.size, len(self.sats)
        self.m_el = mp.a + mp.b * np.exp(-(el**2) / (2.0 * mp.c_deg**2))
        rho_c = sc.common_fraction if n_ant == 2 else 0.0
        common = gauss_markov(n, mp.sigma_gm_m, mp.tau_s, sc.interval_s, rng, ns * 2)
        common += rng.normal(0.0, mp.sigma_wn_m, common.shape)
        truth = np.empty((n_ant, n, ns, 2))
        for a in range(n_ant):
            own = gauss_markov(n, mp.sigma_gm_m, mp.tau_s, sc.interval_s, rng, ns * 2)
            own += rng.normal(0.0, mp.sigma_wn_m, own.shape)
            stoch = (np.sqrt(rho_c) * common + np.sqrt(1.0 - rho_c) * own).reshape(n, ns, 2)
            truth[a] = self.m_el[a][:, :, None] * stoch
            for refl in mp.reflections:
                for f in range(2):
                    truth[a, :, :, f] += _reflection_m(
                        refl.kind, refl.distance_m, refl.alpha, el[a], self.lams[None, :, f]
                    )
            truth[a] += rng.normal(0.0, sc.receiver_noise_m, (n, ns, 2))
        self.truth = truth

    def add_atmosphere(self, rng: np.random.Generator) -> None:
        """Ionosphere (L1-equivalent delay scaled per carrier) and troposphere, metres."""
        sc, t, t0, el, sats = self.sc, self.t, self.t0, self.el, self.sats
        local_h = ((t - t0) / 3600.0 + float(sc.start_gps[11:13]) + sc.lon_deg / 15.0) % 24.0
        vtec = sc.vtec_night_tecu + (sc.vtec_day_tecu - sc.vtec_night_tecu) * 0.5 * (
            1.0 + np.cos(2.0 * np.pi * (local_h - 14.0) / 24.0)
        )
        tid_phase = rng.uniform(0.0, 2.0 * np.pi, len(sats))
        stec = (
            vtec[None, :, None]
            + sc.tid_amplitude_tecu
            * np.sin(
                2.0 * np.pi * (t - t0)[None, :, None] / sc.tid_period_s + tid_phase[None, None, :]
            )
        ) * _obliquity(el)
        stec = stec + _disturbance_tecu(sc, t - t0, sats)[None, :, :]
        freqs = np.array([[carrier_frequency_hz(s, c) for c in SIGNALS[s[0]]] for s in sats])
        self.iono = 40.3e16 * stec[..., None] / freqs[None, None, :, :] ** 2
        self.tropo = sc.zenith_tropo_m / np.sin(np.radians(np.clip(el, 1.0, 90.0)))

    def add_ambiguities(self, rng: np.random.Generator) -> list[dict]:
        """Integer ambiguities (cycles) changed by cycle slips; return the slips."""
        sc, t, sats = self.sc, self.t, self.sats
        n_ant, n, ns = len(self.antennas), t.size, len(sats)
        amb = rng.integers(-2_000_000, 2_000_000, (n_ant, ns, 2)).astype(float)
        self.amb_t = np.broadcast_to(amb[:, None, :, :], (n_ant, n, ns, 2)).copy()
        self.lli = np.zeros((n_ant, n, ns, 2), dtype=np.int8)
        slips = []
        for a in range(n_ant):
            for j in range(ns):
                for _ in range(rng.poisson(sc.slip_rate_per_h * sc.duration_s / 3600.0)):
                    slips.append(self._slip(a, j, rng))
        return slips

    def _slip(self, a: int, j: int, rng: np.random.Generator) -> dict:
        """Draw one cycle slip of antenna ``a``, satellite ``j`` and apply it."""
        i0 = int(rng.integers(1, self.t.size))
        f = int(rng.integers(0, 2))
        cycles = int(rng.choice([-3, -2, -1, 1, 2, 3]))
        flagged = bool(rng.random() < self.sc.slip_lli_fraction)
        self.amb_t[a, i0:, j, f] += cycles
        if flagged:
            self.lli[a, i0, j, f] = 1
        return {
            "antenna": "AB"[a],
            "sat": self.sats[j],
            "t_gps_s": float(self.t[i0]),
            "signal": SIGNALS[self.sats[j][0]][f],
            "cycles": cycles,
            "flagged": flagged,
        }

    def observations(self, a: int, rng: np.random.Generator, path: str) -> Observations:
        """Antenna ``a``'s observations: code (m), phase (cycles), SNR (dB-Hz) per system."""
        sc, mp, t, t0, el = self.sc, self.sc.multipath, self.t, self.t0, self.el
        n, ns = t.size, len(self.sats)
        clock_m = SPEED_OF_LIGHT_M_S * (self.clock0[a] + self.drift[a] * (t - t0))
        common_m = self.rho[a] + clock_m[:, None] - SPEED_OF_LIGHT_M_S * self.dts + self.tropo[a]
        phase_m = common_m[..., None] - self.iono[a] + self.truth[a]
        phase_cyc = phase_m / self.lams[None, :, :] + self.amb_t[a]
        code_m = (
            common_m[..., None]
            + self.iono[a]
            + rng.normal(0.0, sc.code_noise_m, (n, ns, 2))
            * (self.m_el[a] / (mp.a + mp.b * np.exp(-(90.0**2) / (2 * mp.c_deg**2))))[..., None]
        )
        snr = np.clip(30.0 + 20.0 * np.sin(np.radians(np.clip(el[a], 0, 90))), 20, 55)
        snr_refl = _reflection_snr_db(mp.reflections, el[a], self.lams)
        blocks = {}
        for system in sc.systems:
            cols = [j for j, s in enumerate(self.sats) if s[0] == system]
            if not cols:
                continue
            blocks[system] = _system_block(
                system,
                tuple(self.sats[j] for j in cols),
                code_m[:, cols],
                phase_cyc[:, cols],
                snr[:, cols],
                snr_refl[:, cols],
                self.tracked[:, cols],
                self.lli[a][:, cols],
            )
        header = ObsHeader(
            version=3.04,
            file_system="M" if len(blocks) > 1 else sc.systems[0],
            marker_name=f"{sc.name.upper()[:56]}-{'AB'[a]}",
            receiver_type="PSDBOUND SIMULATOR",
            antenna_type="SIMULATED",
            approx_position_m=self.antennas[a] + (self.header_error if a == 1 else 0.0),
            antenna_delta_hen_m=np.zeros(3),
            interval_s=sc.interval_s,
            time_system="GPS",
            obs_types={s: b.codes for s, b in blocks.items()},
        )
        return Observations(path, header, t, np.zeros(n, np.int8), blocks)


def _system_block(
    system: str,
    sats: tuple[str, ...],
    code_m: NDArray[np.float64],
    phase_cyc: NDArray[np.float64],
    snr: NDArray[np.float64],
    snr_refl: NDArray[np.float64],
    keep: NDArray[np.bool_],
    lli: NDArray[np.int8],
) -> SystemBlock:
    """One system's observations as written (rounded), with LLI and signal strength flags."""
    codes = (
        CODES[system][0],
        SIGNALS[system][0],
        SNR[system][0],
        CODES[system][1],
        SIGNALS[system][1],
        SNR[system][1],
    )
    v = np.stack(
        [
            np.round(code_m[:, :, 0], 3),
            np.round(phase_cyc[:, :, 0], 3),
            np.round(snr + snr_refl[:, :, 0], 3),
            np.round(code_m[:, :, 1], 3),
            np.round(phase_cyc[:, :, 1], 3),
            np.round(snr - 3.0 + snr_refl[:, :, 1], 3),
        ],
        axis=2,
    )
    v[~keep] = np.nan
    li = np.full(v.shape, -1, dtype=np.int8)
    li[:, :, 1] = lli[:, :, 0]
    li[:, :, 4] = lli[:, :, 1]
    li[~keep] = -1
    ssi = np.where(np.isfinite(v), np.clip(v // 6, 1, 9), -1).astype(np.int8)
    ssi[:, :, [2, 5]] = -1
    # from the direct SNR; none where it is undefined (no orbit: never tracked, blank in the file)
    direct = np.where(np.isfinite(snr), np.clip(snr // 6, 1, 9), -1).astype(np.int8)
    ssi[:, :, [0, 1, 3, 4]] = direct[..., None]
    ssi[~keep] = -1
    return SystemBlock(system, sats, codes, v, li, ssi)


def _write_gz(p: Path, text: str, *, compress: bool = True) -> None:
    data = text.encode("ascii")
    if compress:
        data = gzip.compress(data, mtime=0)
    atomic_write_bytes(p, data)


def _write_truth_csv(p, t, sats, truth, el) -> None:
    n_ant = truth.shape[0]
    lines = ["t_gps_s,antenna,sat,elevation_deg,nu_1_m,nu_2_m"]
    for a in range(n_ant):
        ok = np.isfinite(truth[a, :, :, 0])
        ii, jj = np.nonzero(ok)
        rows = np.char.add(
            np.char.add(np.char.mod("%.1f", t[ii]), f",{'AB'[a]},"),
            np.asarray(sats)[jj],
        )
        cols = [el[a][ii, jj], truth[a, ii, jj, 0], truth[a, ii, jj, 1]]
        body = rows
        for fmt, v in zip((",%.4f", ",%.6f", ",%.6f"), cols, strict=True):
            body = np.char.add(body, np.char.mod(fmt, v))
        lines.extend(body.tolist())
    _write_gz(p, "\n".join(lines) + "\n")
