#!/usr/bin/python3
"""The far-field table of issue 23 from `workbench compare` output folders (docs/agent-model.md, "Measured").

    /usr/bin/python3 bench/research/compare_table.py OUT_DIR [OUT_DIR ...]

Per folder: far.<field>.rel_l2 of summary.json for every stress component and the displacement, and
the share of the side-edge nodes (x at the box's ends, above the lowest tenth of the height) whose
agent u_x has FEM's sign, all of them and those where FEM's |u_x| is at least 5 % of its largest on
the sides. Exit 2 with one line on a folder it cannot read."""
import csv
import json
import os
import sys

import numpy as np

FIELDS = ["sigma_x", "sigma_y", "tau_xy", "von_mises", "displacement", "u_x", "u_y"]


def row(folder):
    try:
        metrics = json.load(open(os.path.join(folder, "summary.json")))["metrics"]
        values = [metrics["far.%s.rel_l2" % f]["value"] for f in FIELDS]
        nodes = list(csv.DictReader(open(os.path.join(folder, "nodes.csv"))))
        x, y, agent, fem = (np.array([float(r[k]) for r in nodes]) for k in ("x [m]", "y [m]", "agent_u_x [m]", "fem_u_x [m]"))
    except (OSError, ValueError, KeyError) as e:
        print("compare_table.py: %s: not a 2D comparison folder (%s)" % (folder, e), file=sys.stderr)
        sys.exit(2)
    if not np.all(np.isfinite(values)):
        print("compare_table.py: %s: a non-finite error" % folder, file=sys.stderr)
        sys.exit(2)
    side = (np.isclose(x, x.min()) | np.isclose(x, x.max())) & (y > y.min() + 0.1 * (y.max() - y.min()))
    same = np.sign(agent[side]) == np.sign(fem[side])
    big = np.abs(fem[side]) >= 0.05 * np.abs(fem[side]).max()
    return values, same.mean(), same[big].mean()


def main():
    if len(sys.argv) < 2:
        print("usage: compare_table.py OUT_DIR [OUT_DIR ...]", file=sys.stderr)
        sys.exit(2)
    rows = [(f, row(f)) for f in sys.argv[1:]]
    print("| case | " + " | ".join(FIELDS) + " | u_x sign, side nodes | where FEM's >= 5 % |")
    print("|---" * (len(FIELDS) + 3) + "|")
    for folder, (values, share, share_big) in rows:
        name = os.path.basename(os.path.normpath(folder))
        print("| %s | %s | %.2f | %.2f |" % (name, " | ".join("%.3f" % v for v in values), share, share_big))


if __name__ == "__main__":
    main()
