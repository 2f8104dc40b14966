"""GLONASS broadcast ephemerides: reading (RINEX 2 and 3), integration, channels."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import ESBC_NAV, ESBC_OBS, ESBC_SP3, shared_file
from scipy.integrate import solve_ivp

from psdbound.arcs import find_arcs
from psdbound.constants import GLONASS_GM_M3_S2, GLONASS_OMEGA_E_RAD_S
from psdbound.io import read_nav, read_obs, read_orbit
from psdbound.io.glonass import (
    GlonassEphemerides,
    glonass_acceleration,
    glonass_positions_ecef_m,
    propagate_glonass_state,
    select_glonass_records,
)
from psdbound.io.signals import carrier_frequency_hz
from psdbound.io.timescales import calendar_to_gps_s

# PZ-90.11 values written out, so that a wrong constant in the module fails
GM, J2, AE, WE = 398600.4418e9, 1082.62575e-6, 6378136.0, 7.2921151467e-5
R_GLO = 25_508_000.0  # m, a GLONASS orbit radius
LEAP_2020 = 18.0  # GPS - UTC in 2020, s


def hdr(content: str, label: str) -> str:
    return f"{content:<60}{label:<20}"


def circular_state(node_deg=30.0, inc_deg=64.8, u_deg=40.0):
    """Inertial position and velocity (m, m/s) of a circular orbit of radius R_GLO."""
    node, inc, u = np.radians([node_deg, inc_deg, u_deg])
    p = np.array([np.cos(node), np.sin(node), 0.0])
    q = np.array([-np.sin(node) * np.cos(inc), np.cos(node) * np.cos(inc), np.sin(inc)])
    v = np.sqrt(GM / R_GLO)
    return R_GLO * (np.cos(u) * p + np.sin(u) * q), v * (-np.sin(u) * p + np.cos(u) * q), (p, q, u)


def to_rotating(r, v, t):
    """Inertial state at t -> Earth-fixed state (frames aligned at t = 0)."""
    c, s = np.cos(WE * t), np.sin(WE * t)
    rot = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return rot @ r, rot @ (v - np.cross([0.0, 0.0, WE], r))


def exact(pos, vel, acc, dt):
    """The same equations of motion integrated by scipy's DOP853 at tight tolerance."""

    def f(_, y):
        a = glonass_acceleration(y[None, :3], y[None, 3:], acc[None, :])[0]
        return np.r_[y[3:], a]

    sol = solve_ivp(f, (0.0, dt), np.r_[pos, vel], method="DOP853", rtol=1e-12, atol=1e-7)
    return sol.y[:3, -1], sol.y[3:, -1]


def f19(v: float) -> str:
    return f"{v:19.12e}"


def record_v3(sat, ymdhms, pos, vel, acc, *, clock=6.3559e-05, gamma=0.0, health=0, k=1):
    y, mo, d, h, mi, s = ymdhms
    km = [x / 1000.0 for x in (*pos, *vel, *acc)]
    lines = [
        f"{sat} {y:4d} {mo:02d} {d:02d} {h:02d} {mi:02d} {s:02d}"
        + f19(clock)
        + f19(gamma)
        + f19(342000.0)
    ]
    extra = (health, k, 0.0)
    for i in range(3):
        lines.append("    " + f19(km[i]) + f19(km[3 + i]) + f19(km[6 + i]) + f19(extra[i]))
    lines.append("    " + " " * 19 + f19(0.999999999999e9) + f19(15.0))  # RINEX 3.05 line
    return lines


def record_v2(prn, ymdhms, pos, vel, acc, *, k=-4):
    y, mo, d, h, mi, s = ymdhms
    km = [x / 1000.0 for x in (*pos, *vel, *acc)]
    d19 = [f19(v).replace("e", "D") for v in km]
    lines = [
        f"{prn:2d}{y % 100:3d}{mo:3d}{d:3d}{h:3d}{mi:3d}{s:5.1f}"
        + f19(-1.2e-5).replace("e", "D")
        + f19(9.1e-13).replace("e", "D")
        + f19(84600.0).replace("e", "D")
    ]
    extra = [f19(0.0), f19(float(k)), f19(3.0)]
    for i in range(3):
        lines.append("   " + d19[i] + d19[3 + i] + d19[6 + i] + extra[i].replace("e", "D"))
    return lines


