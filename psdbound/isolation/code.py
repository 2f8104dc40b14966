"""Code (pseudorange) multipath by carrier levelling (issue 21 part 1).

One code ``P_i`` and two carriers ``Phi_i``, ``Phi_j`` (metres), with
``a = (f_i / f_j)**2``: the classical MP combination (TEQC)

    MP_i = P_i - (1 + 2/(a-1)) Phi_i + (2/(a-1)) Phi_j

cancels geometry, clocks, troposphere and the first-order ionosphere; what is
left is the code multipath and noise plus a constant per continuous phase arc
(the ambiguities and the hardware biases), removed with the arc mean. Two
codes on two bands give the ionosphere-free version ``P_IF - Phi_IF`` with
``P_IF = g P_i + h P_j``, ``Phi_IF = g Phi_i + h Phi_j``,
``g = f_i**2 / (f_i**2 - f_j**2)`` and ``h = -f_j**2 / (f_i**2 - f_j**2)``.
The carrier multipath (millimetres) stays in the result, negligible beside
the code's (decimetres).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.arcs.find import DEFAULT_SIGNALS, find_arcs
from psdbound.common.notices import warn
from psdbound.errors import InputError, NoDataError
from psdbound.io.obs import SYSTEM_NAMES, Observations
from psdbound.io.signals import RINEX2_TO_RINEX3, carrier_frequency_hz
from psdbound.isolation.series import MultipathSeries

__all__ = ["isolate_code_multipath", "level_shifts", "rms_by_satellite"]

_ONE = "MP_i = P_i - (1 + 2/(a-1)) Phi_i + (2/(a-1)) Phi_j, a = (f_i/f_j)^2, minus the arc mean"
_IF = (
    "MP_IF = (g P_i + h P_j) - (g Phi_i + h Phi_j), g = f_i^2/(f_i^2-f_j^2), "
    "h = -f_j^2/(f_i^2-f_j^2), minus the arc mean"
)


def _v3(code: str) -> str:
    """Return the RINEX 3 name of a file's code (RINEX 2 codes mapped)."""
    return RINEX2_TO_RINEX3.get(code, code) if len(code) == 2 else code


def _phase_on_band(obs: Observations, system: str, code3: str) -> str | None:
    """Return the file's phase on the band of ``code3`` (same attribute if any)."""
    phases = [c for c in obs.codes(system) if c.startswith("L")]
    same = [c for c in phases if _v3(c)[1] == code3[1]]
    exact = [c for c in same if _v3(c)[2:] == code3[2:]]
    return (exact or same or [None])[0]


def _no_phase(obs: Observations, system: str, code: str) -> InputError:
    phases = [c for c in obs.codes(system) if c.startswith("L")]
    return InputError(
        f"no carrier phase on band {_v3(code)[1]} of {SYSTEM_NAMES.get(system, system)} code "
        f"{code} to level it with; phases in the file: {' '.join(phases) or 'none'}; choose "
        "another code or give phases",
        path=obs.path,
    )


def _choose_phases(
    obs: Observations, system: str, codes: tuple[str, ...], phases: Sequence[str] | None
) -> tuple[str, str]:
    """Return the carrier pair as stored in the file, ``Phi_i`` on the first code's band."""
    if phases is None:
        return _default_phases(obs, system, codes)
    return _given_phases(obs, system, codes, phases)


def _default_phases(obs: Observations, system: str, codes: tuple[str, ...]) -> tuple[str, str]:
    """Return the file's carrier pair for the codes (see ``phases`` of the caller)."""
    bands = [_v3(c)[1] for c in codes]
    first = _phase_on_band(obs, system, _v3(codes[0]))
    if first is None:
        raise _no_phase(obs, system, codes[0])
    if len(codes) == 2:
        second = _phase_on_band(obs, system, _v3(codes[1]))
        if second is None:
            raise _no_phase(obs, system, codes[1])
        return first, second
    file_phases = [c for c in obs.codes(system) if c.startswith("L")]
    by_v3 = {_v3(c): c for c in file_phases}
    others = [by_v3[s] for s in DEFAULT_SIGNALS.get(system, ()) if s in by_v3]
    others = [c for c in [*others, *file_phases] if _v3(c)[1] != bands[0]]
    if not others:
        raise InputError(
            f"no carrier phase on a band other than {bands[0]} "
            f"({SYSTEM_NAMES.get(system, system)}; phases: {' '.join(file_phases) or 'none'})"
            f": the combination for {codes[0]} needs a second carrier",
            path=obs.path,
        )
    return first, others[0]


