"""Tests of the SP3 reader and interpolation (psdbound.io.sp3)."""

from __future__ import annotations

import time

import numpy as np
import pytest
from conftest import ESBC_SP3, shared_file

from psdbound.errors import InputError
from psdbound.io.sp3 import PreciseOrbit, read_sp3
from psdbound.io.timescales import calendar_to_gps_s

START = (2020, 6, 25, 0, 0, 0.0)
T_START = float(calendar_to_gps_s(*START))
STEP = 900.0
A_M = 26_560_000.0
N_ORBIT = 2 * np.pi / 43082.0  # ~ half a sidereal day
OMEGA_E = 7.2921151467e-5


def orbit_m(k: int, t_rel: np.ndarray) -> np.ndarray:
    """Analytic inclined circular orbit seen in the rotating Earth frame, m."""
    inc = np.radians(55.0)
    u = N_ORBIT * t_rel + 0.4 * k
    node = 0.3 * k - OMEGA_E * t_rel
    xo, yo = A_M * np.cos(u), A_M * np.sin(u)
    return np.stack(
        [
            xo * np.cos(node) - yo * np.cos(inc) * np.sin(node),
            xo * np.sin(node) + yo * np.cos(inc) * np.cos(node),
            yo * np.sin(inc),
        ],
        axis=-1,
    )