RNX3_HEADER = [
    hdr("     3.05           N: GNSS NAV DATA    R: GLONASS", "RINEX VERSION / TYPE"),
    hdr("test", "PGM / RUN BY / DATE"),
    hdr("    18", "LEAP SECONDS"),
    hdr("", "END OF HEADER"),
]
RNX2_HEADER = [
    hdr("     2.11           G: GLONASS NAV DATA", "RINEX VERSION / TYPE"),
    hdr("test", "PGM / RUN BY / DATE"),
    hdr("", "END OF HEADER"),
]
EPOCH = (2020, 6, 24, 23, 15, 0)  # UTC
TB = float(calendar_to_gps_s(*EPOCH)) + LEAP_2020


def two_records():
    """A state at TB and the exactly integrated state 30 min later (with J2, luni-solar)."""
    r, v, _ = circular_state()
    pos, vel = to_rotating(r, v, 0.0)
    acc = np.array([-1.9e-6, 9.3e-7, -2.8e-6])
    pos2, vel2 = exact(pos, vel, acc, 1800.0)
    return (pos, vel, acc), (pos2, vel2, acc)


def write(tmp_path, name, lines):
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return p


# ------------------------------------------------------------------ closed form


def test_two_body_circle_in_the_rotating_frame():
    r, v, (p, q, u0) = circular_state()
    pos, vel = to_rotating(r, v, 0.0)
    dt = np.linspace(-3 * 3600.0, 3 * 3600.0, 25)
    n = len(dt)
    got, _ = propagate_glonass_state(
        np.tile(pos, (n, 1)), np.tile(vel, (n, 1)), np.zeros(3), dt, j2=0.0
    )
    mean_motion = np.sqrt(GM / R_GLO**3)
    want = np.array(
        [
            to_rotating(
                R_GLO * (np.cos(u0 + mean_motion * t) * p + np.sin(u0 + mean_motion * t) * q), v, t
            )[0]
            for t in dt
        ]
    )
    np.testing.assert_allclose(np.linalg.norm(got, axis=1), R_GLO, rtol=0, atol=0.01)
    assert np.max(np.linalg.norm(got - want, axis=1)) < 0.01


def test_two_body_inertial_frame_and_constants():
    r, v, _ = circular_state(u_deg=0.0)
    period = 2 * np.pi * np.sqrt(R_GLO**3 / GM)
    got, vel = propagate_glonass_state(r, v, np.zeros(3), period, j2=0.0, omega_e_rad_s=0.0)
    assert np.linalg.norm(got[0] - r) < 0.05 and np.linalg.norm(vel[0] - v) < 1e-5
    assert GLONASS_GM_M3_S2 == GM and GLONASS_OMEGA_E_RAD_S == WE


def test_j2_acceleration_formula():
    pos = np.array([[AE + 19_000e3, 0.0, 0.0], [0.0, 0.0, 25_000e3]])
    acc = glonass_acceleration(pos, np.zeros((2, 3)), np.zeros((2, 3)), omega_e_rad_s=0.0)
    r = np.linalg.norm(pos, axis=1)
    # equator: -GM/r^2 (1 + 3/2 J2 (ae/r)^2); pole: -GM/r^2 (1 - 3 J2 (ae/r)^2)
    assert acc[0, 0] == pytest.approx(-GM / r[0] ** 2 * (1 + 1.5 * J2 * (AE / r[0]) ** 2), 1e-13)
    assert acc[1, 2] == pytest.approx(-GM / r[1] ** 2 * (1 - 3.0 * J2 * (AE / r[1]) ** 2), 1e-13)


