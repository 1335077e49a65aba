"""One metric of a sweep's summary table against one parameter, a line per value of another.

    /usr/bin/python3 figure.py summary.csv figure.png --metric body.sigma_y.rel_l2 \
        --parameter mesh.parameters.h [--group agent.rule_set]
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("table")
    p.add_argument("figure")
    p.add_argument("--metric", required=True)
    p.add_argument("--parameter", required=True)
    p.add_argument("--group", default="")
    a = p.parse_args()
    with open(a.table, newline="") as f:
        rows = list(csv.DictReader(f))
    for column in [a.metric, a.parameter] + ([a.group] if a.group else []):
        if not rows or column not in rows[0]:
            print(f"figure.py: error: {a.table}: {column}: not a column (a parameter is a column only when "
                  "its value differs between the cases)", file=sys.stderr)
            sys.exit(2)
    lines = {}
    for r in rows:
        if r[a.metric] != "":  # an empty cell: the case has no such metric
            lines.setdefault(r[a.group] if a.group else "", []).append((float(r[a.parameter]), float(r[a.metric])))
    fig, ax = plt.subplots(figsize=(6, 4))
    for name, points in sorted(lines.items()):
        xs, ys = zip(*sorted(points))
        ax.plot(xs, ys, "o-", label=f"{a.group} = {name}" if a.group else None)
    ax.set_xlabel(a.parameter)
    ax.set_ylabel(a.metric)
    if a.group:
        ax.legend()
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.figure, dpi=120)


if __name__ == "__main__":
    main()
