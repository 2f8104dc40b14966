"""RINEX 4 test files made from RINEX 3 ones (no real RINEX 4 file is in ../shared/data).

* :func:`obs_to_v4`: a RINEX 3 observation file as RINEX 4.0x -- the version in
  line 1 and the new header records ``DOI``, ``LICENSE OF USE`` and
  ``STATION INFORMATION``; the data section is the same in both versions.
* :func:`nav_to_v4`: a RINEX 3 navigation file as RINEX 4.0x -- each record
  headed ``> EPH <sat> <message>`` (the message type as the RINEX 4.00
  specification assigns it: GPS/QZSS/NavIC ``LNAV``, Galileo ``INAV`` or
  ``FNAV`` by the data-source bits, BeiDou ``D1`` or ``D2`` (GEO), GLONASS
  ``FDMA``, SBAS ``SBAS``); the header's ``IONOSPHERIC CORR`` and
  ``TIME SYSTEM CORR`` records become ``ION`` and ``STO`` records, and an
  ``EOP`` record and a GPS ``CNAV`` record (both to be skipped) are added.
* :func:`write_variants`: one text as plain, gzip, Hatanaka, Hatanaka+gzip
  and zip files.
"""

from __future__ import annotations

import gzip
import zipfile
from collections.abc import Sequence
from pathlib import Path

from psdbound.io.ephemeris import is_beidou_geo

#: The RINEX 4 header records added to observation files (body, label).
V4_OBS_RECORDS = (
    ("10.57677/PSDBOUND-TEST", "DOI"),
    ("CC BY 4.0 (https://creativecommons.org/licenses/by/4.0/)", "LICENSE OF USE"),
    ("https://example.org/stations/ESBC00DNK", "STATION INFORMATION"),
)


def header_line(body: str, label: str) -> str:
    """A header line: the body in columns 1-60, the label from column 61."""
    return f"{body:<60.60s}{label}"


def with_version(line1: str, version: str) -> str:
    """Line 1 (RINEX VERSION / TYPE) with ``version`` in columns 1-9."""
    return f"{version:>9s}{line1[9:]}"


def obs_to_v4(
    text: bytes, version: str = "4.00", records: Sequence[tuple[str, str]] = V4_OBS_RECORDS
) -> bytes:
    """Return a RINEX 3 observation file's text as a RINEX 4 file.

    Parameters
    ----------
    text : bytes
        Plain RINEX 3 observation file text.
    version : str, default "4.00"
        Written in columns 1-9 of line 1.
    records : sequence of (str, str)
        Header records (body, label) inserted before ``END OF HEADER``.
    """
    lines = text.split(b"\n")
    assert b"RINEX VERSION / TYPE" in lines[0] and lines[0][:9].strip().startswith(b"3.")
    end = next(i for i, ln in enumerate(lines) if ln[60:].strip() == b"END OF HEADER")
    new = [header_line(b, lab).encode("ascii") for b, lab in records]
    lines[0] = with_version(lines[0].decode("ascii"), version).encode("ascii")
    return b"\n".join(lines[:end] + new + lines[end:])


def cut_obs(text: bytes, n_epochs: int) -> bytes:
    """Return the header and the first ``n_epochs`` epochs of a RINEX 3/4 observation file."""
    pos = text.find(b"END OF HEADER")
    for _ in range(n_epochs + 1):
        pos = text.find(b"\n> ", pos + 1)
        if pos < 0:
            return text
    return text[: pos + 1]