def test_rk4_matches_an_independent_integrator():
    (pos, vel, acc), (pos2, vel2, _) = two_records()
    got, gvel = propagate_glonass_state(pos, vel, acc, 1800.0)
    assert np.linalg.norm(got[0] - pos2) < 0.005 and np.linalg.norm(gvel[0] - vel2) < 1e-5


# ------------------------------------------------------------------ reading


def test_read_rinex3_glonass_records(tmp_path):
    (pos, vel, acc), (pos2, vel2, _) = two_records()
    later = (2020, 6, 24, 23, 45, 0)
    lines = RNX3_HEADER + record_v3("R01", EPOCH, pos, vel, acc, k=1)
    lines += record_v3("R01", later, pos2, vel2, acc, k=1)
    lines += record_v3("R02", EPOCH, pos, vel, acc, k=-4, health=1)
    nav = read_nav(write(tmp_path, "BRDC00XXX_R_20201760000_01D_RN.rnx", lines))
    g = nav.glonass
    assert isinstance(g, GlonassEphemerides) and len(g) == 3
    assert nav.systems == ("R",) and nav.satellites == ("R01", "R02") and nav.skipped == {}
    assert g.tb_gps_s[0] == TB  # UTC label + 18 leap seconds
    np.testing.assert_allclose(g.xyz_m[0], pos, rtol=1e-12)
    np.testing.assert_allclose(g.vel_m_s[0], vel, rtol=1e-12)
    np.testing.assert_allclose(g.acc_m_s2[0], acc, rtol=1e-12)
    assert g.clock_bias_s[0] == pytest.approx(6.3559e-05) and g.message_time_s[0] == 342000.0
    assert list(g.channel) == [1, 1, -4] and list(g.health) == [0, 0, 1]
    assert nav.glonass_channels == {"R01": 1, "R02": -4}
    # positions: record 1 before TB + 15 min, record 2 after, continuous across the switch
    a = nav.positions_ecef_m("R01", TB + 899.0)[0]
    b = nav.positions_ecef_m("R01", TB + 901.0)[0]
    ref, _ = propagate_glonass_state(pos, vel, acc, [899.0, 901.0])
    assert np.linalg.norm(a - ref[0]) < 0.001 and np.linalg.norm(b - ref[1]) < 0.01
    np.testing.assert_allclose(nav.positions_ecef_m("R01", TB)[0], pos, atol=1e-6)
    # unhealthy R02 and times beyond 30 min of any record give no position
    assert np.isnan(nav.positions_ecef_m("R02", TB)).all()
    assert np.isnan(nav.positions_ecef_m("R01", [TB - 1801.0, TB + 1800.0 + 1801.0])).all()
    clock = nav.satellite_clock_s("R01", TB + 60.0)
    assert clock[0] == pytest.approx(6.3559e-05)


def test_positions_equal_direct_integration():
    (pos, vel, acc), _ = two_records()
    eph = GlonassEphemerides(
        sat=np.array(["R05"]),
        tb_gps_s=np.array([TB]),
        xyz_m=pos[None],
        vel_m_s=vel[None],
        acc_m_s2=acc[None],
        clock_bias_s=np.zeros(1),
        gamma_n=np.zeros(1),
        message_time_s=np.zeros(1),
        health=np.zeros(1, np.int64),
        channel=np.ones(1, np.int64),
        age_days=np.zeros(1, np.int64),
    )
    dt = np.array([-1800.0, -1234.5, -60.0, -0.5, 0.0, 7.0, 60.0, 61.0, 959.3, 1800.0])
    got = glonass_positions_ecef_m(eph, "R05", TB + dt)
    ref, _ = propagate_glonass_state(np.tile(pos, (dt.size, 1)), vel, acc, dt)
    assert np.max(np.linalg.norm(got - ref, axis=1)) < 1e-3
    assert list(select_glonass_records(eph, "R05", TB + np.array([0.0, 1800.1]))) == [0, -1]


