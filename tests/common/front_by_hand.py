"""The front's speed-ups recomputed by hand from front.json's own points (tests/cli/front*.sh):
the FEM front's time at a fast point's error, log-log between the two FEM points around it, over
the point's time; outside the FEM's errors a bound (its cheapest point's time: at most; its most
accurate one's: at least). Prints what differs; exits 1 if anything does.

    /usr/bin/python3 tests/common/front_by_hand.py FRONT_JSON MIN_CHECKED
"""
import json
import math
import sys


def fem_front(front, metric):
    floor = front["reference"]["errors"][metric]
    fem = [(p["errors"][metric], p["seconds"]["min"]) for p in front["points"]
           if p["model"] == "fem" and p["errors"][metric] > floor]
    return sorted(a for a in fem if not any(b != a and b[1] <= a[1] and b[0] <= a[0] for b in fem))[::-1]


def by_hand(front, metric, e):
    fem = fem_front(front, metric)
    if e > fem[0][0]:
        return "speedup_at_most", fem[0][1]
    if e < fem[-1][0]:
        return "speedup_at_least", fem[-1][1]
    for (e0, t0), (e1, t1) in zip(fem, fem[1:]):
        if e1 <= e <= e0:
            return "speedup", t0 * (t1 / t0) ** (math.log(e / e0) / math.log(e1 / e0))


def main(path, least):
    front = json.load(open(path))
    points = {p["label"]: p for p in front["points"]}
    bad, checked = [], 0
    for v in front["verdicts"]:
        p = points[v["point"]]
        if p["model"] == "fem" or v["below_floor"]:
            continue
        kind, t = by_hand(front, v["metric"], p["errors"][v["metric"]])
        checked += 1
        if v[kind] is None or not math.isclose(v[kind], t / p["seconds"]["min"], rel_tol=1e-9):
            bad.append(f"{v['point']} {v['metric']}: {kind} {v[kind]}, by hand {t / p['seconds']['min']}")
    if checked < least:
        bad.append(f"only {checked} speed-ups checked")
    print("\n".join(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], int(sys.argv[2])))
