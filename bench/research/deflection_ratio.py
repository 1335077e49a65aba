#!/usr/bin/python3
"""Tip / midspan deflection, agent against FEM, from a comparison folder's nodes.csv (the columns rule set,
docs/agent-model.md, "Bending: the column rule set"):
mean u_y over the nodes of the node line at x (the tip: the free end; a beam on supports: midspan).

    /usr/bin/python3 bench/research/deflection_ratio.py OUT_DIR X_M"""
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/nodes.csv")))
x = float(sys.argv[2])
line = [r for r in rows if abs(float(r["x [m]"]) - x) < 1e-9]
a = sum(float(r["agent_u_y [m]"]) for r in line) / len(line)
f = sum(float(r["fem_u_y [m]"]) for r in line) / len(line)
print("x = %g m: %d nodes, agent %.4e m, FEM %.4e m, ratio %.3f" % (x, len(line), a, f, a / f))