def _given_phases(
    obs: Observations, system: str, codes: tuple[str, ...], phases: Sequence[str]
) -> tuple[str, str]:
    """Check the user's carrier pair against the codes; return it as stored in the file."""
    bands = [_v3(c)[1] for c in codes]
    if len(phases) != 2:
        raise InputError(f"expected a pair of carrier phases, got {tuple(phases)}", path=obs.path)
    pair = tuple(obs.resolve_code(system, p) for p in phases)
    for p in pair:
        if not p.startswith("L"):
            raise InputError(f"{p!r} is not a carrier-phase code (L..)", path=obs.path)
    pb = [_v3(p)[1] for p in pair]
    if pb[0] == pb[1]:
        raise InputError(f"phases {pair[0]} and {pair[1]} are on the same band", path=obs.path)
    if pb[0] != bands[0] or (len(codes) == 2 and pb[1] != bands[1]):
        raise InputError(
            f"phases {pair[0]} {pair[1]} do not match the codes {' '.join(codes)}: Phi_i must be "
            "on the first code's band (and Phi_j on the second code's, for two codes)",
            path=obs.path,
        )
    return pair[0], pair[1]


def isolate_code_multipath(
    obs: Observations,
    codes: str | Sequence[str],
    *,
    phases: Sequence[str] | None = None,
    orbit: object | None = None,
    receiver_xyz_m: NDArray[np.float64] | None = None,
    system: str | None = None,
    elevation_mask_deg: float = 0.0,
    min_length_s: float = 600.0,
    gap_factor: float = 1.5,
    slip_threshold_m: float = 0.04,
    satellites: Sequence[str] | None = None,
    outlier_m: float = 30.0,
    min_jump_m: float = 1.0,
) -> MultipathSeries:
    """Isolate code multipath by carrier levelling over continuous phase arcs.

    Parameters
    ----------
    obs : Observations
        Observations from :func:`psdbound.io.read_obs`.
    codes : str or sequence of one or two str
        One pseudorange code (``"C1C"``; RINEX 2 ``"C1"``, ``"P2"``) for its
        single-frequency multipath (MP combination), or two codes on two
        bands (``("C1C", "C5Q")``) for the ionosphere-free ``P_IF - Phi_IF``.
    phases : sequence of two str, optional
        Carrier pair ``(Phi_i, Phi_j)``, ``Phi_i`` on the (first) code's band
        (for two codes, ``Phi_j`` on the second code's band). Default: the
        file's phase on the code's band with the code's attribute, else
        another phase on that band; for one code, ``Phi_j`` is the carrier of
        :data:`psdbound.arcs.DEFAULT_SIGNALS` on another band (else the file's
        first phase on another band).
    orbit : OrbitSource, optional
        Orbit for elevations and the elevation mask (see
        :func:`psdbound.arcs.find_arcs`); GLONASS channels are taken from it too.
    receiver_xyz_m : ndarray of shape (3,), optional
        Receiver ECEF position, metres; default the header's.
    system : str, optional
        Satellite system letter; default the file's only system.
    elevation_mask_deg : float, default 0
        Epochs below this elevation are excluded, degrees (needs ``orbit``).
    min_length_s : float, default 600
        Minimum arc duration, seconds, both for the phase arcs and after
        epochs without a pseudorange are dropped.
    gap_factor : float, default 1.5
        A gap longer than this many sampling intervals breaks an arc.
    slip_threshold_m : float, default 0.04
        Geometry-free phase jump counted as a cycle slip, metres.
    satellites : sequence of str, optional
        Restrict to these satellites.
    outlier_m : float, default 30
        Samples beyond +-``outlier_m`` metres after levelling are counted in
        ``meta["outlier_samples_gt_m"]`` and warned about (kept).
    min_jump_m : float, default 1
        Smallest level shift of the code-minus-carrier combination that
        splits an arc, metres (see :func:`level_shifts`): slips the
        geometry-free test cannot see (equal-metre slips on both carriers,
        e.g. 77 and 60 cycles on L1 and L2) and receiver code jumps move the
        combination by metres and would otherwise be levelled as multipath.

    Returns
    -------
    MultipathSeries
        ``method="CODE"`` (one code) or ``"CODE-IF"`` (two), metres,
        ``scaling=1``, no filter; ``signals`` = the code(s) then the phases as
        stored in the file; elevations NaN without an orbit. An arc keeps
        holes where its pseudorange is missing. ``meta`` gives the source,
        system, formula, codes, phases, coefficients (term -> value, or term
        -> satellite -> value for GLONASS FDMA), arc counts, missing code
        samples, outliers and the warnings issued.

    Raises
    ------
    InputError
        An unknown code or phase (the message lists the file's codes), a code
        that is not a pseudorange, no phase on a code's band, two codes on
        one band, or no system given for a file of several systems.
    NoDataError
        No arc, or none of ``min_length_s`` once missing pseudoranges are
        dropped.

    Warns
    -----
    PsdboundWarning
        For each arc with samples beyond ``outlier_m`` (naming the satellite
        and the arc's index in the result), and for the orbit's coverage (see
        :func:`psdbound.arcs.find_arcs`).

    See Also
    --------
    rms_by_satellite : RMS of the result per satellite.
    psdbound.arcs.find_arcs : The arcs.
    isolate_dual_frequency : Carrier-phase multipath.

    References
    ----------
    .. [1] Estey, L. H., & Meertens, C. M. (1999). TEQC: The multi-purpose
       toolkit for GPS/GLONASS data. *GPS Solutions*, 3(1), 42-49.
    .. [2] Blanch, J., Walter, T., & Phelts, R. E. (2019). Code multipath
       estimation using a biased ionosphere estimate from a second carrier.

    Examples
    --------
    >>> from psdbound.io import read_obs, read_orbit
    >>> from psdbound.simulate import demo_data
    >>> d = demo_data()
    >>> obs = read_obs(d.obs_paths[0], systems="G")
    >>> mp = isolate_code_multipath(obs, "C1C", orbit=read_orbit(d.nav_path))
    >>> mp.method, mp.signals, mp.meta["phases"]
    ('CODE', ('C1C', 'L1C', 'L2W'), ('L1C', 'L2W'))
    >>> 0.1 < min(rms_by_satellite(mp).values()) < 1.0   # metres
    True
    """
    system, fcodes = _check_codes(obs, codes, system)
    pi, pj = _choose_phases(obs, system, fcodes, phases)
    arcs = find_arcs(
        obs,
        (pi, pj),
        system=system,
        orbit=orbit,
        receiver_xyz_m=receiver_xyz_m,
        min_length_s=min_length_s,
        gap_factor=gap_factor,
        slip_threshold_m=slip_threshold_m,
        elevation_mask_deg=elevation_mask_deg,
        satellites=satellites,
    )
    if len(arcs) == 0:
        raise NoDataError(arcs.empty_reason(), path=arcs.path)
    lv = _Levelling(fcodes, min_length_s, outlier_m, min_jump_m, notes=list(arcs.warnings))
    channels = arcs.glonass_channels or dict(obs.header.glonass_channels)
    for arc in arcs:
        if arc.sat not in lv.coef:
            fi, fj = (carrier_frequency_hz(arc.sat, _v3(p), channels) for p in (pi, pj))
            lv.coef[arc.sat] = _coefficients(fi, fj, len(fcodes))
        lv.level(obs, arc)
    if not lv.out:
        raise NoDataError(
            f"no arc of {SYSTEM_NAMES.get(system, system)} {' '.join(fcodes)} lasts "
            f"{min_length_s / 60:g} min once the {lv.missing} epochs without the pseudorange are "
            f"dropped ({lv.short} arcs); choose another code",
            path=obs.path,
        )
    meta = {
        "source": obs.path,
        "system": system,
        "combination": _ONE if len(fcodes) == 1 else _IF,
        "codes": fcodes,
        "phases": (pi, pj),
        "coefficients": _coefficient_table(lv.coef, len(fcodes)),
        "arcs_in": len(arcs),
        "arcs_dropped_code_missing": lv.short,
        "code_missing_samples": lv.missing,
        "arc_breaks": dict(arcs.breaks),
        "stretches_dropped_short": int(sum(arcs.dropped.values())),
        "elevation_mask_deg": arcs.elevation_mask_deg,
        "outlier_threshold_m": float(outlier_m),
        "outlier_samples_gt_m": dict(sorted(lv.outliers.items())),
        "level_shift_min_m": float(min_jump_m),
        "level_shift_breaks": dict(sorted(lv.shifts.items())),
        "level_shift_dropped_samples": int(lv.shift_dropped),
        "has_elevation": all(a.elevation_deg is not None for a in arcs),
        "warnings": tuple(lv.notes),
    }
    return MultipathSeries.from_arcs(
        "CODE" if len(fcodes) == 1 else "CODE-IF",
        lv.out,
        signals=(*fcodes, pi, pj),
        scaling=1.0,
        interval_s=arcs.interval_s,
        cutoff_hz=None,
        meta=meta,
    )


