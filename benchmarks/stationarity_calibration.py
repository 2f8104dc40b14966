"""Benchmark: level and power of the stationarity tests on correlated 10-minute windows.

Each trial is a 10-minute window at 1 Hz (600 samples) of a first-order
Gauss-Markov process (tau 30 s, sigma 3 mm; ``psdbound.simulate.gauss_markov``,
exact discretisation, started stationary) plus white noise (1 mm), drawn from
one seeded ``numpy.random.Generator``. Three cases:

* ``stationary``: as above;
* ``variance step``: the second half multiplied by sqrt(2) (the variance
  doubles at mid-window);
* ``tau change``: the Gauss-Markov part continues from its mid-window value
  with tau 300 s (the AR(1) recursion with the new coefficient, the same
  marginal variance: no jump, no variance change, only the correlation time);
* ``tau change, restart`` (for comparison with ``tests/stationarity``): the
  second half an independent stationary draw with tau 300 s (a jump at
  mid-window as well). Not in the RESULT line.

Both tests run on every window at level ``alpha``: the spectral-homogeneity
test (``psdbound.stationarity.test_spectral_homogeneity``, multitaper log
spectra of the halves) and the thesis's Levene-then-K-S test
(``psdbound.stationarity.test_stationarity``). The rejection rates are
reported as measured (nothing is tuned here).

Targets: spectral rejection of stationary windows <= alpha within Monte-Carlo
error (``alpha + 2 mc_se``); detection of both changes >= 0.90.

Last line: ``RESULT stationary_reject_spectral=... step_detect_spectral=...
tau_detect_spectral=... stationary_reject_thesis=... mc_se=...`` (``mc_se``:
the Monte-Carlo standard error of a 5 % rate over the trials).
"""

from __future__ import annotations

import argparse
import math
import sys
from collections.abc import Callable

import numpy as np
from scipy.signal import lfilter

from psdbound.simulate import gauss_markov
from psdbound.stationarity import test_spectral_homogeneity, test_stationarity

N = 600  # 10 minutes at 1 Hz
DT_S = 1.0
SIGMA_GM_M = 0.003
SIGMA_WN_M = 0.001
TAU_S = 30.0
TAU_CHANGED_S = 300.0


def stationary(rng: np.random.Generator) -> np.ndarray:
    """Return GM(tau 30 s, 3 mm) + white noise (1 mm), 600 samples at 1 Hz, metres."""
    gm = gauss_markov(N, SIGMA_GM_M, TAU_S, DT_S, rng)[:, 0]
    return gm + rng.normal(0.0, SIGMA_WN_M, N)


def variance_step(rng: np.random.Generator) -> np.ndarray:
    """Return a stationary window whose second half has twice the variance."""
    x = stationary(rng)
    x[N // 2 :] *= math.sqrt(2.0)
    return x


def tau_change(rng: np.random.Generator) -> np.ndarray:
    """Return GM whose time constant becomes 300 s at mid-window (same variance) + white noise."""
    half = N // 2
    first = gauss_markov(half, SIGMA_GM_M, TAU_S, DT_S, rng)[:, 0]
    phi = math.exp(-DT_S / TAU_CHANGED_S)
    w = rng.normal(0.0, SIGMA_GM_M * math.sqrt(1.0 - phi**2), N - half)
    second = lfilter([1.0], [1.0, -phi], w, zi=[phi * first[-1]])[0]
    return np.r_[first, second] + rng.normal(0.0, SIGMA_WN_M, N)


def tau_restart(rng: np.random.Generator) -> np.ndarray:
    """Return GM(30 s) then an independent GM(300 s), same variance, + white noise."""
    half = N // 2
    gm = np.r_[
        gauss_markov(half, SIGMA_GM_M, TAU_S, DT_S, rng)[:, 0],
        gauss_markov(N - half, SIGMA_GM_M, TAU_CHANGED_S, DT_S, rng)[:, 0],
    ]
    return gm + rng.normal(0.0, SIGMA_WN_M, N)


CASES: dict[str, Callable[[np.random.Generator], np.ndarray]] = {
    "stationary": stationary,
    "variance step 2x": variance_step,
    f"tau {TAU_S:g} -> {TAU_CHANGED_S:g} s": tau_change,
    f"tau {TAU_S:g} -> {TAU_CHANGED_S:g} s, restart": tau_restart,
}


def rejection_rates(
    make: Callable[[np.random.Generator], np.ndarray], trials: int, alpha: float, seed: int
) -> tuple[float, float]:
    """Return the rejection rates (spectral, thesis) of ``trials`` windows from ``make``."""
    rng = np.random.default_rng(seed)
    rej_s = rej_t = 0
    for _ in range(trials):
        x = make(rng)
        rej_s += not test_spectral_homogeneity(x, alpha=alpha).stationary
        rej_t += not test_stationarity(x, alpha=alpha).stationary
    return rej_s / trials, rej_t / trials


def main(argv: list[str] | None = None) -> int:
    """Measure the rejection rates of both tests; print the table and the RESULT line."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=400, help="windows per case (default 400)")
    ap.add_argument("--alpha", type=float, default=0.05, help="test level (default 0.05)")
    ap.add_argument("--seed", type=int, default=2024, help="seed of the first case")
    args = ap.parse_args(argv)
    if args.trials < 1 or not 0.0 < args.alpha < 1.0:
        ap.error("--trials must be >= 1 and --alpha in (0, 1)")
    mc_se = math.sqrt(args.alpha * (1.0 - args.alpha) / args.trials)
    rates = {
        name: rejection_rates(make, args.trials, args.alpha, args.seed + k)
        for k, (name, make) in enumerate(CASES.items())
    }
    print(
        f"{N} samples at {DT_S:g} s: GM tau {TAU_S:g} s, sigma {1e3 * SIGMA_GM_M:g} mm + white "
        f"{1e3 * SIGMA_WN_M:g} mm; {args.trials} trials per case, alpha {args.alpha:g}, "
        f"Monte-Carlo s.e. of a {100 * args.alpha:g} % rate {mc_se:.4f}"
    )
    print(f"{'case':<31} {'spectral':>9} {'thesis':>9}   (rejection rate)")
    for name, (r_s, r_t) in rates.items():
        print(f"{name:<31} {r_s:>9.3f} {r_t:>9.3f}")
    (st_s, st_t), (step_s, _), (tau_s, _), _ = rates.values()
    level_ok = st_s <= args.alpha + 2.0 * mc_se
    print(
        f"targets: spectral stationary rejection <= {args.alpha:g} + 2 s.e. "
        f"({args.alpha + 2 * mc_se:.3f}): {'met' if level_ok else 'NOT met'}; "
        f"detections >= 0.90: variance step {'met' if step_s >= 0.9 else 'NOT met'}, "
        f"tau change {'met' if tau_s >= 0.9 else 'NOT met'}"
    )
    print(
        f"RESULT stationary_reject_spectral={st_s:.4f} step_detect_spectral={step_s:.4f} "
        f"tau_detect_spectral={tau_s:.4f} stationary_reject_thesis={st_t:.4f} mc_se={mc_se:.4f}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
