"""Benchmark: how long a user waits for ``--help`` or a usage error, whole process (issue 31).

Every subcommand's ``--help`` and one usage error (an unknown option) are run
as separate processes, ``python3.11 -m psdbound ...``, with this checkout's
package first on the path; each is timed from process start to exit
(interpreter start-up, imports, argument parsing, output, shutdown) as the
median of ``--repeat`` runs. The reference is the bare interpreter
(``python3.11 -c pass``), the floor no command can go under.

Target (issue 31): every command's ``--help`` and usage error in at most
0.3 s. The package's subpackages import their public names on first use
(:mod:`psdbound.common.lazy`) and the option classes live in modules that
import nothing heavy, so ``--help`` no longer loads numpy's, scipy's and
matplotlib's analysis code (1.7 s for ``fit --help`` before).

Last line::

    RESULT python_s=... worst_s=... worst=... n_commands=... all_under_0.3s=...
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

from _simfit import checkout_env

COMMANDS = (
    "fit",
    "export",
    "campaign",
    "simulate",
    "inspect",
    "cutoff",
    "validate",
    "overbound",
    "budget",
    "report",
)
TARGET_S = 0.3


def timed(args: list[str], repeat: int) -> float:
    """Median wall time of ``repeat`` whole-process runs of ``args``, seconds."""
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        subprocess.run(args, capture_output=True, env=checkout_env(), check=False)
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main() -> int:
    """Time every command; print a table and the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=5, help="runs per case (median)")
    args = ap.parse_args()
    py = [sys.executable]
    base = timed([*py, "-c", "pass"], args.repeat)
    print(f"{'case':<34}{'wall s':>8}")
    print(f"{'python -c pass (floor)':<34}{base:>8.3f}")
    rows = []
    for cmd in COMMANDS:
        for label, extra in (("--help", ["--help"]), ("usage error", ["--no-such-option"])):
            t = timed([*py, "-m", "psdbound", cmd, *extra], args.repeat)
            rows.append((f"{cmd} {label}", t))
            print(f"{cmd + ' ' + label:<34}{t:>8.3f}")
    worst = max(rows, key=lambda r: r[1])
    ok = all(t <= TARGET_S for _, t in rows)
    print(
        f"RESULT python_s={base:.3f} worst_s={worst[1]:.3f} worst={worst[0].replace(' ', '_')} "
        f"n_commands={len(COMMANDS)} all_under_0.3s={str(ok).lower()}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
