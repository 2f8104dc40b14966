"""The isolation stage's choices and defaults, in a module that imports nothing heavy.

The configuration and every command's ``--help`` need them without loading
the dual-antenna machinery (orbits, arcs, scipy).
"""

from __future__ import annotations

__all__ = ["BASELINE_MODES", "BASELINE_TOLERANCE_M"]

#: Baseline modes: estimate and use above the tolerance, always use, keep given.
BASELINE_MODES = ("auto", "estimate", "given")
#: Default size above which the estimated correction replaces the given position, m.
BASELINE_TOLERANCE_M = 0.005
