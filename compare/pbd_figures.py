#!/usr/bin/python3
"""The PBD rod against the FEM strip: both centrelines and Euler-Bernoulli, from a comparison's CSV.

    /usr/bin/python3 compare/pbd_figures.py OUT_DIR [--title TITLE]

Reads OUT_DIR/centreline.csv (written by `workbench compare` with [compare] model = "pbd") and
writes OUT_DIR/figures/centreline.png and .pdf: (a) the deflection u_y along the strip of PBD, FEM
and Euler-Bernoulli; (b) PBD - FEM and EB - FEM relative to the largest FEM deflection.
Uses Debian's python3-matplotlib and python3-numpy only; call it with /usr/bin/python3.
"""
import argparse
import os

import matplotlib.pyplot as plt
import numpy as np

from figures import read_csv, saving  # compare/figures.py: the same CSV reader, the checked save (and the Agg backend)
from child_report import guarded  # scripts/child_report.py, on the path figures.py sets


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("--title", default="")
    parser.add_argument("--formats", default="png", help="comma-separated: png, pdf")
    args = parser.parse_args()
    c = {k: v.astype(float) for k, v in read_csv(os.path.join(args.dir, "centreline.csv")).items()}
    out = os.path.join(args.dir, "figures")
    os.makedirs(out, exist_ok=True)

    s_mm = 1e3 * c["s"]
    scale = np.max(np.abs(c["fem_u_y"])) or 1.0
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    ax.plot(s_mm, 1e3 * c["fem_u_y"], "-", color="tab:blue", lw=2, label="FEM strip (mid-height)")
    ax.plot(s_mm, 1e3 * c["eb_u_y"], "--", color="k", lw=1, label="Euler-Bernoulli")
    ax.plot(s_mm, 1e3 * c["pbd_u_y"], "o", color="tab:red", ms=4, mfc="none", label="PBD nodes")
    ax.set_ylabel("deflection u_y [mm]")
    ax.set_title("(a) centreline deflection" + (f": {args.title}" if args.title else ""), fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend()
    bx.plot(s_mm, (c["pbd_u_y"] - c["fem_u_y"]) / scale, "o-", color="tab:red", ms=3, label="PBD - FEM")
    bx.plot(s_mm, (c["eb_u_y"] - c["fem_u_y"]) / scale, "--", color="k", lw=1, label="EB - FEM")
    bx.axhline(0, color="0.5", lw=0.5)
    bx.set_xlabel("s from the clamp [mm]")
    bx.set_ylabel("difference / max |u_y FEM|")
    bx.set_title("(b) differences", fontsize=10)
    bx.grid(alpha=0.3)
    bx.legend()
    fig.tight_layout()
    for ext in args.formats.split(","):
        saving(os.path.join(out, f"centreline.{ext}"), lambda p: fig.savefig(p, dpi=150, bbox_inches="tight"))
    plt.close(fig)


if __name__ == "__main__":
    guarded(main)