def _check_codes(
    obs: Observations, codes: str | Sequence[str], system: str | None
) -> tuple[str, tuple[str, ...]]:
    """Return the system and the pseudorange codes as stored in the file, checked."""
    codes = (codes,) if isinstance(codes, str) else tuple(codes)
    if len(codes) not in (1, 2):
        raise InputError(f"expected one or two pseudorange codes, got {codes}", path=obs.path)
    if system is None and len(obs.systems) != 1:
        msg = f"the file holds several systems ({' '.join(obs.systems)}); give system"
        raise InputError(msg, path=obs.path)
    system = obs.systems[0] if system is None else system
    fcodes = tuple(obs.resolve_code(system, c) for c in codes)
    for c in fcodes:
        if c[0] not in "CP":
            raise InputError(f"{c!r} is not a pseudorange code (C.. or P..)", path=obs.path)
    if len(fcodes) == 2 and _v3(fcodes[0])[1] == _v3(fcodes[1])[1]:
        raise InputError(
            f"codes {fcodes[0]} and {fcodes[1]} are on the same band; the ionosphere-free "
            "combination needs two bands",
            path=obs.path,
        )
    return system, fcodes


#: Frames between :func:`_Levelling.level`'s warnings and the caller of
#: :func:`isolate_code_multipath` (where the warnings point, as before the split).
_WARN_STACKLEVEL = 3


