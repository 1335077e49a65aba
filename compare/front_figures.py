#!/usr/bin/python3
"""Work-precision figures of a cost-accuracy front: time against error, log-log, per far-field metric.

    /usr/bin/python3 compare/front_figures.py OUT_DIR [--title TITLE] [--formats png,pdf]

Reads OUT_DIR/front.json (written by `workbench front`) and writes OUT_DIR/figures/front_<field>.png
for each far-field metric of the front ("far.sigma_y.rel_l2" -> front_sigma_y.png): one line per
model family (each agent rule set, FEM Q1, FEM Q2) through its points' minimum times, each point
labelled with its size, the case's own agent point ringed, and the reference's own error in that
metric as a shaded floor (no verdict is given below it; the axis stops a decade below it, so that a
point at round-off, the reference's own level, is off the figure), as DiffEqDevTools' work-precision
diagrams.
Uses Debian's python3-matplotlib and python3-numpy only; call it with /usr/bin/python3.
"""
import argparse
import json
import os

import matplotlib.pyplot as plt

from figures import saving  # compare/figures.py: the checked save (and the Agg backend)
from child_report import guarded  # scripts/child_report.py, on the path figures.py sets

STYLES = {"fem 1": ("s-", "tab:blue"), "fem 2": ("D-", "tab:purple")}
AGENT_COLOURS = ["tab:red", "tab:orange", "tab:green", "tab:brown"]


def families(points):
    """{family name: [points sorted by size]}: each agent rule set, and each FEM degree."""
    out = {}
    for p in points:
        name = f"agents, {p['rule_set']}" if p["model"] == "agent" else f"FEM Q{p['degree']}"
        out.setdefault(name, []).append(p)
    return {k: sorted(v, key=lambda p: p["size"]) for k, v in out.items()}


def style(name, agent_index):
    if name.startswith("FEM"):
        return STYLES["fem " + name[-1]]
    return "o-", AGENT_COLOURS[agent_index % len(AGENT_COLOURS)]


def draw(front, metric, title):
    fig, ax = plt.subplots(figsize=(7, 5))
    agents = 0
    for name, points in families(front["points"]).items():
        marker, colour = style(name, agents)
        agents += name.startswith("agents")
        errors = [p["errors"][metric] for p in points]
        seconds = [p["seconds"]["min"] for p in points]
        ax.loglog(errors, seconds, marker, color=colour, label=name, mfc="none")
        for p, e, t in zip(points, errors, seconds):
            ax.annotate(f"{1e3 * p['size']:g} mm", (e, t), textcoords="offset points", xytext=(4, 3), fontsize=7,
                        color=colour)
            if p["label"] == front["case_point"]:
                ax.plot([e], [t], "o", ms=14, mfc="none", color="k", label="the case's own agents")
    floor = front["reference"]["errors"].get(metric)
    if floor and floor > 0:  # below it no verdict: the axis shows a decade of it, not the round-off beyond
        ax.set_xlim(left=max(ax.get_xlim()[0], floor / 10))
        ax.axvspan(ax.get_xlim()[0], floor, color="0.85", label="below the reference's own error")
    ax.set_xlabel(f"{metric} (against the converged reference)")
    ax.set_ylabel("time, min of warm runs [s]")
    ax.set_title(f"{title}: cost against error, {metric.split('.')[1]}", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--title", default="")
    parser.add_argument("--formats", default="png", help="comma-separated: png, pdf")
    args = parser.parse_args()
    with open(os.path.join(args.dir, "front.json")) as f:
        front = json.load(f)
    out = os.path.join(args.dir, "figures")
    os.makedirs(out, exist_ok=True)
    for metric in front["metrics"]:
        if not metric.startswith("far."):
            continue
        fig = draw(front, metric, args.title)
        field = metric.split(".")[1]
        for ext in args.formats.split(","):
            saving(os.path.join(out, f"front_{field}.{ext}"), lambda p: fig.savefig(p, dpi=120))
        plt.close(fig)
    print(f"front_figures.py: drew {out}")


if __name__ == "__main__":
    guarded(main)
