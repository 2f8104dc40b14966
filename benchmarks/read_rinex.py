"""Benchmark: read the ESBC day into GPS + Galileo phases, LLI flags and elevations.

Times our reader (decompression, parsing, broadcast orbits, elevation of every
satellite at every epoch) and georinex loading the same signals (carrier
phases with indicators of systems G and E) in the same run.

Last line: ``RESULT read_s=<ours> reference_s=<georinex> ratio=<reference/ours>``.
Target (issue #2): read_s <= 3 and ratio >= 20 on the 2-core machine.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from psdbound.io import read_obs, read_orbit
from psdbound.io.geometry import satellite_azel

DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data" / "rinex"
OBS = DATA / "ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz"
NAV = DATA / "ESBC00DNK_R_20201770000_01D_MN.rnx.gz"


def ours() -> tuple[float, int]:
    """Read phases + LLI of G and E, and elevations at every epoch; return (s, n)."""
    t0 = time.perf_counter()
    header_codes = None
    obs = read_obs(OBS, systems="GE")
    header_codes = {s: [c for c in b.codes if c.startswith("L")] for s, b in obs.blocks.items()}
    nav = read_orbit(NAV)
    rx = obs.header.approx_position_m
    n = 0
    for sys_, block in obs.blocks.items():
        k = [block.codes.index(c) for c in header_codes[sys_]]
        tracked = np.isfinite(block.values[:, :, k]).any(axis=2)
        for i, sat in enumerate(block.sats):
            ep = np.flatnonzero(tracked[:, i])
            if ep.size and sat in nav.satellites:
                _, el = satellite_azel(nav, sat, obs.t_gps_s[ep], rx)
                n += int(np.isfinite(el).sum())
    return time.perf_counter() - t0, n


def reference() -> float:
    """georinex loading carrier phases with indicators for G and E."""
    import georinex

    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        georinex.load(OBS, use={"G", "E"}, meas=["L"], useindicators=True)
    return time.perf_counter() - t0


def main() -> int:
    """Run both and print the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=3, help="runs of our reader (best is kept)")
    ap.add_argument("--no-reference", action="store_true", help="skip georinex")
    args = ap.parse_args()
    if not OBS.is_file():
        print(f"real data not found: {OBS}", file=sys.stderr)
        return 2
    runs = [ours() for _ in range(args.repeat)]
    read_s = min(r[0] for r in runs)
    print(
        f"ours: {read_s:.2f} s (runs {', '.join(f'{r[0]:.2f}' for r in runs)}); "
        f"{runs[0][1]} satellite-epochs with elevations"
    )
    if args.no_reference:
        print(f"RESULT read_s={read_s:.3f}")
        return 0
    ref_s = reference()
    print(f"georinex: {ref_s:.2f} s")
    print(f"RESULT read_s={read_s:.3f} reference_s={ref_s:.3f} ratio={ref_s / read_s:.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