@dataclass
class _Levelling:
    """The levelled arcs of :func:`isolate_code_multipath` and what was dropped, split, warned."""

    fcodes: tuple[str, ...]
    min_length_s: float
    outlier_m: float
    min_jump_m: float
    notes: list[str]
    coef: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    out: list[dict[str, Any]] = field(default_factory=list)
    missing: int = 0
    short: int = 0
    outliers: Counter = field(default_factory=Counter)
    shifts: Counter = field(default_factory=Counter)
    shift_dropped: int = 0

    def level(self, obs: Observations, arc: Any) -> None:
        """Level one phase arc: drop epochs without the code, split at level shifts."""
        c_code, c_phase = self.coef[arc.sat]
        p = np.column_stack([obs.get(arc.sat, c)[arc.epoch_index] for c in self.fcodes])
        ok = np.all(np.isfinite(p) & (p != 0.0), axis=1)
        self.missing += int(ok.size - ok.sum())
        t = arc.t_gps_s[ok]
        if t.size < 2 or t[-1] - t[0] < self.min_length_s:
            self.short += 1
            return
        raw = p[ok] @ c_code + arc.phase_m[ok] @ c_phase
        el_all = np.full(t.size, np.nan) if arc.elevation_deg is None else arc.elevation_deg[ok]
        cuts = level_shifts(raw, min_jump_m=self.min_jump_m)
        if cuts.size:
            self.shifts[arc.sat] += int(cuts.size)
            self.notes.append(
                warn(
                    f"{arc.sat} ({self.fcodes[0]}, {t[0]:.0f}-{t[-1]:.0f} GPS s): the "
                    f"code-minus-carrier level steps by {_steps_text(raw, cuts)} m "
                    "(a slip the geometry-free test cannot see, a code jump, or a reacquisition at "
                    "the arc's edge): the arc is split "
                    "there, each piece levelled on its own",
                    path=obs.path,
                    stacklevel=_WARN_STACKLEVEL,
                )
            )
        for a, b in zip(np.r_[0, cuts], np.r_[cuts, t.size], strict=True):
            if b - a < 2 or t[b - 1] - t[a] < self.min_length_s:
                self.shift_dropped += b - a
                continue
            self._add_piece(obs, arc.sat, t[a:b], raw[a:b], el_all[a:b])

    def _add_piece(
        self,
        obs: Observations,
        sat: str,
        t: NDArray[np.float64],
        raw: NDArray[np.float64],
        el: NDArray[np.float64],
    ) -> None:
        """Remove a piece's mean (m), count and warn about its outliers, keep it."""
        mp = raw - raw.mean()
        bad = np.abs(mp) > self.outlier_m
        if bad.any():
            self.outliers[sat] += int(bad.sum())
            text = (
                f"{sat} arc {len(self.out)} ({self.fcodes[0]}, {t[0]:.0f}-{t[-1]:.0f} GPS s): "
                f"{int(bad.sum())} code-multipath samples beyond {self.outlier_m:g} m after "
                f"levelling (largest {np.abs(mp).max():.1f} m): not multipath but a code "
                "outlier or an undetected slip; kept, counted in meta['outlier_samples_gt_m']"
            )
            self.notes.append(warn(text, path=obs.path, stacklevel=_WARN_STACKLEVEL + 1))
        self.out.append({"sats": sat, "t_gps_s": t, "value_m": mp, "elevation_deg": el})


