#!/usr/bin/python3
"""Work-precision figures of a cost-accuracy front: time against error, log-log, per far-field metric.

    /usr/bin/python3 compare/front_figures.py OUT_DIR [--title TITLE] [--formats png,pdf]

Reads OUT_DIR/front.json (written by `workbench front`) and writes OUT_DIR/figures/front_<field>.png
for each far-field metric of the front ("far.sigma_y.rel_l2" -> front_sigma_y.png; a PBD case's
front: every metric, "tip.deflection.rel_error" -> front_tip_deflection.png): one line per model
family (each agent rule set, the PBD at each iteration count, FEM Q1, FEM Q2) through its points'
minimum times, each point labelled with its size (PBD: its substeps), the case's own point ringed, and the reference's own error in that
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
FAST_COLOURS = ["tab:red", "tab:orange", "tab:green", "tab:brown"]


def family(p):
    if p["model"] == "agent":
        return f"agents, {p['rule_set']}"
    if p["model"] == "pbd":
        return f"PBD, {p['work']['iterations_per_substep']:g} iterations"
    return f"FEM Q{p['degree']}"


def families(points):
    """{family name: [points in ladder order]}: each agent rule set, the PBD per iteration count
    (by substeps), each FEM degree (by size)."""
    out = {}
    for p in points:
        out.setdefault(family(p), []).append(p)
    order = lambda p: p["work"]["substeps"] if p["model"] == "pbd" else p["size"]
    return {k: sorted(v, key=order) for k, v in out.items()}


def point_text(p):
    return f"{p['work']['substeps']:g} sub" if p["model"] == "pbd" else f"{1e3 * p['size']:g} mm"


def field_name(metric):
    """far.sigma_y.rel_l2 -> sigma_y; tip.deflection.rel_error -> tip_deflection."""
    parts = metric.split(".")[:-1]
    return "_".join(parts[1:] if parts[0] == "far" else parts)


def drawn_metrics(front):
    """The far-field metrics, or every metric of a front that has none (a PBD case's)."""
    far = [m for m in front["metrics"] if m.startswith("far.")]
    return far or front["metrics"]


def style(name, fast_index):
    if name.startswith("FEM"):
        return STYLES["fem " + name[-1]]
    return "o-", FAST_COLOURS[fast_index % len(FAST_COLOURS)]


def draw(front, metric, title):
    fig, ax = plt.subplots(figsize=(7, 5))
    fast = 0
    for name, points in families(front["points"]).items():
        points = [p for p in points if metric not in p.get("not_modelled", [])]  # a zero field: no point
        if not points:
            continue
        marker, colour = style(name, fast)
        fast += not name.startswith("FEM")
        errors = [p["errors"][metric] for p in points]
        seconds = [p["seconds"]["min"] for p in points]
        ax.loglog(errors, seconds, marker, color=colour, label=name, mfc="none")
        for p, e, t in zip(points, errors, seconds):
            ax.annotate(point_text(p), (e, t), textcoords="offset points", xytext=(4, 3), fontsize=7,
                        color=colour)
            if p["label"] == front["case_point"]:
                ax.plot([e], [t], "o", ms=14, mfc="none", color="k", label="the case's own point")
    floor = front["reference"]["errors"].get(metric)
    if floor and floor > 0:  # below it no verdict: the axis shows a decade of it, not the round-off beyond
        ax.set_xlim(left=max(ax.get_xlim()[0], floor / 10))
        ax.axvspan(ax.get_xlim()[0], floor, color="0.85", label="below the reference's own error")
    ax.set_xlabel(f"{metric} (against the converged reference)")
    ax.set_ylabel("time, min of warm runs [s]")
    ax.set_title(f"{title}: cost against error, {field_name(metric)}", fontsize=10)
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
    for metric in drawn_metrics(front):
        fig = draw(front, metric, args.title)
        field = field_name(metric)
        for ext in args.formats.split(","):
            saving(os.path.join(out, f"front_{field}.{ext}"), lambda p: fig.savefig(p, dpi=120))
        plt.close(fig)
    print(f"front_figures.py: drew {out}")


if __name__ == "__main__":
    guarded(main)
