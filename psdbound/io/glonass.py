"""GLONASS broadcast ephemerides: the container and their propagation.

A GLONASS navigation message does not carry Keplerian elements but the
satellite state at the reference time ``tb`` in the Earth-fixed PZ-90 frame:
position, velocity and the luni-solar acceleration. Positions at other times
are found by integrating the equations of motion of the GLONASS ICD (edition
5.1, 2008, appendix A.3.1.2) in the rotating frame::

    dv/dt = -GM r / |r|^3 + J2 term + omega_e^2 (x, y, 0) + 2 omega_e (vy, -vx, 0) + a_ls

with the J2 term ``-3/2 J2 GM a_e^2 / |r|^5 (x (1 - 5 z^2/r^2), y (1 - 5 z^2/r^2),
z (3 - 5 z^2/r^2))`` and the luni-solar acceleration ``a_ls`` of the message
held constant. The integration is a fourth-order Runge-Kutta scheme with
:data:`INTEGRATION_STEP_S` (60 s) steps from ``tb`` to the requested time,
the last step shorter; its error is far below a millimetre over the 15-30
minutes a record is used, well under the metre-level error of the broadcast
state itself.

Constants are those of PZ-90.11 (``GLONASS_GM_M3_S2``, ``GLONASS_J2``,
``GLONASS_A_E_M``, ``GLONASS_OMEGA_E_RAD_S`` of :mod:`psdbound.constants`).
PZ-90.11 and WGS84 (G1762) agree to a few centimetres; the difference is
neglected and the positions are used as WGS84 coordinates.

Record selection
----------------
For every requested time the healthy record (``health == 0``) of that
satellite with the nearest ``tb`` is used, when ``|t - tb|`` is at most
:data:`GLONASS_MAX_AGE_S` (30 min; records are broadcast every 30 min, so
the nearest one is at most 15 min away on a complete file). Positions are
NaN elsewhere.

Times: RINEX writes the epoch of a GLONASS record in UTC (the ICD's ``tb``
is in GLONASS time, UTC(SU) + 3 h, which the RINEX writer has already
removed); the reader converts it to GPS seconds with the leap seconds of
:func:`psdbound.io.timescales.utc_to_gps_s`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from psdbound.constants import GLONASS_A_E_M, GLONASS_GM_M3_S2, GLONASS_J2, GLONASS_OMEGA_E_RAD_S
from psdbound.io.kepler import RecordTable

__all__ = [
    "GLONASS_MAX_AGE_S",
    "INTEGRATION_STEP_S",
    "GlonassEphemerides",
    "glonass_acceleration",
    "glonass_clock_s",
    "glonass_positions_ecef_m",
    "propagate_glonass_state",
    "select_glonass_records",
]

#: Largest |t - tb| for which a record is used, s.
GLONASS_MAX_AGE_S = 1800.0
#: Runge-Kutta step of the orbit integration, s.
INTEGRATION_STEP_S = 60.0


@dataclass(frozen=True, eq=False)
class GlonassEphemerides(RecordTable):
    """GLONASS broadcast ephemerides (one row per navigation record, file order).

    All attributes are numpy arrays with the records along axis 0.

    Attributes
    ----------
    sat : ndarray of str
        Satellite id, e.g. ``'R01'`` (slot number).
    tb_gps_s : ndarray of float64
        Reference time of the ephemeris (the record's epoch), GPS seconds.
    xyz_m : ndarray of float64, shape (n, 3)
        Position at ``tb`` in the PZ-90 Earth-fixed frame, m.
    vel_m_s : ndarray of float64, shape (n, 3)
        Velocity at ``tb`` in the Earth-fixed frame, m/s.
    acc_m_s2 : ndarray of float64, shape (n, 3)
        Luni-solar acceleration at ``tb``, m/s^2 (held constant).
    clock_bias_s : ndarray of float64
        Satellite clock offset at ``tb``, ``-tau_n``, s (as written in RINEX).
    gamma_n : ndarray of float64
        Relative frequency bias ``gamma_n`` (s/s).
    message_time_s : ndarray of float64
        Message frame time ``tk`` as written (RINEX 3: seconds of the UTC
        week; RINEX 2: seconds of the UTC day), s.
    health : ndarray of int64
        Health flag ``Bn`` (0 = healthy).
    channel : ndarray of int64
        FDMA frequency number ``k`` (-7 to +13).
    age_days : ndarray of int64
        Age of the operational information ``En``, days.

    """

    sat: NDArray[np.str_]
    tb_gps_s: NDArray[np.float64]
    xyz_m: NDArray[np.float64]
    vel_m_s: NDArray[np.float64]
    acc_m_s2: NDArray[np.float64]
    clock_bias_s: NDArray[np.float64]
    gamma_n: NDArray[np.float64]
    message_time_s: NDArray[np.float64]
    health: NDArray[np.int64]
    channel: NDArray[np.int64]
    age_days: NDArray[np.int64]

    def __len__(self) -> int:
        return int(self.sat.shape[0])

    @property
    def satellites(self) -> tuple[str, ...]:
        """Sorted ids of the satellites with at least one record."""
        return tuple(sorted({str(s) for s in self.sat}))

    @property
    def channels(self) -> dict[str, int]:
        """FDMA frequency number per satellite, from its latest record, e.g. ``{'R01': 1}``."""
        order = np.argsort(self.tb_gps_s, kind="stable")
        return {str(self.sat[i]): int(self.channel[i]) for i in order}


def select_glonass_records(
    eph: GlonassEphemerides,
    sat: str,
    t_gps_s: ArrayLike,
    max_age_s: float = GLONASS_MAX_AGE_S,
) -> NDArray[np.intp]:
    """Choose the record to use for each time: the healthy one with the nearest ``tb``.

    Parameters
    ----------
    eph : GlonassEphemerides
        GLONASS records.
    sat : str
        Satellite id such as ``'R07'``.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).
    max_age_s : float, optional
        Largest ``|t - tb|`` accepted, s (default :data:`GLONASS_MAX_AGE_S`).

    Returns
    -------
    ndarray of intp, shape (n,)
        Row index into ``eph`` per time, or -1 where no healthy record of the
        satellite lies within ``max_age_s``.

    """
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    rows = np.flatnonzero((eph.sat == sat) & (eph.health == 0))
    if rows.size == 0:
        return np.full(t.shape[0], -1, dtype=np.intp)
    rows = rows[np.argsort(eph.tb_gps_s[rows], kind="stable")]
    tb = eph.tb_gps_s[rows]
    t_ok = np.where(np.isfinite(t), t, np.inf)
    k = np.searchsorted(tb, t_ok)
    lo = np.clip(k - 1, 0, tb.size - 1)
    hi = np.clip(k, 0, tb.size - 1)
    d_lo, d_hi = np.abs(t_ok - tb[lo]), np.abs(t_ok - tb[hi])
    take_hi = d_hi < d_lo
    best = np.where(take_hi, rows[hi], rows[lo])
    ok = np.where(take_hi, d_hi, d_lo) <= max_age_s
    return np.where(ok, best, -1).astype(np.intp)


def glonass_acceleration(
    pos_m: NDArray[np.float64],
    vel_m_s: NDArray[np.float64],
    acc_ls_m_s2: NDArray[np.float64],
    *,
    j2: float = GLONASS_J2,
    omega_e_rad_s: float = GLONASS_OMEGA_E_RAD_S,
) -> NDArray[np.float64]:
    """Acceleration of the GLONASS equations of motion in the Earth-fixed frame.

    Parameters
    ----------
    pos_m : ndarray of float64, shape (n, 3)
        Positions, m.
    vel_m_s : ndarray of float64, shape (n, 3)
        Velocities in the rotating frame, m/s.
    acc_ls_m_s2 : ndarray of float64, shape (n, 3)
        Luni-solar accelerations, m/s^2.
    j2 : float, optional
        Second zonal harmonic (0 for a pure central field).
    omega_e_rad_s : float, optional
        Rotation rate of the frame, rad/s (0 for an inertial frame).

    Returns
    -------
    ndarray of float64, shape (n, 3)
        Accelerations, m/s^2: central attraction, J2, centrifugal and
        Coriolis terms plus the luni-solar acceleration.

    """
    x, y, z = pos_m[:, 0], pos_m[:, 1], pos_m[:, 2]
    r2 = x * x + y * y + z * z
    r = np.sqrt(r2)
    mu_r3 = GLONASS_GM_M3_S2 / (r2 * r)
    k = 1.5 * j2 * GLONASS_GM_M3_S2 * GLONASS_A_E_M**2 / (r2 * r2 * r)
    z2 = 5.0 * z * z / r2
    w2 = omega_e_rad_s * omega_e_rad_s
    out = np.empty_like(pos_m)
    out[:, 0] = -mu_r3 * x - k * x * (1.0 - z2) + w2 * x + 2.0 * omega_e_rad_s * vel_m_s[:, 1]
    out[:, 1] = -mu_r3 * y - k * y * (1.0 - z2) + w2 * y - 2.0 * omega_e_rad_s * vel_m_s[:, 0]
    out[:, 2] = -mu_r3 * z - k * z * (3.0 - z2)
    return out + acc_ls_m_s2


def _rk4(
    state: NDArray[np.float64], acc: NDArray[np.float64], h: NDArray[np.float64], **kw: float
) -> NDArray[np.float64]:
    """One Runge-Kutta step of per-row length ``h`` (s) for states (n, 6)."""
    hh = h[:, None]

    def f(s: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.hstack([s[:, 3:], glonass_acceleration(s[:, :3], s[:, 3:], acc, **kw)])

    k1 = f(state)
    k2 = f(state + 0.5 * hh * k1)
    k3 = f(state + 0.5 * hh * k2)
    k4 = f(state + hh * k3)
    return state + hh / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def propagate_glonass_state(
    pos_m: ArrayLike,
    vel_m_s: ArrayLike,
    acc_ls_m_s2: ArrayLike,
    dt_s: ArrayLike,
    *,
    step_s: float = INTEGRATION_STEP_S,
    j2: float = GLONASS_J2,
    omega_e_rad_s: float = GLONASS_OMEGA_E_RAD_S,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Integrate GLONASS states over per-row time spans (RK4, fixed steps).

    Each row is integrated from its reference time over ``dt_s`` with
    ``ceil(|dt| / step_s)`` equal steps (backwards for a negative span).

    Parameters
    ----------
    pos_m, vel_m_s, acc_ls_m_s2 : array_like of float, shape (n, 3) or (3,)
        Position (m), velocity (m/s) and luni-solar acceleration (m/s^2) at
        the reference time, Earth-fixed frame (one state for all spans, or
        one per span).
    dt_s : array_like of float, shape (n,) or scalar
        Time from the reference time to the wanted time, s.
    step_s : float, optional
        Largest integration step, s (default 60 s).
    j2 : float, optional
        Second zonal harmonic (0: no oblateness).
    omega_e_rad_s : float, optional
        Rotation rate of the frame, rad/s (0: inertial frame).

    Returns
    -------
    pos_m : ndarray of float64, shape (n, 3)
        Positions at the wanted times, m.
    vel_m_s : ndarray of float64, shape (n, 3)
        Velocities at the wanted times, m/s.

    """
    p = np.atleast_2d(np.asarray(pos_m, dtype=np.float64))
    v = np.atleast_2d(np.asarray(vel_m_s, dtype=np.float64))
    a = np.atleast_2d(np.asarray(acc_ls_m_s2, dtype=np.float64))
    dt1 = np.atleast_1d(np.asarray(dt_s, dtype=np.float64))
    n = np.broadcast_shapes(p.shape[:1], v.shape[:1], a.shape[:1], dt1.shape)[0]
    p, v, a = (np.broadcast_to(x, (n, 3)) for x in (p, v, a))
    dt = np.broadcast_to(dt1, (n,))
    n_steps = np.ceil(np.abs(dt) / step_s).astype(np.int64)
    h = np.where(n_steps > 0, dt / np.maximum(n_steps, 1), 0.0)
    state = np.hstack([p, v])
    acc = np.array(a)
    for i in range(int(n_steps.max(initial=0))):
        live = n_steps > i
        state[live] = _rk4(state[live], acc[live], h[live], j2=j2, omega_e_rad_s=omega_e_rad_s)
    return state[:, :3], state[:, 3:]


