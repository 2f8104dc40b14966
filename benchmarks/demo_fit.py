"""Benchmark: ``python -m psdbound fit`` with no arguments, end to end.

Runs the CLI in an empty temporary folder with an empty cache, so the demo
data set is simulated first (cold), then a second time with the cache warm.
Target (issue #7): demo_fit_s <= 60 s (cold run).

Last line: ``RESULT demo_fit_s=<cold seconds> warm_s=<seconds>``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time


def main() -> int:
    """Time a cold and a warm demo fit; print the RESULT line."""
    with tempfile.TemporaryDirectory() as work, tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, PSDBOUND_CACHE=cache)
        times = []
        for _ in range(2):
            t0 = time.perf_counter()
            r = subprocess.run(
                [sys.executable, "-m", "psdbound", "fit", "--quiet"],
                cwd=work,
                env=env,
                capture_output=True,
                text=True,
            )
            times.append(time.perf_counter() - t0)
            if r.returncode != 0:
                print(r.stderr, file=sys.stderr)
                return 1
        print(r.stdout.strip())
    print(f"RESULT demo_fit_s={times[0]:.2f} warm_s={times[1]:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
