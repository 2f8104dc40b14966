"""Benchmark: ``python -m psdbound campaign`` on 1, 7 and 30 station-days at 30 s.

Simulates 3 stations x 10 days of 24 h at 30 s (cached in
``benchmarks/out/``; each day's navigation file is simulated once and used
by every station of that day, so the campaign gets one navigation file per
day), then runs the campaign CLI on the first 1, 7 and 30 station-days on a
local 2-worker Dask cluster, each run with a fresh, empty task cache. The
peak RSS of every worker process is sampled (psutil, every 0.1 s).

Target (issue 18, part 5): campaign_30d_s <= 300 and worker_peak_mb <= 1024,
with the cost per station-day about constant (linear in data).

Last line: ``RESULT campaign_1d_s=... campaign_7d_s=... campaign_30d_s=...
per_day_s_1=... per_day_s_30=... worker_peak_mb=...``.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import psutil

OUT = Path(__file__).resolve().parent / "out" / "scale_campaign"
STATIONS = (("SCA1", 41.84, -87.63), ("SCB1", 55.6, 12.5), ("SCC1", -33.9, 151.2))
N_DAYS = 10
FIRST_DAY = 1  # 2021-01-01 + day index


def _name(station: str, doy: int) -> str:
    return f"{station}00USA_R_2021{doy:03d}0000_01D_30S"


def simulated() -> list[tuple[Path, Path]]:
    """Return (observation, navigation) per station-day, day-major (simulated on first use)."""
    from psdbound.simulate import Scenario, simulate

    files = []
    for d in range(N_DAYS):
        doy = FIRST_DAY + d
        nav = None
        for s, (st, lat, lon) in enumerate(STATIONS):
            name = _name(st, doy)
            folder = OUT / name
            obs = folder / f"{name}-A_MO.rnx.gz"
            if not obs.is_file():
                sc = Scenario(
                    name=name,
                    duration_s=86400.0,
                    interval_s=30.0,
                    dual_antenna=False,
                    lat_deg=lat,
                    lon_deg=lon,
                    start_gps=f"2021-01-{doy:02d}T00:00:00",
                    seed=1000 * s + doy,
                    nav_path=str(nav) if nav else None,
                )
                simulate(sc, folder)
            if nav is None:
                nav = folder / f"{name}_MN.rnx.gz"
            files.append((obs, nav))
    return files


def _watch(pid: int, stop: threading.Event, peaks: dict[int, float]) -> None:
    """Sample the RSS of every descendant of ``pid`` (the Dask workers) until ``stop``."""
    try:
        root = psutil.Process(pid)
    except psutil.Error:
        return
    while not stop.is_set():
        try:
            kids = root.children(recursive=True)
        except psutil.Error:
            break
        for k in kids:
            try:
                peaks[k.pid] = max(peaks.get(k.pid, 0.0), k.memory_info().rss / 2**20)
            except psutil.Error:
                pass
        stop.wait(0.1)


def run_campaign(files: list[tuple[Path, Path]], workers: int) -> tuple[float, float, float]:
    """Run the campaign CLI; return (wall s, largest worker peak MB, main process peak MB)."""
    obs = [str(o) for o, _ in files]
    navs = sorted({str(n) for _, n in files})
    with tempfile.TemporaryDirectory() as work:
        cmd = [
            sys.executable,
            "-m",
            "psdbound",
            "campaign",
            *obs,
            "--nav",
            *navs,
            "--out",
            str(Path(work) / "campaign"),
            "--workers",
            str(workers),
            "--cache-dir",
            str(Path(work) / "cache"),
        ]
        peaks: dict[int, float] = {}
        stop = threading.Event()
        t0 = time.perf_counter()
        proc = subprocess.Popen(
            cmd,
            cwd=work,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            env=dict(os.environ),
        )
        watcher = threading.Thread(target=_watch, args=(proc.pid, stop, peaks), daemon=True)
        watcher.start()
        main_peak = 0.0
        while proc.poll() is None:
            try:
                main_peak = max(main_peak, psutil.Process(proc.pid).memory_info().rss / 2**20)
            except psutil.Error:
                pass
            time.sleep(0.1)
        out, err = proc.communicate()
        wall = time.perf_counter() - t0
        stop.set()
        watcher.join()
    if proc.returncode not in (0, 3):  # 3: some station's pooled bound is not bounded
        print(out, err, file=sys.stderr)
        raise SystemExit(f"campaign failed (exit {proc.returncode})")
    return wall, max(peaks.values(), default=float("nan")), main_peak


def main() -> int:
    """Simulate (once), run the campaigns, print the table and the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--workers", type=int, default=2, help="local Dask workers (2)")
    ap.add_argument("--sizes", default="1,7,30", help="station-days per run (1,7,30)")
    args = ap.parse_args()
    files = simulated()
    sizes = [int(s) for s in args.sizes.split(",")]
    rows = []
    for n in sizes:
        wall, worker_peak, main_peak = run_campaign(files[:n], args.workers)
        rows.append((n, wall, worker_peak, main_peak))
    print(f"{'station-days':>12} {'wall s':>8} {'s/day':>7} {'worker MB':>10} {'main MB':>8}")
    for n, wall, wp, mp in rows:
        print(f"{n:>12d} {wall:>8.1f} {wall / n:>7.2f} {wp:>10.0f} {mp:>8.0f}")
    res = " ".join(f"campaign_{n}d_s={w:.1f}" for n, w, _, _ in rows)
    per = " ".join(f"per_day_s_{n}={w / n:.2f}" for n, w, _, _ in (rows[0], rows[-1]))
    print(f"RESULT {res} {per} worker_peak_mb={max(r[2] for r in rows):.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
