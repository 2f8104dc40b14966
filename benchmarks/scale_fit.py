"""Benchmark: one ``psdbound fit`` (defaults, dual-frequency) on 24 h of 1 Hz data.

Simulates one GPS antenna for 24 h at 1 s (cached in ``benchmarks/out/``,
which git ignores), then runs ``python -m psdbound fit OBS --nav NAV`` in a
subprocess under ``/usr/bin/time -v`` (wall time and peak RSS of the whole
CLI, imports and report included), and times reading the observation file
in this process (best of ``--repeat``). There is no reference run: the
competitor figure quoted in issue 18 (gnssmultipath, a 24 h multi-GNSS file
read in 0.8 s) is for its reader only and a different file.

Target (issue 18, part 5): fit24h_1hz_s <= 10 and fit24h_1hz_peak_mb <= 500.

Also times the library call alone (``psdbound.fit`` without the reports, in a
fresh process, imports included).

Last line: ``RESULT fit24h_1hz_s=<wall s> fit24h_1hz_peak_mb=<MB>
fit24h_1hz_library_s=<s> fit24h_1hz_library_peak_mb=<MB> read_s=<s> read_peak_mb=<MB>``.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

OUT = Path(__file__).resolve().parent / "out" / "scale_fit"
NAME = "scale24h"


def simulated() -> tuple[Path, Path]:
    """Return the 24 h, 1 Hz observation and navigation files (simulated on first use)."""
    obs, nav = OUT / f"{NAME}-A_MO.rnx.gz", OUT / f"{NAME}_MN.rnx.gz"
    if not (obs.is_file() and nav.is_file()):
        from psdbound.simulate import Scenario, simulate

        t0 = time.perf_counter()
        sc = Scenario(
            name=NAME,
            duration_s=86400.0,
            interval_s=1.0,
            dual_antenna=False,
            start_gps="2020-11-24T00:00:00",
            seed=18,
        )
        simulate(sc, OUT)
        print(f"simulated {obs.name} in {time.perf_counter() - t0:.1f} s")
    return obs, nav


def _peak_mb(stderr: str) -> float:
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", stderr)
    return int(m.group(1)) / 1024 if m else float("nan")


def run_fit(obs: Path, nav: Path) -> tuple[float, float, int, str]:
    """Run the CLI fit once; return (wall s, peak MB, exit code, stdout)."""
    with tempfile.TemporaryDirectory() as work:
        cmd = [
            sys.executable,
            "-m",
            "psdbound",
            "fit",
            str(obs),
            "--nav",
            str(nav),
            "--out",
            str(Path(work) / "fit"),
            "--quiet",
        ]
        timer = ["/usr/bin/time", "-v"] if Path("/usr/bin/time").is_file() else []
        t0 = time.perf_counter()
        r = subprocess.run(
            timer + cmd, capture_output=True, text=True, cwd=work, env=dict(os.environ)
        )
        wall = time.perf_counter() - t0
    peak = _peak_mb(r.stderr)
    if not timer:  # no GNU time: the largest child waited for so far
        import resource

        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    return wall, peak, r.returncode, r.stdout + (r.stderr if r.returncode not in (0, 3) else "")


def run_library_fit(obs: Path, nav: Path) -> tuple[float, float]:
    """``psdbound.fit`` alone (no report) in a fresh process: wall s from import, peak MB."""
    code = (
        "import resource, sys, time\n"
        "t0 = time.perf_counter()\n"
        "import psdbound\n"
        "res = psdbound.fit(sys.argv[1], nav=sys.argv[2])\n"
        "rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024\n"
        "print(time.perf_counter() - t0, rss)\n"
    )
    r = subprocess.run(
        [sys.executable, "-c", code, str(obs), str(nav)], capture_output=True, text=True, check=True
    )
    wall, peak = map(float, r.stdout.split()[-2:])
    return wall, peak


def time_read(obs: Path, repeat: int) -> tuple[float, float]:
    """Best wall time of ``read_obs(obs, systems="G")`` and the peak RSS, MB (own process)."""
    code = (
        "import resource, sys, time\n"
        "from psdbound.io import read_obs\n"
        "best = float('inf')\n"
        f"for _ in range({repeat}):\n"
        "    t0 = time.perf_counter(); read_obs(sys.argv[1], systems='G')\n"
        "    best = min(best, time.perf_counter() - t0)\n"
        "print(best, resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)\n"
    )
    r = subprocess.run(
        [sys.executable, "-c", code, str(obs)], capture_output=True, text=True, check=True
    )
    best, peak = map(float, r.stdout.split()[-2:])
    return best, peak


def main() -> int:
    """Simulate (once), time the fit and the reader; print the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--repeat", type=int, default=1, help="fit runs (best is kept)")
    args = ap.parse_args()
    obs, nav = simulated()
    runs = [run_fit(obs, nav) for _ in range(args.repeat)]
    for wall, peak, code, out in runs:
        print(f"fit: {wall:.2f} s, peak {peak:.0f} MB, exit {code}")
        if code not in (0, 3):
            print(out, file=sys.stderr)
            return 1
    print(runs[0][3].strip())
    wall, peak = min(r[0] for r in runs), max(r[1] for r in runs)
    lib_s, lib_peak = run_library_fit(obs, nav)
    print(f"library fit (psdbound.fit, no report): {lib_s:.2f} s, peak {lib_peak:.0f} MB")
    read_s, read_peak = time_read(obs, 2)
    print(
        f"RESULT fit24h_1hz_s={wall:.2f} fit24h_1hz_peak_mb={peak:.0f} "
        f"fit24h_1hz_library_s={lib_s:.2f} fit24h_1hz_library_peak_mb={lib_peak:.0f} "
        f"read_s={read_s:.2f} read_peak_mb={read_peak:.0f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