def sp3_lines(
    sats: list[str],
    n_epochs: int,
    *,
    version: str = "c",
    time_system: str = "GPS",
    header_epochs: int | None = None,
    eof: bool = True,
    missing: dict[tuple[int, str], str] | None = None,
    times: list[float] | None = None,
) -> list[str]:
    """Text of a synthetic SP3 file: satellite k on ``orbit_m(k, t)``.

    Epoch e is at ``times[e]`` seconds after START (default ``e * STEP``).
    """
    y, mo, d, h, mi, s = START
    nh = n_epochs if header_epochs is None else header_epochs
    out = [
        f"#{version}P{y:4d} {mo:2d} {d:2d} {h:2d} {mi:2d} {s:11.8f} {nh:7d} ORBIT IGS14 FIT  TST",
        "## 2111 345600.00000000   900.00000000 59025 0.0000000000000",
    ]
    ids = sats + ["  0"] * max(0, 5 * 17 - len(sats))
    ids += ["  0"] * (-len(ids) % 17)
    for r in range(len(ids) // 17):
        lead = f"+  {len(sats):3d}   " if r == 0 else "+        "
        out.append(lead + "".join(ids[17 * r : 17 * r + 17]))
    for _ in range(len(ids) // 17):
        out.append("++       " + "  5" * 17)
    out += [
        f"%c M  cc {time_system} ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
        "%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
        "%f  0.0000000  0.000000000  0.00000000000  0.000000000000000",
        "%i    0    0    0    0      0      0      0      0         0",
        "/* synthetic test file",
    ]
    missing = missing or {}
    for e in range(n_epochs):
        t_rel = e * STEP if times is None else times[e]
        hh, rem = divmod(t_rel, 3600.0)
        mm, ss = divmod(rem, 60.0)
        out.append(f"*  {y:4d} {mo:2d} {d:2d} {int(hh):2d} {int(mm):2d} {ss:11.8f}")
        for k, sat in enumerate(sats):
            if (e, sat) in missing:
                out.append(f"P{sat}" + missing[(e, sat)])
                continue
            x, yy, z = orbit_m(k, np.array(t_rel)) / 1000.0
            clk = 100.0 + 0.001 * e
            out.append(f"P{sat}{x:14.6f}{yy:14.6f}{z:14.6f}{clk:14.6f}")
    if eof:
        out.append("EOF")
    return out


def write(tmp_path, name: str, lines: list[str]) -> str:
    p = tmp_path / name
    p.write_text("\n".join(lines) + "\n")
    return str(p)


# ------------------------------------------------------------------ synthetic


def test_sp3c_values(tmp_path):
    sats = ["G01", "E05", "R24"]
    missing = {
        (3, "E05"): "      0.000000      0.000000      0.000000 999999.999999",
        (4, "R24"): "  12000.000000  13000.000000  14000.000000 999999.999999",
    }
    orb = read_sp3(write(tmp_path, "a.sp3", sp3_lines(sats, 30, missing=missing)))
    assert isinstance(orb, PreciseOrbit)
    assert orb.sats == ("G01", "E05", "R24")
    assert orb.satellites == ("E05", "G01", "R24")
    assert orb.time_system == "GPS"
    assert orb.t_gps_s.shape == (30,)
    np.testing.assert_array_equal(orb.t_gps_s, T_START + STEP * np.arange(30))
    assert orb.xyz_m.shape == (30, 3, 3)
    assert orb.clock_s.shape == (30, 3)
    np.testing.assert_allclose(orb.xyz_m[5, 1], orbit_m(1, np.array(5 * STEP)), atol=1e-3)
    assert orb.clock_s[5, 0] == pytest.approx(100.005e-6, rel=1e-12)
    assert np.isnan(orb.xyz_m[3, 1]).all()
    assert np.isnan(orb.clock_s[3, 1])
    assert np.isfinite(orb.xyz_m[4, 2]).all()
    assert np.isnan(orb.clock_s[4, 2])


def test_sp3d_many_satellites_utc(tmp_path):
    sats = (
        [f"G{i:02d}" for i in range(1, 33)]
        + [f"E{i:02d}" for i in range(1, 37)]
        + [f"R{i:02d}" for i in range(1, 25)]
        + [f"C{i:02d}" for i in range(19, 29)]
    )
    assert len(sats) > 85  # needs more than the 5 '+' lines of SP3-c
    orb = read_sp3(write(tmp_path, "d.sp3", sp3_lines(sats, 3, version="d", time_system="UTC")))
    assert orb.sats == tuple(sats)
    assert orb.time_system == "UTC"
    # 2020: GPS - UTC = 18 s
    assert orb.t_gps_s[0] == T_START + 18.0


@pytest.mark.parametrize(
    ("ts", "offset"),
    [
        ("GPS", 0.0),
        ("GAL", 0.0),
        ("QZS", 0.0),
        ("TAI", -19.0),
        ("BDT", 14.0),
        ("UTC", 18.0),
        ("GLO", 18.0 - 10800.0),
        ("ccc", 0.0),
    ],
)
def test_time_systems(tmp_path, ts, offset):
    orb = read_sp3(write(tmp_path, "t.sp3", sp3_lines(["G01"], 2, time_system=ts)))
    assert orb.t_gps_s[0] == T_START + offset


def test_interpolation_accuracy_and_span(tmp_path):
    sats = ["G01", "G02"]
    orb = read_sp3(write(tmp_path, "i.sp3", sp3_lines(sats, 40)))
    t_rel = np.linspace(0.0, 39 * STEP, 1001)
    for k, sat in enumerate(sats):
        got = orb.positions_ecef_m(sat, T_START + t_rel)
        err = np.linalg.norm(got - orbit_m(k, t_rel), axis=1)
        # 11-node Lagrange on 15-min nodes: ~1 mm (the file's mm rounding) where
        # the window is centred, about 1 cm in the first/last interval
        centred = (t_rel >= 4 * STEP) & (t_rel <= 35 * STEP)
        assert err[centred].max() < 0.002
        assert err.max() < 0.03
    # exactly at the nodes the file values are returned
    nodes = orb.positions_ecef_m("G02", orb.t_gps_s)
    np.testing.assert_allclose(nodes, orb.xyz_m[:, 1], rtol=0, atol=1e-6)
    # outside the span, and unknown satellites: NaN
    out = orb.positions_ecef_m("G01", T_START + np.array([-1.0, 39 * STEP + 1.0]))
    assert out.shape == (2, 3) and np.isnan(out).all()
    assert np.isnan(orb.positions_ecef_m("G09", T_START)).all()


def test_interpolation_nan_where_node_missing(tmp_path):
    missing = {(20, "G01"): "      0.000000      0.000000      0.000000    100.000000"}
    orb = read_sp3(write(tmp_path, "m.sp3", sp3_lines(["G01"], 40, missing=missing)))
    t = T_START + STEP * np.array([2.5, 14.5, 15.5, 19.5, 25.5, 26.5, 30.5])
    got = orb.positions_ecef_m("G01", t)
    # windows: interval k uses nodes k-4 .. k+6; node 20 is in them for k = 14..24
    expect_nan = np.array([False, True, True, True, False, False, False])
    np.testing.assert_array_equal(np.isnan(got).any(axis=1), expect_nan)
    # interval 25 uses nodes 21-31: fine; interval 24 would need node 20
    assert np.isnan(orb.positions_ecef_m("G01", T_START + 24.5 * STEP)).all()


def test_interpolation_irregular_epochs_and_gaps(tmp_path):
    # epoch 20 is 2 min late (irregular but usable); epochs 30-31 are absent (a gap)
    times = [e * STEP for e in range(60) if e not in (30, 31)]
    times[20] += 120.0
    orb = read_sp3(write(tmp_path, "g.sp3", sp3_lines(["G01"], len(times), times=times)))
    t_rel = np.arange(0.0, 59 * STEP, 97.0)
    got = orb.positions_ecef_m("G01", T_START + t_rel)
    err = np.linalg.norm(got - orbit_m(0, t_rel), axis=1)
    # windows holding the 30-min gap (a spacing of 3 steps) give NaN ...
    node_t = np.asarray(times)
    gap_lo, gap_hi = node_t[29], node_t[30]
    assert np.isnan(err[(t_rel > gap_lo) & (t_rel < gap_hi)]).all()
    # ... and elsewhere, including windows with the late epoch 20, the orbit is met
    far = (t_rel < node_t[23]) | (t_rel > node_t[36])
    assert np.isfinite(err[far]).all()
    assert err[far].max() < 0.03
    late = (t_rel > node_t[18]) & (t_rel < node_t[22])
    assert err[late].max() < 0.002


# ------------------------------------------------------------------ bad input


def test_truncated_mid_epoch(tmp_path):
    lines = sp3_lines(["G01", "G02", "G03"], 10)
    cut = lines[: lines.index("EOF") - 2]  # last epoch keeps 1 of 3 records
    path = write(tmp_path, "cut.sp3", cut)
    last_epoch = max(k for k, s in enumerate(cut) if s.startswith("*")) + 1
    with pytest.raises(
        InputError,
        match=rf"cut\.sp3, line {len(cut)}: truncated SP3 file: the last epoch \(line "
        rf"{last_epoch}\) "
        r"has 1 of 3 position records and there is no EOF line",
    ):
        read_sp3(path)


def test_truncated_missing_epochs(tmp_path):
    lines = sp3_lines(["G01"], 10, header_epochs=96, eof=False)
    path = write(tmp_path, "short.sp3", lines)
    with pytest.raises(
        InputError,
        match=rf"short\.sp3, line {len(lines)}: truncated SP3 file: the header announces 96 "
        r"epochs but the file holds 10 and ends without the EOF line",
    ):
        read_sp3(path)


def test_header_only(tmp_path):
    lines = sp3_lines(["G01"], 2)
    head = lines[: next(k for k, s in enumerate(lines) if s.startswith("*"))]
    with pytest.raises(
        InputError, match=rf"h\.sp3, line {len(head)}: truncated SP3 file: no epoch line"
    ):
        read_sp3(write(tmp_path, "h.sp3", head))


def test_incomplete_epoch_mid_file(tmp_path):
    lines = sp3_lines(["G01", "G02"], 4)
    i = next(k for k, s in enumerate(lines) if s.startswith("*"))
    del lines[i + 2]  # drop G02 of the first epoch
    with pytest.raises(InputError, match=r"line \d+: incomplete epoch: 1 of 2 position records"):
        read_sp3(write(tmp_path, "gap.sp3", lines))


def test_not_sp3(tmp_path):
    path = write(tmp_path, "notes.txt", ["hello", "world"])
    with pytest.raises(InputError, match=r"notes\.txt, line 1: not an SP3 file .*'#c' or '#d'"):
        read_sp3(path)
    rinex = [f"{'     3.05           N: GNSS NAV DATA    M: MIXED':<60}RINEX VERSION / TYPE"]
    path = write(tmp_path, "nav.rnx", rinex)
    with pytest.raises(InputError, match=r"nav\.rnx, line 1: not an SP3 file \(a RINEX file\)"):
        read_sp3(path)


def test_unknown_time_system(tmp_path):
    path = write(tmp_path, "ts.sp3", sp3_lines(["G01"], 2, time_system="XYZ"))
    with pytest.raises(InputError, match=r"ts\.sp3: unknown time system 'XYZ'"):
        read_sp3(path)


def test_bad_number(tmp_path):
    lines = sp3_lines(["G01"], 3)
    i = next(k for k, s in enumerate(lines) if s.startswith("PG01"))
    lines[i] = lines[i][:4] + "  1234x.000000" + lines[i][18:]
    with pytest.raises(
        InputError,
        match=rf"bad\.sp3, line {i + 1}: cannot parse number '1234x\.000000' in columns 5-18",
    ):
        read_sp3(write(tmp_path, "bad.sp3", lines))


# ------------------------------------------------------------------ real file


@pytest.mark.realdata
def test_real_grg_sp3():
    path = shared_file(ESBC_SP3)
    t0 = time.perf_counter()
    orb = read_sp3(path)
    dt = time.perf_counter() - t0
    print(f"\nread {ESBC_SP3}: {dt * 1e3:.0f} ms")
    assert dt < 0.5
    assert orb.t_gps_s.shape == (96,)
    assert orb.time_system == "GPS"
    assert orb.t_gps_s[0] == calendar_to_gps_s(2020, 6, 25, 0, 0, 0)
    np.testing.assert_array_equal(np.diff(orb.t_gps_s), 900.0)
    assert len(orb.sats) == 75
    assert sum(s[0] == "G" for s in orb.sats) >= 30
    assert sum(s[0] == "E" for s in orb.sats) >= 20
    j = orb.sats.index("E01")
    np.testing.assert_allclose(
        orb.xyz_m[0, j], [-11562163.582, 14053114.306, 23345128.269], rtol=0, atol=1e-6
    )
    assert orb.clock_s[0, j] == pytest.approx(-884.707516e-6)
    r = np.linalg.norm(orb.xyz_m, axis=-1)
    assert np.nanmin(r) > 2.3e7 and np.nanmax(r) < 3.3e7  # E14, E18 are eccentric
    # interpolation at mid-epochs stays on a plausible orbit and is smooth
    tm = orb.t_gps_s[:-1] + 450.0
    p = orb.positions_ecef_m("G05", tm)
    assert np.isfinite(p).all()
    rm = np.linalg.norm(p, axis=1)
    assert np.all(np.abs(rm - 26.56e6) < 0.3e6)
