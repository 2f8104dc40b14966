"""Benchmark: the whole cutoff map on a local Dask cluster (2 workers), cold cache.

The map of ``psdbound cutoff --map``: the 20 reference stations of the
thesis's appendix C and the default latitude-longitude grid (20 x 90 deg,
36 nodes), a solar-minimum (2020) and a solar-maximum (2024) layer, the
first Monday of March, June, September and December, default settings (the
residual criterion). Target (issue #16): <= 5 min on 2 cores.

Options: ``--install`` also replaces the shipped map
(``psdbound/ionosphere/data/cutoff_map.json``); ``--scheduler ADDRESS``
runs on an existing cluster.

Last line: ``RESULT map_s=<seconds> station_days=<n> per_task_s=<core seconds>``.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time


def main() -> int:
    """Compute the map from an empty cache; print the timing and the validation."""
    from psdbound.ionosphere.workflow import run_world_map

    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--install", action="store_true")
    p.add_argument("--scheduler")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--out", default=None)
    args = p.parse_args()
    with tempfile.TemporaryDirectory(prefix="psdbound-map-bench-") as tmp:
        t0 = time.perf_counter()
        outcome = run_world_map(
            workers=args.workers,
            scheduler=args.scheduler,
            cache_dir=os.path.join(tmp, "cache"),
            out_dir=args.out or os.path.join(tmp, "out"),
            install=args.install,
        )
        elapsed = time.perf_counter() - t0
    doc = outcome.doc
    n = doc["compute"]["n_station_days"]
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(
        f"map: {len(doc['layers'][0]['stations'])} stations + {len(doc['grid']['lat_deg'])} x "
        f"{len(doc['grid']['lon_deg'])} grid, {len(doc['layers'])} layers, {n} station-days, "
        f"{elapsed:.1f} s with {args.workers} workers (load average {load:.2f})"
    )
    for v in doc["validation"]:
        print(
            f"  grid interpolation at the stations ({v['name']}): median |error| "
            f"{100 * v['median_abs_rel_error']:.1f} %, worst {100 * v['worst_rel_error']:+.1f} % "
            f"({v['worst_station']})"
        )
    if args.install:
        print(f"  installed {outcome.files[-1]}")
    print(
        f"RESULT map_s={elapsed:.1f} station_days={n} per_task_s={elapsed * args.workers / n:.2f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
