"""Benchmark: the whole job, side by side with gnssmultipath, on the ESBC day (shared data).

Both tools run as a user runs them, in a fresh process each time, imports,
figures, files and interpreter shutdown included:

* ours: ``python -m psdbound fit OBS --nav NAV --out DIR`` (GPS, the default
  system), with the PDF, with ``--no-pdf`` (the HTML report and its figures
  still drawn) and with ``--no-report`` (``result.json`` alone, no figure);
* theirs: ``gnssmultipath.GNSS_MultipathAnalysis(OBS, broadcastNav1=NAV,
  desiredGNSSsystems=["G"], outputDir=DIR, use_LaTex=False)``, its whole
  code-multipath analysis with its defaults (figures, polar plots, CSV,
  pickle, summary), GPS only, once without its figures (``plotEstimates``
  and ``plot_polarplot`` off: its analysis alone, the figure issue 31
  quoted: 1.77x), and once with every system it reads.

Both run from compiled bytecode, as installed packages do (pip compiles a
package's modules when it installs it; gnssmultipath's are compiled in
site-packages): our package's bytecode is compiled once before the runs
(:func:`compile_ours`). Without it, a source checkout run with
``PYTHONDONTWRITEBYTECODE`` set (as in some sandboxes and CI) compiles the
~170 modules a fit imports on every run, about 0.2 s of CPU that an
installed psdbound never spends; ``--no-compile`` times that case.

Same day, same files: gnssmultipath does not read Hatanaka-compressed or
gzipped files, so both read the same plain RINEX copies, decompressed once
into ``benchmarks/out/whole_job`` (git ignores it). Our fit analyses one
satellite system per run (``--system``); the all-systems time of
gnssmultipath is printed for information, not compared.

Targets (issue 31), all on GPS: like for like, ``gps_ratio`` = ours (with
its figures and PDF) / theirs (with its figures) <= 1.0 and
``gps_noreport_vs_nofig_ratio`` = ours (``--no-report``, no figures) /
theirs (no figures) <= 1.0 (``pass``); and the strict one,
``gps_nopdf_vs_nofig_ratio`` = ours (``--no-pdf``, still drawing the HTML
report's nine figures) / theirs (no figures) <= 1.0 (``strict_pass``).
Each figure is the median of ``--repeat`` runs (default 3). Last line:
``RESULT ours_gps_s=... ours_gps_nopdf_s=... ours_gps_noreport_s=... theirs_gps_s=...
theirs_gps_nofig_s=... theirs_all_s=... gps_ratio=... gps_nopdf_ratio=...
gps_nopdf_vs_nofig_ratio=... gps_noreport_vs_nofig_ratio=... ours_bytecode=compiled|source
pass=... strict_pass=...``. Skips (exit 0, ``RESULT skipped=...``)
without the shared data or gnssmultipath.
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

DATA = (
    Path(
        os.environ.get(
            "PSDBOUND_SHARED_DATA", Path(__file__).resolve().parents[2] / "shared" / "data"
        )
    )
    / "rinex"
)
OBS = "ESBC00DNK_R_20201770000_01D_30S_MO.crx.gz"
NAV = "ESBC00DNK_R_20201770000_01D_MN.rnx.gz"
OUT = Path(__file__).resolve().parent / "out" / "whole_job"

THEIRS = (
    "import sys\n"
    "from gnssmultipath import GNSS_MultipathAnalysis\n"
    "systems = None if sys.argv[4] == 'all' else sys.argv[4].split(',')\n"
    "plots = sys.argv[5] == 'figures'\n"
    "GNSS_MultipathAnalysis(sys.argv[1], broadcastNav1=sys.argv[2], outputDir=sys.argv[3],\n"
    "                       desiredGNSSsystems=systems, use_LaTex=False,\n"
    "                       plotEstimates=plots, plot_polarplot=plots)\n"
)


def plain_copies() -> tuple[Path, Path]:
    """Return plain RINEX copies of the ESBC observation and navigation files (made once)."""
    import hatanaka

    OUT.mkdir(parents=True, exist_ok=True)
    obs, nav = OUT / "ESBC1770.20o", OUT / "ESBC1770.20p"
    if not obs.is_file():
        obs.write_bytes(hatanaka.decompress(DATA / OBS))
    if not nav.is_file():
        nav.write_bytes(hatanaka.decompress(DATA / NAV))
    return obs, nav


def compile_ours() -> Path:
    """Compile the bytecode of the psdbound this benchmark runs (once; kept in ``__pycache__``)."""
    import compileall

    import psdbound

    root = Path(psdbound.__file__).resolve().parent
    compileall.compile_dir(root, quiet=1)
    return root


def timed(cmd: list[str], cwd: str) -> tuple[float, int, str]:
    """Run a command; return (wall s, exit code, the tail of its output)."""
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd)
    return time.perf_counter() - t0, r.returncode, (r.stdout + r.stderr)[-400:]


def ours(obs: Path, nav: Path, *, pdf: bool, report: bool = True) -> tuple[float, int, str]:
    """One whole ``psdbound fit`` in a fresh process."""
    with tempfile.TemporaryDirectory() as work:
        cmd = (
            [
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
            + ([] if pdf else ["--no-pdf"])
            + ([] if report else ["--no-report"])
        )
        return timed(cmd, work)


def theirs(obs: Path, nav: Path, systems: str, *, figures: bool = True) -> tuple[float, int, str]:
    """One whole gnssmultipath analysis in a fresh process (``systems``: ``G`` or ``all``)."""
    with tempfile.TemporaryDirectory() as work:
        cmd = [
            sys.executable,
            "-c",
            THEIRS,
            str(obs),
            str(nav),
            work,
            systems,
            "figures" if figures else "none",
        ]
        return timed(cmd, work)


def median_of(run, repeat: int, label: str) -> float:
    """Median wall time of ``repeat`` runs; print each; stop on a failed run."""
    times = []
    for _ in range(repeat):
        wall, code, tail = run()
        print(f"  {label:<28} {wall:6.2f} s (exit {code})", flush=True)
        if code not in (0, 3):
            raise SystemExit(f"{label} failed (exit {code}):\n{tail}")
        times.append(wall)
    return statistics.median(times)


def main() -> int:
    """Run both tools side by side; print the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="runs of each (median), default 3")
    ap.add_argument(
        "--no-compile",
        action="store_true",
        help="do not compile psdbound's bytecode first (a source checkout that cannot cache it)",
    )
    args = ap.parse_args()
    if not (DATA / OBS).is_file():
        print(f"RESULT skipped=no_shared_data path={DATA}")
        return 0
    try:
        import gnssmultipath  # noqa: F401
    except ImportError:
        print("RESULT skipped=no_gnssmultipath")
        return 0
    obs, nav = plain_copies()
    print(f"ESBC 2020-177, 30 s, plain RINEX in {OUT}; median of {args.repeat}")
    if args.no_compile:
        print("psdbound: bytecode not compiled first (--no-compile)")
    else:
        print(f"psdbound: bytecode compiled in {compile_ours()}")
    r = {
        "ours_gps_s": median_of(lambda: ours(obs, nav, pdf=True), args.repeat, "psdbound fit"),
        "ours_gps_nopdf_s": median_of(
            lambda: ours(obs, nav, pdf=False), args.repeat, "psdbound fit --no-pdf"
        ),
        "ours_gps_noreport_s": median_of(
            lambda: ours(obs, nav, pdf=False, report=False),
            args.repeat,
            "psdbound fit --no-report",
        ),
        "theirs_gps_s": median_of(
            lambda: theirs(obs, nav, "G"), args.repeat, "gnssmultipath (GPS)"
        ),
        "theirs_gps_nofig_s": median_of(
            lambda: theirs(obs, nav, "G", figures=False),
            args.repeat,
            "gnssmultipath (GPS, no figures)",
        ),
        "theirs_all_s": median_of(
            lambda: theirs(obs, nav, "all"), args.repeat, "gnssmultipath (all systems)"
        ),
    }
    r["gps_ratio"] = r["ours_gps_s"] / r["theirs_gps_s"]
    r["gps_nopdf_ratio"] = r["ours_gps_nopdf_s"] / r["theirs_gps_s"]
    r["gps_nopdf_vs_nofig_ratio"] = r["ours_gps_nopdf_s"] / r["theirs_gps_nofig_s"]
    r["gps_noreport_vs_nofig_ratio"] = r["ours_gps_noreport_s"] / r["theirs_gps_nofig_s"]
    fields = " ".join(f"{k}={v:.3f}" for k, v in r.items())
    ok = r["gps_ratio"] <= 1.0 and r["gps_noreport_vs_nofig_ratio"] <= 1.0
    strict = r["gps_nopdf_vs_nofig_ratio"] <= 1.0
    code = "source" if args.no_compile else "compiled"
    print(
        f"RESULT {fields} ours_bytecode={code} pass={str(ok).lower()} "
        f"strict_pass={str(strict).lower()}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