def glonass_positions_ecef_m(
    eph: GlonassEphemerides, sat: str, t_gps_s: ArrayLike
) -> NDArray[np.float64]:
    """Satellite positions from GLONASS broadcast ephemerides.

    Each record is integrated with 60 s RK4 steps away from ``tb`` once, and
    every time is reached from the last full step before it with one
    shorter step: the same result as integrating from ``tb`` to each time.

    Parameters
    ----------
    eph : GlonassEphemerides
        GLONASS records.
    sat : str
        Satellite id such as ``'R07'``.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of float64, shape (n, 3)
        ECEF coordinates in metres (PZ-90.11, used as WGS84) in the
        Earth-fixed frame at each time; NaN rows where no valid record
        exists (see :func:`select_glonass_records`).

    """
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    out = np.full((t.shape[0], 3), np.nan)
    sel = select_glonass_records(eph, sat, t)
    ok = sel >= 0
    if not np.any(ok):
        return out
    records, which = np.unique(sel[ok], return_inverse=True)
    dt = t[ok] - eph.tb_gps_s[sel[ok]]
    full = np.trunc(dt / INTEGRATION_STEP_S).astype(np.int64)  # full steps towards t
    rest = dt - full * INTEGRATION_STEP_S
    n_max = int(np.abs(full).max())
    acc = eph.acc_m_s2[records]
    start = np.hstack([eph.xyz_m[records], eph.vel_m_s[records]])
    # nodes[j] = states j full steps after tb (forward) / before tb (backward)
    fwd, bwd = [start], [start]
    step = np.full(records.size, INTEGRATION_STEP_S)
    for _ in range(n_max):
        fwd.append(_rk4(fwd[-1], acc, step))
        bwd.append(_rk4(bwd[-1], acc, -step))
    nodes_f, nodes_b = np.stack(fwd), np.stack(bwd)
    n_full = np.abs(full)
    node = np.where((full >= 0)[:, None], nodes_f[n_full, which], nodes_b[n_full, which])
    out[ok] = _rk4(node, acc[which], rest)[:, :3]
    return out


def glonass_clock_s(eph: GlonassEphemerides, sat: str, t_gps_s: ArrayLike) -> NDArray[np.float64]:
    """Broadcast GLONASS satellite clock offset ``-tau_n + gamma_n (t - tb)``.

    Parameters
    ----------
    eph : GlonassEphemerides
        GLONASS records.
    sat : str
        Satellite id such as ``'R07'``.
    t_gps_s : array_like of float
        Times, GPS seconds (scalar or 1-D).

    Returns
    -------
    ndarray of float64, shape (n,)
        Clock offset in seconds with respect to GLONASS system time (the
        GLONASS-GPS time offset is not applied); NaN where no valid record
        exists (same selection as :func:`glonass_positions_ecef_m`).

    """
    t = np.atleast_1d(np.asarray(t_gps_s, dtype=np.float64))
    out = np.full(t.shape[0], np.nan)
    sel = select_glonass_records(eph, sat, t)
    ok = sel >= 0
    idx = sel[ok]
    out[ok] = eph.clock_bias_s[idx] + eph.gamma_n[idx] * (t[ok] - eph.tb_gps_s[idx])
    return out