def write_variants(tmp: Path, stem: str, text: bytes) -> dict[str, Path]:
    """Write ``text`` as plain, gzip, Hatanaka, Hatanaka+gzip and zip files."""
    import hatanaka

    crx = hatanaka.rnx2crx(text)
    out = {
        "plain": tmp / f"{stem}.rnx",
        "gzip": tmp / f"{stem}.rnx.gz",
        "hatanaka": tmp / f"{stem}.crx",
        "hatanaka+gzip": tmp / f"{stem}.crx.gz",
        "zip": tmp / f"{stem}.zip",
    }
    out["plain"].write_bytes(text)
    out["gzip"].write_bytes(gzip.compress(text, mtime=0))
    out["hatanaka"].write_bytes(crx)
    out["hatanaka+gzip"].write_bytes(gzip.compress(crx, mtime=0))
    with zipfile.ZipFile(out["zip"], "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr(f"{stem}.rnx", text)
    return out


# ---------------------------------------------------------------- navigation


def _d19(v: float) -> str:
    return f"{v:19.12E}"


def message_type(sat: str, rec: list[str]) -> str:
    """The RINEX 4.00 message type of a RINEX 3 ephemeris record of ``sat``."""
    system = sat[0]
    if system == "E":
        source = int(float(rec[5][23:42].replace("D", "E")))
        return "FNAV" if source & 2 else "INAV"
    if system == "C":
        return "D2" if is_beidou_geo(sat) else "D1"
    return {"G": "LNAV", "J": "LNAV", "I": "LNAV", "R": "FDMA", "S": "SBAS"}[system]


def _records(body: list[str]) -> list[list[str]]:
    """The records of a RINEX 3 navigation body (a record starts with a satellite id)."""
    out: list[list[str]] = []
    for ln in body:
        if not ln.strip():
            continue
        if ln[:1] != " ":
            out.append([ln])
        else:
            out[-1].append(ln)
    return out


def _epoch(rec0: str) -> str:
    """``yyyy mm dd hh mm ss`` of a RINEX 3 record's first line."""
    return rec0[4:23]


def _corrections(header: list[str], epoch: str) -> list[list[str]]:
    """ION and STO records from the header's IONOSPHERIC CORR and TIME SYSTEM CORR records."""
    ion = {ln[:4].strip(): ln for ln in header if ln[60:].strip() == "IONOSPHERIC CORR"}
    sto = [ln for ln in header if ln[60:].strip() == "TIME SYSTEM CORR"]
    out = []

    def nums(ln: str) -> list[float]:
        return [float(ln[k : k + 12].replace("D", "E")) for k in (5, 17, 29, 41)]

    if "GPSA" in ion and "GPSB" in ion:
        a, b = nums(ion["GPSA"]), nums(ion["GPSB"])
        out.append(
            [
                "> ION G01 LNAV",
                f"    {epoch}" + "".join(map(_d19, a[:3])),
                "    " + "".join(map(_d19, [a[3], *b[:3]])),
                "    " + _d19(b[3]) + _d19(0.0),
            ]
        )
    if "GAL" in ion:
        g = nums(ion["GAL"])
        out.append(
            ["> ION E01 IFNV", f"    {epoch}" + "".join(map(_d19, g[:3])), "    " + _d19(0.0)]
        )
    for ln in sto:
        kind = ln[:4]
        a0, a1 = float(ln[5:22].replace("D", "E")), float(ln[22:38].replace("D", "E"))
        t_ref = float(ln[38:45])
        sat = "E01 IFNV" if kind.startswith("GA") else "G01 LNAV"
        utc = {"GPUT": "UTC(USNO)", "GAUT": "UTCGAL"}.get(kind, "")
        out.append(
            [
                f"> STO {sat}",
                f"    {epoch} {kind:<18s} {'':18s} {utc:<18s}".rstrip(),
                "    " + "".join(map(_d19, (t_ref, a0, a1, 0.0))),
            ]
        )
    return out


def eop_record(epoch: str) -> list[str]:
    """A GPS CNAV Earth orientation record (three lines after its header)."""
    return [
        "> EOP G01 CNVX",
        f"    {epoch}" + "".join(map(_d19, (-4.02e-2, 3.95e-5, 0.0))),
        " " * 23 + "".join(map(_d19, (3.56e-1, 2.60e-3, 0.0))),
        "    " + "".join(map(_d19, (4392.0, -1.94e-2, -1.41e-4, 0.0))),
    ]


def cnav_record(lnav: list[str]) -> list[str]:
    """A GPS CNAV-shaped record (nine lines) built from an LNAV record of the same satellite.

    Its times of clock and ephemeris are 30 min later and its mean anomaly 1 rad off: a reader
    that took it for an LNAV record would put the satellite thousands of km
    away near that time.
    """
    first = lnav[0]
    minute = int(first[18:20]) + 30
    first = f"{first[:18]}{minute:02d}{first[20:]}"
    m0 = float(lnav[1][61:80].replace("D", "E")) + 1.0
    orbit1 = lnav[1][:61] + _d19(m0)
    toe = float(lnav[3][4:23].replace("D", "E")) + 1800.0
    orbit3 = "    " + _d19(toe) + lnav[3][23:]
    return [
        "> EPH " + first[:3] + " CNAV",
        first,
        orbit1,
        lnav[2],
        orbit3,
        *lnav[4:7],
        "    " + _d19(float(lnav[7][4:23].replace("D", "E"))) + _d19(0.0),
        "    " + "".join(map(_d19, (0.0, 0.0, 0.0, 0.0))),
    ]


def nav_to_v4(text: str, version: str = "4.00") -> str:
    """Return a RINEX 3 navigation file's text as a RINEX 4 file (see the module docstring).

    The ``ION``/``STO`` records come first (as in the IGS merged files), the
    ``EOP`` and ``CNAV`` records after the 100th ephemeris.
    """
    lines = text.split("\n")
    end = next(i for i, ln in enumerate(lines) if ln[60:].strip() == "END OF HEADER")
    header, records = lines[: end + 1], _records(lines[end + 1 :])
    epoch = _epoch(records[0][0])
    line1 = with_version(
        header_line(f"{'':9s}{'':11s}{'N: GNSS NAV DATA':<20s}M: MIXED", "RINEX VERSION / TYPE"),
        version,
    )
    moved = ("IONOSPHERIC CORR", "TIME SYSTEM CORR", "RINEX VERSION / TYPE", "END OF HEADER")
    kept = [ln for ln in header if ln[60:].strip() not in moved]
    out = [
        line1,
        *kept,
        header_line("10.57677/PSDBOUND-TEST", "DOI"),
        header_line("", "END OF HEADER"),
    ]
    for rec in _corrections(header, epoch):
        out.extend(rec)
    gps = next(r for r in records if r[0][0] == "G")
    for k, rec in enumerate(records):
        out.append(f"> EPH {rec[0][:3]} {message_type(rec[0][:3], rec)}")
        out.extend(rec)
        if k == 100:
            out.extend(eop_record(epoch) + cnav_record(gps))
    return "\n".join(out) + "\n"