def test_read_rinex2_glonass_file(tmp_path):
    (pos, vel, acc), _ = two_records()
    lines = RNX2_HEADER + record_v2(3, EPOCH, pos, vel, acc, k=-4)
    lines += record_v2(14, EPOCH, pos, vel, acc, k=-7)
    nav = read_orbit(write(tmp_path, "brdc1760.20g", lines))
    assert nav.systems == ("R",) and nav.glonass_channels == {"R03": -4, "R14": -7}
    assert nav.glonass.tb_gps_s[0] == TB and list(nav.glonass.age_days) == [3, 3]
    np.testing.assert_allclose(nav.glonass.xyz_m[1], pos, rtol=1e-12)
    assert np.isfinite(nav.positions_ecef_m("R14", TB + 600.0)).all()


def test_damaged_glonass_record_is_left_out(tmp_path):
    (pos, vel, acc), _ = two_records()
    bad = record_v3("R07", EPOCH, pos / 10.0, vel, acc)  # 2 550 km from the centre
    wrong_k = record_v3("R08", EPOCH, pos, vel, acc, k=20)
    lines = RNX3_HEADER + bad + wrong_k + record_v3("R09", EPOCH, pos, vel, acc)
    with pytest.warns(UserWarning, match="2 navigation record.s. left out .* R07"):
        nav = read_nav(write(tmp_path, "bad.rnx", lines))
    assert nav.satellites == ("R09",)


def test_truncated_glonass_record(tmp_path):
    (pos, vel, acc), _ = two_records()
    lines = RNX3_HEADER + record_v3("R01", EPOCH, pos, vel, acc)[:3]
    from psdbound.errors import InputError

    with pytest.raises(InputError, match="ends in the middle of the record of R01"):
        read_nav(write(tmp_path, "cut.rnx", lines))


# ------------------------------------------------------------------ channels


def test_channels_from_the_navigation_file_reach_the_wavelengths(tmp_path):
    from orbit_samples import RX, geometric_observations, nominal

    from psdbound.io.glonass import GLONASS_MAX_AGE_S

    gps = nominal("G")
    obs = geometric_observations(gps, systems="G", hours=1.0)
    # one GLONASS satellite observed with a nav-file channel only (as in RINEX 2)
    (pos, vel, acc), _ = two_records()
    t0 = obs.t_gps_s[0]
    tb = t0 + np.arange(0.0, 3601.0, 1800.0)
    states = [propagate_glonass_state(pos, vel, acc, x - tb[0]) for x in tb]
    eph = GlonassEphemerides(
        sat=np.array(["R05"] * tb.size),
        tb_gps_s=tb,
        xyz_m=np.vstack([s[0] for s in states]),
        vel_m_s=np.vstack([s[1] for s in states]),
        acc_m_s2=np.tile(acc, (tb.size, 1)),
        clock_bias_s=np.zeros(tb.size),
        gamma_n=np.zeros(tb.size),
        message_time_s=np.zeros(tb.size),
        health=np.zeros(tb.size, np.int64),
        channel=np.full(tb.size, 6),
        age_days=np.zeros(tb.size, np.int64),
    )
    from dataclasses import replace

    from psdbound.io.geometry import signal_path
    from psdbound.io.obs import SystemBlock

    nav = replace(gps, glonass=eph)
    rho, _, _ = signal_path(nav, "R05", obs.t_gps_s, RX)
    lam = [299792458.0 / (f0 + 6 * df) for f0, df in ((1602e6, 0.5625e6), (1246e6, 0.4375e6))]
    v = np.stack([rho / lam[0], rho / lam[1]], axis=1)[:, None, :]
    lli = np.zeros(v.shape, np.int8)
    block = SystemBlock("R", ("R05",), ("L1C", "L2P"), v, lli, lli.copy())
    obs = replace(obs, blocks={**obs.blocks, "R": block})
    assert obs.header.glonass_channels == {}
    arcs = find_arcs(obs, system="R", orbit=nav, min_length_s=600)  # default pair L1C-L2P
    assert arcs.signals == ("L1C", "L2P") and len(arcs) == 1
    assert arcs.glonass_channels == {"R05": 6}
    np.testing.assert_allclose(arcs[0].phase_m[:, 0], rho[arcs[0].epoch_index], rtol=1e-12)
    np.testing.assert_allclose(arcs[0].geometry_free_m, 0.0, atol=1e-5)
    assert GLONASS_MAX_AGE_S == 1800.0
    # the header's own SLOT / FRQ # values win over the navigation file's
    mixed = obs.with_glonass_channels({"R05": 6})
    assert mixed.header.glonass_channels == {"R05": 6} and obs.with_glonass_channels({}) is obs
    own = replace(obs, header=replace(obs.header, glonass_channels={"R05": 2}))
    assert own.with_glonass_channels({"R05": 6}).header.glonass_channels == {"R05": 2}
    assert carrier_frequency_hz("R05", "L1C", nav.glonass_channels) == 1602e6 + 6 * 0.5625e6


