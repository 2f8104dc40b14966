"""The polygons of two non-negative variables against scipy's HiGHS solver."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import linprog

from psdbound.spectra import _plane as plane


@pytest.mark.parametrize("seed", range(40))
def test_feasibility_equals_highs(seed):
    """Two-sided band intervals (the model set): feasible exactly when HiGHS finds a point."""
    rng = np.random.default_rng(100 + seed)
    m = int(rng.integers(2, 20))
    a = rng.uniform(0.0, 1.0, (m, 2))
    centre = a @ rng.uniform(0.0, 2.0, 2)
    half = rng.uniform(0.0, 0.4, m) * centre
    wobble = rng.normal(0.0, 0.08, m) * centre  # about half the programs are infeasible
    a_ub = np.vstack([a, -a])
    b_ub = np.r_[centre + wobble + half, -(centre + wobble - half)]
    ours = plane.corners(a_ub, b_ub).shape[0] > 0
    ref = linprog(np.zeros(2), A_ub=a_ub, b_ub=b_ub, bounds=[(0, None)] * 2, method="highs")
    assert ours == (ref.status == 0)


def test_corners_of_a_square():
    a_ub = np.array([[1.0, 0.0], [0.0, 1.0]])
    got = plane.corners(a_ub, np.array([2.0, 3.0]))
    assert sorted(map(tuple, got)) == [(0.0, 0.0), (0.0, 3.0), (2.0, 0.0), (2.0, 3.0)]


def test_empty_set_has_no_corner():
    assert plane.corners(np.array([[1.0, 1.0]]), np.array([-1.0])).shape == (0, 2)
