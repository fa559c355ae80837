"""How close to the wall's edge a fan's coat can be even (docs/deposition.md, "Where the coat is
uneven"): passes parallel to a straight edge, their centres at least r from it (a disk tool stays
inside the wall), each at any speed (its dwell w >= 0), lay g(e) = sum_k w_k f(c_k - e) at a
distance e from the edge, f the fan's profile. For a beta fan this finds, by linear programming
(scipy.optimize.linprog), the smallest e* such that some passes keep g within 10 % of one value
everywhere from e* to 5 r: closer to the edge than e*, no arrangement of parallel passes is even.
    /usr/bin/python3 bench/coat_edge_bound.py [BETA ...]      (default 2.5)
Centres on a grid of r/100 from r to 7 r, points on a grid of r/500; e* is the first grid point
from which the passes can be even (bisection over the points)."""
import sys

import numpy as np
from scipy.optimize import linprog
from scipy.special import beta as beta_function


def profile(beta, x):
    """The beta fan of radius 1: (1 - x^2)^(beta - 1) / B(1/2, beta) on [-1, 1]."""
    inside = np.abs(x) <= 1.0
    return np.where(inside, np.clip(1.0 - x * x, 0.0, None) ** (beta - 1.0), 0.0) / beta_function(0.5, beta)


def even_from(beta, start, centres, points):
    """Whether some dwell w >= 0 keeps 0.9 <= g(e) <= 1.1 for every point e >= start."""
    e = points[points >= start]
    a = profile(beta, centres[None, :] - e[:, None])
    rows = np.vstack([a, -a])
    bounds = np.concatenate([np.full(len(e), 1.1), np.full(len(e), -0.9)])
    res = linprog(np.zeros(len(centres)), A_ub=rows, b_ub=bounds, bounds=(0, None), method="highs")
    return res.status == 0


def edge_bound(beta):
    """The least grid point e* from which passes can keep the coat even, in radii."""
    centres = np.arange(1.0, 7.0 + 1e-9, 0.01)
    points = np.arange(0.0, 5.0 + 1e-9, 0.002)
    lo, hi = 0, int(np.searchsorted(points, 1.0 - 1e-9))  # even from 1 (a pass's centre) is possible; from 0 it may not be
    if even_from(beta, points[lo], centres, points):
        return points[lo]  # even up to the edge (a uniform fan)
    assert even_from(beta, points[hi], centres, points)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if even_from(beta, points[mid], centres, points):
            hi = mid
        else:
            lo = mid
    return points[hi]


def one_pass_bound(beta):
    """The closed form it must not beat: a point e < r from the edge gains at most (1 - (1 - e)^2)^(beta - 1)
    of what the point r from it gains (every pass's centre is at least r from the edge, and f falls
    faster the farther out), so g(e) >= 0.9 and g(r) <= 1.1 need (1 - (1 - e)^2)^(beta - 1) >= 9/11."""
    return 1.0 - np.sqrt(1.0 - (9.0 / 11.0) ** (1.0 / (beta - 1.0))) if beta > 1 else 0.0


if __name__ == "__main__":
    for b in [float(v) for v in sys.argv[1:]] or [2.5]:
        print(f"beta {b:g}: no parallel passes are even closer to the edge than e* = {edge_bound(b):.3f} r "
              f"(one pass at r alone: {one_pass_bound(b):.3f} r)")
