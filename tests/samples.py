"""Small synthetic RINEX files for tests that must run without ../shared/data."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from psdbound.io import ObsHeader
from psdbound.io.obs import Observations, SystemBlock
from psdbound.io.signals import wavelength_m
from psdbound.io.timescales import calendar_to_gps_s
from psdbound.io.write import write_obs_v3


def _header(marker: str, interval_s: float, codes) -> ObsHeader:
    """A GPS RINEX 3.04 header of a synthetic receiver near ESBC."""
    return ObsHeader(
        version=3.04,
        file_system="G",
        marker_name=marker,
        receiver_type="SYNTH",
        antenna_type="NONE",
        approx_position_m=np.array([3582105.291, 532589.7313, 5232754.8054]),
        antenna_delta_hen_m=np.zeros(3),
        interval_s=interval_s,
        time_system="GPS",
        obs_types={"G": codes},
    )


def small_observations(n_epoch: int = 40, interval_s: float = 30.0, seed: int = 1) -> Observations:
    """Two GPS satellites, L1C/L2W/C1C/S1C, 30 s, with a loss-of-lock flag and a gap."""
    rng = np.random.default_rng(seed)
    t0 = float(calendar_to_gps_s(2020, 6, 25, 0, 0, 0.0))
    t = t0 + interval_s * np.arange(n_epoch)
    sats = ("G05", "G12")
    codes = ("C1C", "L1C", "L2W", "S1C")
    v = np.empty((n_epoch, 2, 4))
    v[:, :, 0] = 2.2e7 + rng.normal(0, 1, (n_epoch, 2)).cumsum(axis=0)
    v[:, :, 1] = v[:, :, 0] / 0.19029367 + 1000.0
    v[:, :, 2] = v[:, :, 0] / 0.24421021 - 500.0
    v[:, :, 3] = 45.0
    v = np.round(v, 3)
    v[10:13, 1, :] = np.nan  # G12 missing for three epochs
    lli = np.where(np.isfinite(v), 0, -1).astype(np.int8)
    lli[:, :, 0] = -1
    lli[:, :, 3] = -1
    lli[20, 0, 1] = 1  # loss of lock on G05 L1C
    ssi = np.where(np.isfinite(v), 7, -1).astype(np.int8)
    ssi[:, :, 3] = -1
    header = _header("TEST", interval_s, codes)
    block = SystemBlock("G", sats, codes, v, lli, ssi)
    return Observations("synthetic", header, t, np.zeros(n_epoch, np.int8), {"G": block})


def write_small(path: Path, **kwargs) -> Path:
    """Write :func:`small_observations` as RINEX 3 to ``path``."""
    return write_obs_v3(path, small_observations(**kwargs))


NAV3_TEXT = """\
     3.04           N: GNSS NAV DATA    G: GPS              RINEX VERSION / TYPE
test                                                        PGM / RUN BY / DATE
                                                            END OF HEADER