# ------------------------------------------------------------------ real data


@pytest.mark.realdata
def test_esbc_consecutive_glonass_records_agree():
    """Propagating a record 30 min forward lands within metres of the next record."""
    g = read_nav(shared_file(ESBC_NAV)).glonass
    pairs = []
    for sat in g.satellites:
        rows = np.flatnonzero((g.sat == sat) & (g.health == 0))
        rows = rows[np.argsort(g.tb_gps_s[rows])]
        pairs += [
            (a, b)
            for a, b in zip(rows[:-1], rows[1:], strict=True)
            if g.tb_gps_s[b] - g.tb_gps_s[a] == 1800.0
        ]
    a, b = np.array(pairs).T

    def ahead(rows, dt, **kw):
        state = (g.xyz_m[rows], g.vel_m_s[rows], g.acc_m_s2[rows])
        return propagate_glonass_state(*state, dt, **kw)[0]

    full = np.linalg.norm(ahead(a, 1800.0) - g.xyz_m[b], axis=1)
    half = np.linalg.norm(ahead(a, 900.0) - ahead(b, -900.0), axis=1)
    no_j2 = np.linalg.norm(ahead(a, 1800.0, j2=0.0) - g.xyz_m[b], axis=1)
    print(
        f"\n{full.size} pairs: 30 min ahead median {np.median(full):.2f} m, max "
        f"{full.max():.2f} m; meeting half-way median {np.median(half):.2f} m"
    )
    assert full.size > 300
    assert np.median(full) < 5.0 and np.percentile(full, 99) < 20.0
    assert np.median(half) < 3.0 and half.max() < 20.0
    assert np.median(no_j2) > 50.0  # J2 matters: about 150 m without it


@pytest.mark.realdata
def test_esbc_broadcast_glonass_against_sp3():
    nav = read_nav(shared_file(ESBC_NAV))
    sp3 = read_orbit(shared_file(ESBC_SP3))
    t = sp3.t_gps_s[4:-4]
    errs = []
    for sat in nav.glonass.satellites:
        if sat in sp3.sats:
            d = np.linalg.norm(nav.positions_ecef_m(sat, t) - sp3.positions_ecef_m(sat, t), axis=1)
            errs.append(d[np.isfinite(d)])
    d = np.concatenate(errs)
    print(f"\nbroadcast - GRG SP3, GLONASS: median {np.median(d):.2f} m, max {d.max():.2f} m")
    assert d.size > 500 and np.median(d) < 5.0 and d.max() < 15.0


@pytest.mark.realdata
def test_esbc_glonass_arcs_with_elevations():
    obs = read_obs(shared_file(ESBC_OBS), systems="R")
    nav = read_orbit(shared_file(ESBC_NAV))
    arcs = find_arcs(obs, system="R", orbit=nav, elevation_mask_deg=10.0)
    assert arcs.signals == ("L1C", "L2P") and len(arcs) > 30 and arcs.warnings == ()
    for a in arcs:
        assert np.all((a.elevation_deg >= 10.0) & (a.elevation_deg <= 90.0))
        d = np.diff(a.geometry_free_m)
        assert np.max(np.abs(d - np.median(d))) < 0.5