_TERMS = {1: ("P_i", "Phi_i", "Phi_j"), 2: ("P_i", "P_j", "Phi_i", "Phi_j")}


def _coefficients(fi: float, fj: float, n_codes: int) -> tuple[np.ndarray, np.ndarray]:
    """Return the coefficients of the codes and of the two phases."""
    if n_codes == 1:
        k = 2.0 / ((fi / fj) ** 2 - 1.0)
        return np.array([1.0]), np.array([-(1.0 + k), k])
    g, h = fi**2 / (fi**2 - fj**2), -(fj**2) / (fi**2 - fj**2)
    return np.array([g, h]), np.array([-g, -h])


def _coefficient_table(
    coef: dict[str, tuple[np.ndarray, np.ndarray]], n_codes: int
) -> dict[str, float] | dict[str, dict[str, float]]:
    """Return term -> value, or term -> satellite -> value (GLONASS FDMA)."""
    rows = {s: np.concatenate(c) for s, c in coef.items()}
    ref = next(iter(rows.values()))
    if all(np.allclose(r, ref, rtol=1e-12, atol=0.0) for r in rows.values()):
        return {name: float(v) for name, v in zip(_TERMS[n_codes], ref, strict=True)}
    return {
        name: {s: float(r[k]) for s, r in sorted(rows.items())}
        for k, name in enumerate(_TERMS[n_codes])
    }


