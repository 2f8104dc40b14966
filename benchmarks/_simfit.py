"""Shared scaffolding of the benchmarks that simulate days and fit them through the CLI.

``run_cli`` runs ``python -m psdbound`` with this checkout's package first on
the path (so a benchmark measures the code beside it, wherever it is run
from) and never raises on an exit code; ``tail`` keeps the last lines of its
output for a message; ``simulated_truth`` finds what ``simulate`` wrote in a
folder and ``fit_simulated`` fits it; ``fmt`` prints a number or ``-`` for
a missing one.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

__all__ = ["REPO", "checkout_env", "fit_simulated", "fmt", "run_cli", "simulated_truth", "tail"]

#: The checkout the benchmarks belong to.
REPO = Path(__file__).resolve().parent.parent


def checkout_env() -> dict[str, str]:
    """Return the environment with this checkout's package first on ``PYTHONPATH``."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(REPO), env.get("PYTHONPATH")) if p)
    return env


def run_cli(args: list[str], cwd: Path) -> subprocess.CompletedProcess[str]:
    """Run ``python -m psdbound ARGS`` with this checkout's package; never raises on exit codes."""
    return subprocess.run(
        [sys.executable, "-m", "psdbound", *args],
        cwd=cwd,
        env=checkout_env(),
        capture_output=True,
        text=True,
    )


def tail(proc: subprocess.CompletedProcess[str], n: int = 4) -> str:
    """Return the last ``n`` lines of a run's output, joined."""
    lines = (proc.stdout + proc.stderr).strip().splitlines()
    return " | ".join(lines[-n:])


def fmt(v: Any, spec: str = ".3f") -> str:
    """Format a number, or ``-`` for None or a non-finite value."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "-"
    return format(v, spec)


def simulated_truth(folder: Path) -> Path:
    """Return the one ``*_truth.json`` that ``psdbound simulate`` wrote in ``folder``.

    Raises
    ------
    RuntimeError
        When there is not exactly one.
    """
    found = sorted(folder.glob("*_truth.json"))
    if len(found) != 1:
        raise RuntimeError(f"expected one *_truth.json in {folder}, found {len(found)}")
    return found[0]


def fit_simulated(truth: Path, out: Path) -> tuple[int, str]:
    """Run ``psdbound fit`` on the simulated files; return (exit code, message tail)."""
    files = json.loads(truth.read_text())["files"]
    obs = [str(truth.parent / f) for f in files["obs"]]
    nav = str(truth.parent / files["nav"])
    proc = run_cli(
        ["fit", *obs, "--nav", nav, "--out", str(out), "--no-pdf", "--quiet"], out.parent
    )
    return proc.returncode, tail(proc)