"""


LAM1 = wavelength_m("G01", "L1C")
LAM2 = wavelength_m("G01", "L2W")


def make_obs(l1_m, l2_m, lli1=None, interval_s=30.0, t=None, flags=None):
    """One GPS satellite G07 with given phases in metres (NaN = not tracked)."""
    n = len(l1_m)
    if t is None:
        t = 1.277e9 + interval_s * np.arange(n)
    v = np.stack([np.asarray(l1_m) / LAM1, np.asarray(l2_m) / LAM2], axis=1)[:, None, :]
    lli = np.where(np.isfinite(v), 0, -1).astype(np.int8)
    if lli1 is not None:
        lli[:, 0, 0] = lli1
    header = ObsHeader(
        version=3.04,
        file_system="G",
        marker_name="T",
        receiver_type="",
        antenna_type="",
        approx_position_m=None,
        antenna_delta_hen_m=np.zeros(3),
        interval_s=interval_s,
        time_system="GPS",
        obs_types={"G": ("L1C", "L2W")},
    )
    block = SystemBlock("G", ("G07",), ("L1C", "L2W"), v, lli, lli.copy())
    f = np.zeros(n, np.int8) if flags is None else np.asarray(flags, np.int8)
    return Observations("mem", header, np.asarray(t, float), f, {"G": block})


def moving_observations(n_epoch: int = 40, interval_s: float = 30.0, seed: int = 2) -> Observations:
    """Two GPS satellites moving at realistic range rates (C1C, L1C, L2W, D1C, S1C).

    Phases and Doppler follow the pseudorange (as real data do), so the
    reader's phase-rate and value-range checks see physical columns.
    """
    rng = np.random.default_rng(seed)
    t0 = float(calendar_to_gps_s(2020, 6, 25, 0, 0, 0.0))
    t = t0 + interval_s * np.arange(n_epoch)
    sats = ("G05", "G12")
    codes = ("C1C", "L1C", "L2W", "D1C", "S1C")
    rate = np.array([600.0, -450.0])  # m/s
    rho = 2.2e7 + rate[None, :] * (t - t0)[:, None]
    v = np.empty((n_epoch, 2, 5))
    v[:, :, 0] = rho + rng.normal(0, 0.5, (n_epoch, 2))
    v[:, :, 1] = rho / LAM1 + 1234.0
    v[:, :, 2] = rho / LAM2 - 4321.0
    v[:, :, 3] = -rate[None, :] / LAM1
    v[:, :, 4] = 45.0
    v = np.round(v, 3)
    lli = np.full(v.shape, -1, np.int8)
    ssi = np.full(v.shape, -1, np.int8)
    header = _header("MOVE", interval_s, codes)
    block = SystemBlock("G", sats, codes, v, lli, ssi)
    return Observations("moving", header, t, np.zeros(n_epoch, np.int8), {"G": block})


#: A small RINEX 2.11 observation file: GPS, C1 L1 L2 P2, three epochs at 30 s.
V2_TEXT = """\
     2.11           OBSERVATION DATA    G (GPS)             RINEX VERSION / TYPE
test                                                        PGM / RUN BY / DATE
V2                                                          MARKER NAME
  3582105.2910   532589.7313  5232754.8054                  APPROX POSITION XYZ
        0.0000        0.0000        0.0000                  ANTENNA: DELTA H/E/N
     4    C1    L1    L2    P2                              # / TYPES OF OBSERV
    30.000                                                  INTERVAL
  2020     6    25     0     0    0.0000000     GPS         TIME OF FIRST OBS
                                                            END OF HEADER
 20  6 25  0  0  0.0000000  0  2G05G12
  22000000.000 7 115612000.000 7  90087000.000 6  22000001.000 6
  23000000.000 7 120867000.000 7  94182000.000 6  23000001.000 6
 20  6 25  0  0 30.0000000  0  2G05G12
  22018000.000 7 115706591.000 7  90160708.000 6  22018001.000 6
  22986500.000 7 120796056.000 7  94126720.000 6  22986501.000 6
 20  6 25  0  1  0.0000000  0  2G05G12
  22036000.000 7 115801182.000 7  90234416.000 6  22036001.000 6
  22973000.000 7 120725112.000 7  94071440.000 6  22973001.000 6
"""


def esbc_hours(path: Path, hours) -> Path:
    """Write the epochs of the shared ESBC day that fall in the given hours (RINEX 3, plain).

    ``hours``: iterable of hour numbers, e.g. ``range(0, 8)``; the header is kept.
    """
    import hatanaka
    from conftest import ESBC_OBS, shared_file

    text = hatanaka.decompress(shared_file(ESBC_OBS).read_bytes()).decode()
    head, body = text.split("END OF HEADER", 1)
    head += "END OF HEADER" + body[: body.index("\n") + 1]
    wanted = {f"{h:02d}" for h in hours}
    out, keep = [], False
    for line in body[body.index("\n") + 1 :].splitlines(keepends=True):
        if line.startswith(">"):
            keep = line[13:15] in wanted
        if keep:
            out.append(line)
    path.write_text(head + "".join(out))
    return path
