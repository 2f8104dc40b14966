"""Writing RINEX 3.04 observation files from :class:`Observations`.

Used by the simulator (the demo data set goes through the real reading path)
and by tests (round trips). Values are written as ``F14.3`` with the loss of
lock and signal strength indicators; NaN values are left blank.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from psdbound.io._fields import format_fields
from psdbound.io.nav import Navigation
from psdbound.io.obs import Observations
from psdbound.io.timescales import gps_s_to_datetime64

__all__ = ["format_nav_v3", "format_obs_v3", "write_nav_v3", "write_obs_v3"]


def _hdr(body: str, label: str) -> str:
    return f"{body:<60.60s}{label:<20.20s}\n"


def format_obs_v3(obs: Observations, *, program: str = "psdbound") -> str:
    """Return the text of a RINEX 3.04 observation file for ``obs``.

    Parameters
    ----------
    obs : Observations
        Observations; epochs are written in GPS time.
    program : str, default "psdbound"
        Written in the ``PGM / RUN BY / DATE`` record.

    Returns
    -------
    str
        The complete file text.
    """
    h = obs.header
    systems = list(obs.blocks)
    out = [
        _hdr(
            f"{3.04:9.2f}{'':11s}{'O':<20s}{'M' if len(systems) > 1 else systems[0]:<20s}",
            "RINEX VERSION / TYPE",
        ),
        _hdr(f"{program:<20.20s}{'':20s}{'':20s}", "PGM / RUN BY / DATE"),
        _hdr(h.marker_name or "UNKNOWN", "MARKER NAME"),
        _hdr(f"{'':20s}{h.receiver_type:<20.20s}", "REC # / TYPE / VERS"),
        _hdr(f"{'':20s}{h.antenna_type:<20.20s}", "ANT # / TYPE"),
    ]
    if h.approx_position_m is not None:
        x, y, z = h.approx_position_m
        out.append(_hdr(f"{x:14.4f}{y:14.4f}{z:14.4f}", "APPROX POSITION XYZ"))
    dh, de, dn = h.antenna_delta_hen_m
    out.append(_hdr(f"{dh:14.4f}{de:14.4f}{dn:14.4f}", "ANTENNA: DELTA H/E/N"))
    for s in systems:
        codes = obs.blocks[s].codes
        for k in range(0, len(codes), 13):
            chunk = "".join(f" {c:3s}" for c in codes[k : k + 13])
            lead = f"{s}  {len(codes):3d}" if k == 0 else " " * 6
            out.append(_hdr(lead + chunk, "SYS / # / OBS TYPES"))
    if h.interval_s:
        out.append(_hdr(f"{h.interval_s:10.3f}", "INTERVAL"))
    first = str(gps_s_to_datetime64(obs.t_gps_s[0]))
    y, mo, d = first[:4], first[5:7], first[8:10]
    hh, mi, ss = first[11:13], first[14:16], first[17:]
    out.append(
        _hdr(
            f"{y:>6s}{int(mo):6d}{int(d):6d}{int(hh):6d}{int(mi):6d}{float(ss):13.7f}     GPS",
            "TIME OF FIRST OBS",
        )
    )
    out.append(_hdr("", "END OF HEADER"))

    labels = gps_s_to_datetime64(obs.t_gps_s).astype(str)
    epochs, order_sys, rows = [], [], []
    for k, b in enumerate(obs.blocks.values()):
        present = np.isfinite(b.values).any(axis=2)
        ee, ii = np.nonzero(present)
        chars = format_fields(b.values[ee, ii], b.lli[ee, ii], b.ssi[ee, ii])
        ids = np.frombuffer("".join(b.sats).encode("ascii"), dtype=np.uint8).reshape(-1, 3)
        rows.append(np.concatenate([ids[ii], chars.reshape(ee.size, -1)], axis=1))
        epochs.append(ee)
        order_sys.append(np.full(ee.size, k))
    if rows:
        width = max(r.shape[1] for r in rows)
        rows = [np.pad(r, ((0, 0), (0, width - r.shape[1])), constant_values=32) for r in rows]
        all_rows = np.concatenate(rows)
        ep = np.concatenate(epochs)
        order = np.lexsort((np.concatenate(order_sys), ep))  # stable within a system
        all_rows, ep = all_rows[order], ep[order]
        lines = [r.tobytes().rstrip().decode("ascii") for r in all_rows]
        counts = np.bincount(ep, minlength=obs.t_gps_s.size)
    else:
        lines, counts = [], np.zeros(obs.t_gps_s.size, dtype=np.int64)
    pos = 0
    for e, lab in enumerate(labels):
        c = int(counts[e])
        if not c:
            continue
        out.append(
            f"> {lab[:4]} {lab[5:7]} {lab[8:10]} {lab[11:13]} {lab[14:16]}"
            f"{float(lab[17:]):11.7f}  {int(obs.epoch_flag[e]):d}{c:3d}\n"
        )
        out.append("\n".join(lines[pos : pos + c]) + "\n")
        pos += c
    return "".join(out)


def write_obs_v3(path: str | os.PathLike[str], obs: Observations, **kwargs: str) -> Path:
    """Write ``obs`` as a RINEX 3.04 file atomically (temporary file + rename).

    A ``.gz`` suffix writes a gzip-compressed file (with a fixed timestamp,
    so the same observations always give the same bytes).

    Parameters
    ----------
    path : str or path-like
        Destination.
    obs : Observations
        What to write.
    **kwargs
        Passed to :func:`format_obs_v3`.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    return _write_atomic(Path(path), format_obs_v3(obs, **kwargs))


