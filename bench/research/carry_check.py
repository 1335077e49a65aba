#!/usr/bin/python3
"""Saying before the run whether a marching rule set can carry a load (research prototype, 2D).

From the loaded faces, the rows ahead along the march direction are swept through the body: each row the
reached set widens by ceil(tan(fan_angle)) agents each way through agents of that row (free sides mirror
packets, so they stay in the body), and every face across the march where the body ends ahead of a
reached agent is an exit: rigid (a reaction) or free (passed out). No rigid exit: the load cannot be
carried by this rule set. The rigid share of the exit area is a first guess of the carried share.
Cost: one pass over the reachable rows.  /usr/bin/python3 bench/research/carry_check.py [NOTCHED_BEAM_OUT_DIR]"""
import csv, math, sys
import numpy as np


def carry_check(present, rigid, loaded, march, fan_angle=66.0):
    """present[i, j]: agents; rigid: set of (i, j, side) rigid boundary faces, side in {'-x','+x','-y','+y'};
    loaded: agent cells under the load; march: (di, dj) one of the four axis steps.
    Returns (rigid exit faces, free exit faces)."""
    nx, ny = present.shape
    di, dj = march
    side = {(0, -1): "-y", (0, 1): "+y", (-1, 0): "-x", (1, 0): "+x"}[march]
    lat = (1, 0) if di == 0 else (0, 1)
    widen = math.ceil(math.tan(math.radians(fan_angle)))
    inside = lambda i, j: 0 <= i < nx and 0 <= j < ny and present[i, j]
    now = set(loaded)
    n_rigid = n_free = 0
    seen = set()
    while now:
        nxt = set()
        for (i, j) in now:
            a, b = i + di, j + dj
            if inside(a, b):
                nxt.add((a, b))
            else:
                if (i, j, side) in rigid:
                    n_rigid += 1
                else:
                    n_free += 1
        # widen through the next row's agents (connected, up to `widen` each way)
        grown = set(nxt)
        for (a, b) in nxt:
            for sgn in (1, -1):
                for s in range(1, widen + 1):
                    p = (a + sgn * s * lat[0], b + sgn * s * lat[1])
                    if not inside(*p):
                        break
                    grown.add(p)
        now = grown - seen
        seen |= grown
    return n_rigid, n_free


def report(name, r):
    n_rigid, n_free = r
    total = n_rigid + n_free
    verdict = "cannot carry: no rigid face ahead" if n_rigid == 0 else "carries (rigid share of the exits %.2f)" % (n_rigid / total)
    print("%-52s rigid exits %4d, free exits %4d: %s" % (name, n_rigid, n_free, verdict))


if __name__ == "__main__":
    nx = ny = 40
    plate = np.ones((nx, ny), bool)
    base = {(i, 0, "-y") for i in range(nx)}
    report("seed plate, pushed (-y), march -y", carry_check(plate, base, [(19, ny - 1), (20, ny - 1)], (0, -1)))
    report("seed plate, pulled (+y), march along the load (now)", carry_check(plate, base, [(19, ny - 1), (20, ny - 1)], (0, 1)))
    report("seed plate, pulled, march along the inward normal", carry_check(plate, base, [(19, ny - 1), (20, ny - 1)], (0, -1)))
    cant = np.ones((40, 8), bool)
    clamp = {(0, j, "-x") for j in range(8)}
    report("cantilever 200 x 40 mm clamped at x = 0, load -y at the tip", carry_check(cant, clamp, [(39, 7)], (0, -1)))
    report("the same, march toward the clamp (-x): the column rule", carry_check(cant, clamp, [(39, j) for j in range(8)], (-1, 0)))
    if len(sys.argv) > 1:
        rows = list(csv.reader(open(sys.argv[1] + "/cells.csv")))
        h = 0.002
        ij = [(round(float(r[1]) / h - .5), round(float(r[2]) / h - .5)) for r in rows[1:]]
        bx, by = max(p[0] for p in ij) + 1, max(p[1] for p in ij) + 1
        beam = np.zeros((bx, by), bool)
        for p in ij:
            beam[p] = True
        sup = {(i, 0, "-y") for i in list(range(5)) + list(range(bx - 5, bx))}   # 10 mm supports at both ends
        report("notched beam (cases/notched_beam.toml), load -y", carry_check(beam, sup, [(i, by - 1) for i in range(47, 53)], (0, -1)))