def level_shifts(
    x: ArrayLike, *, min_jump_m: float = 1.0, k: int = 5, n_sigma: float = 5.0, window: int = 30
) -> NDArray[np.intp]:
    """Find where a code-minus-carrier series steps to a new level.

    A sample ``i`` starts a new level when the change ``x[i] - x[i-1]``
    and the change of the medians of the ``k`` samples before and from
    ``i`` both exceed ``max(min_jump_m, n_sigma * s_i)``, where ``s_i`` is
    the robust (MAD) standard deviation of the first differences within
    ``window`` samples of ``i`` (the jump itself left out). The scale is
    local because code noise grows tenfold from zenith to the horizon: a
    whole-arc scale would split noisy low-elevation stretches. For white
    noise of standard deviation ``sigma`` the threshold is at least
    ``5 sqrt(2) sigma``, about nine standard deviations of the median
    change, so noise alone does not split an arc; the median test keeps a
    single-epoch spike (one large change in, one out) from splitting it
    either: a spike is an outlier, not a new level.

    Parameters
    ----------
    x : array_like, shape (n,)
        The combination of one arc, metres, time-ordered.
    min_jump_m : float, default 1
        Smallest step that counts, metres.
    k : int, default 5
        Samples on each side whose medians are compared.
    n_sigma : float, default 5
        Step threshold in local robust standard deviations of the differences.
    window : int, default 30
        Differences on each side of a candidate step for the local scale.

    Returns
    -------
    ndarray of int
        First index of every new level (increasing; empty when none).

    See Also
    --------
    isolate_code_multipath : Splits its levelling arcs here.

    References
    ----------
    .. [1] Estey, L. H., & Meertens, C. M. (1999). TEQC: The multi-purpose
       toolkit for GPS/GLONASS data. *GPS Solutions*, 3(1), 42-49 (code
       multipath jumps as slip indicators).
    .. [2] docs/method/aviation.rst (the thresholds and their checks).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.r_[np.zeros(20), np.full(10, 7.0)] + 0.01 * np.sin(np.arange(30))
    >>> level_shifts(x).tolist()
    [20]
    >>> x[5] = 9.0            # a spike is not a new level
    >>> level_shifts(x).tolist()
    [20]
    """
    x = np.asarray(x, dtype=float)
    if x.size < 3:
        return np.empty(0, dtype=np.intp)
    d = np.diff(x)
    cuts = []
    for i in np.flatnonzero(np.abs(d) > min_jump_m) + 1:
        near = np.r_[d[max(0, i - 1 - window) : i - 1], d[i : i + window]]
        s = 1.4826 * float(np.median(np.abs(near - np.median(near)))) if near.size else 0.0
        thr = max(float(min_jump_m), n_sigma * s)
        if (
            abs(d[i - 1]) > thr
            and abs(np.median(x[i : i + k]) - np.median(x[max(0, i - k) : i])) > thr
        ):
            cuts.append(i)
    return np.asarray(cuts, dtype=np.intp)


def _steps_text(x: NDArray[np.float64], cuts: NDArray[np.intp], k: int = 5) -> str:
    """Format the level steps at ``cuts`` as text, metres."""
    return ", ".join(
        f"{abs(np.median(x[i : i + k]) - np.median(x[max(0, i - k) : i])):.1f}" for i in cuts
    )


def rms_by_satellite(series: MultipathSeries) -> dict[str, float]:
    """Root-mean-square of a series per satellite, over all its samples.

    Parameters
    ----------
    series : MultipathSeries
        E.g. from :func:`isolate_code_multipath` (one satellite per arc).

    Returns
    -------
    dict of str to float
        Satellite -> RMS in metres, sorted by satellite.
    """
    sats = np.asarray(series.arc_sats)[series.arc_id] if series.n_arcs else np.zeros(0, str)
    out = {}
    for s in sorted(set(series.arc_sats)):
        v = series.value_m[sats == s]
        out[s] = float(np.sqrt(np.mean(v**2)))
    return out