def _d19(v: float) -> str:
    return f"{v:19.12E}"


def format_nav_v3(nav: Navigation, *, program: str = "psdbound") -> str:
    """Return the text of a RINEX 3.04 navigation file for Keplerian records (GPS, Galileo).

    Parameters
    ----------
    nav : Navigation
        Records to write (systems ``G`` and ``E``; others are skipped).
    program : str, default "psdbound"
        Written in the ``PGM / RUN BY / DATE`` record.

    Returns
    -------
    str
        The complete file text.
    """
    systems = [s for s in ("G", "E") if s in nav.ephemerides]
    kind = "M: MIXED" if len(systems) > 1 else {"G": "G: GPS", "E": "E: GALILEO"}[systems[0]]
    out = [
        _hdr(f"{3.04:9.2f}{'':11s}{'N: GNSS NAV DATA':<20s}{kind:<20s}", "RINEX VERSION / TYPE"),
        _hdr(f"{program:<20.20s}{'':40s}", "PGM / RUN BY / DATE"),
        _hdr("", "END OF HEADER"),
    ]
    for s in systems:
        e = nav.ephemerides[s]
        labels = gps_s_to_datetime64(e.toc_gps_s).astype(str)
        week = np.floor(e.toe_gps_s / 604800.0)
        for k in np.argsort(e.toc_gps_s, kind="stable"):
            lab = labels[k]
            out.append(
                f"{e.sat[k]} {lab[:4]} {lab[5:7]} {lab[8:10]} {lab[11:13]} {lab[14:16]} "
                f"{lab[17:19]}{_d19(e.af0_s[k])}{_d19(e.af1[k])}{_d19(e.af2[k])}\n"
            )
            if s == "G":
                extra = (0.0, week[k], 0.0, 2.0, float(e.health[k]), 0.0, float(e.iode[k]))
            else:
                extra = (float(e.data_source[k]), week[k], 0.0, 3.12, float(e.health[k]), 0.0, 0.0)
            rows = (
                (float(e.iode[k]), e.crs_m[k], e.delta_n_rad_s[k], e.m0_rad[k]),
                (e.cuc_rad[k], e.e[k], e.cus_rad[k], e.sqrt_a[k]),
                (e.toe_sow_s[k], e.cic_rad[k], e.omega0_rad[k], e.cis_rad[k]),
                (e.i0_rad[k], e.crc_m[k], e.omega_rad[k], e.omega_dot_rad_s[k]),
                (e.idot_rad_s[k], extra[0], extra[1], extra[2]),
                (extra[3], extra[4], extra[5], extra[6]),
                (e.toe_sow_s[k], 4.0 if s == "G" else 0.0),
            )
            out.extend("    " + "".join(_d19(float(v)) for v in r) + "\n" for r in rows)
    return "".join(out)


def write_nav_v3(path: str | os.PathLike[str], nav: Navigation, **kwargs: str) -> Path:
    """Write ``nav`` as a RINEX 3.04 navigation file atomically (``.gz`` compresses).

    Parameters
    ----------
    path : str or path-like
        Destination.
    nav : Navigation
        Keplerian records to write.
    **kwargs
        Passed to :func:`format_nav_v3`.

    Returns
    -------
    pathlib.Path
        The written path.
    """
    return _write_atomic(Path(path), format_nav_v3(nav, **kwargs))


def _write_atomic(p: Path, text: str) -> Path:
    import gzip

    data = text.encode("ascii")
    if p.suffix == ".gz":
        data = gzip.compress(data, compresslevel=6, mtime=0)
    tmp = p.with_name(p.name + ".part")
    tmp.write_bytes(data)
    os.replace(tmp, p)
    return p
