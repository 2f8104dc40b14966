"""Writing RINEX 3.04 observation files from :class:`Observations`.

Used by the simulator (the demo data set goes through the real reading path)
and by tests (round trips). Values are written as ``F14.3`` with the loss of
lock and signal strength indicators; NaN values are left blank.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from psdbound.io.obs import Observations
from psdbound.io.timescales import gps_s_to_datetime64

__all__ = ["format_obs_v3", "write_obs_v3"]


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
    cells = {}
    for s, b in obs.blocks.items():
        v = b.values
        txt = np.char.mod("%14.3f", np.where(np.isfinite(v), v, 0.0))
        txt = np.where(np.isfinite(v), txt, " " * 14)
        lli = np.where(b.lli >= 0, np.char.mod("%d", np.maximum(b.lli, 0)), " ")
        ssi = np.where(b.ssi >= 0, np.char.mod("%d", np.maximum(b.ssi, 0)), " ")
        cells[s] = (np.char.add(np.char.add(txt, lli), ssi), np.isfinite(v).any(axis=2))
    for e, lab in enumerate(labels):
        recs = []
        for s, b in obs.blocks.items():
            field, present = cells[s]
            for i in np.flatnonzero(present[e]):
                recs.append((b.sats[i] + "".join(field[e, i])).rstrip())
        if not recs:
            continue
        out.append(
            f"> {lab[:4]} {lab[5:7]} {lab[8:10]} {lab[11:13]} {lab[14:16]}"
            f"{float(lab[17:]):11.7f}  {int(obs.epoch_flag[e]):d}{len(recs):3d}\n"
        )
        out.extend(r + "\n" for r in recs)
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
    import gzip

    p = Path(path)
    data = format_obs_v3(obs, **kwargs).encode("ascii")
    if p.suffix == ".gz":
        data = gzip.compress(data, mtime=0)
    tmp = p.with_name(p.name + ".part")
    tmp.write_bytes(data)
    os.replace(tmp, p)
    return p
