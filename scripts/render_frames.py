#!/usr/bin/python3
"""Render a folder of mesh frames to an MP4 or GIF without a display (matplotlib Agg + ffmpeg).

Generic: any model that writes this folder format can be animated (the PBD model does with
`workbench pbd CASE --animate`; the agent model's load steps can reuse it).

Input folder format
  cells.csv          header line "type,nodes", then one cell per line: VTK type, node indices
                     (0-based): 3 line (2 nodes), 5 triangle (3), 9 quad (4); 4 polyline (n).
  frame_*.csv        one per frame, sorted by name: optional "# time=<seconds>" comment line,
                     header "x,y,z[,<field>...]", one row per node (same node count every frame).
                     Positions in metres. The colour field is the column named by --field
                     (default: the 4th column; none -> plain colour); its name, unit included
                     ("displacement [m]"), labels the colour bar.

Usage
  /usr/bin/python3 scripts/render_frames.py DIR -o OUT.mp4|OUT.gif [--fps 25] [--field NAME]
        [--view auto|xy|xz|yz|3d] [--title TEXT] [--every N] [--size 6x4.5] [--dpi 100]

  --view auto: xy when every z is equal in the first frame, else a 3D view (equal axes). Axis
  limits and the colour range are fixed over all frames. Progress on stderr when it is a terminal.
  Exit status 0 on success, 1 with a one-line message, 74 when a write failed (a full disk, a
  file-size limit: scripts/child_report.py).
"""
import argparse
import csv
import errno
import glob
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time as clock

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402

from child_report import DISK_ERRORS, disk_error_text, guarded, write_failed  # noqa: E402  (beside this script)


def fail(msg):
    print("render_frames: error: " + msg, file=sys.stderr)
    sys.exit(1)


def progress_stream():
    """Where progress goes: the workbench's terminal when it runs this script (descriptor
    WORKBENCH_PROGRESS_FD; everything else goes to render.log), else stderr when that is a terminal,
    else nowhere."""
    fd = os.environ.get("WORKBENCH_PROGRESS_FD")
    if fd:
        return os.fdopen(int(fd), "w", closefd=False)
    return sys.stderr if sys.stderr.isatty() else None


PROGRESS = progress_stream()


class Progress:
    """`label k/n` on one terminal line, shown only after the first second."""

    def __init__(self, label, total):
        self.label, self.total, self.start = label, total, clock.monotonic()
        self.shown = False
        self.on = PROGRESS is not None

    def step(self, k):
        if self.on and (self.shown or clock.monotonic() - self.start > 1.0):
            self.shown = True
            print(f"\r{self.label} {k}/{self.total}", end="", file=PROGRESS, flush=True)

    def done(self):
        if self.shown:
            print(f"\r{self.label} {self.total}/{self.total} ({clock.monotonic() - self.start:.1f} s)", file=PROGRESS)


def read_cells(path):
    lines, polys = [], []
    with open(path) as f:
        rows = csv.reader(f)
        next(rows, None)
        for row in rows:
            if not row:
                continue
            t, nodes = int(row[0]), [int(v) for v in row[1:]]
            if t == 3 or t == 4:
                lines.extend([(nodes[k], nodes[k + 1]) for k in range(len(nodes) - 1)])
            elif t in (5, 9):
                polys.append(nodes)
            elif t in (1, 2):
                continue
            else:
                fail(f"{path}: unsupported VTK cell type {t}")
    return np.array(lines, dtype=int).reshape(-1, 2), polys


def read_frame(path, field):
    time = None
    with open(path) as f:
        first = f.readline()
        if first.startswith("#"):
            if "time=" in first:
                time = float(first.split("time=")[1])
            header = f.readline()
        else:
            header = first
        names = header.strip().split(",")
        data = np.loadtxt(f, delimiter=",", ndmin=2)
    if data.shape[1] < 3 or names[:3] != ["x", "y", "z"]:
        fail(f"{path}: needs columns x,y,z first")
    values = None
    if field != "none":
        if field is None and len(names) > 3:
            field = names[3]
        if field is not None:
            if field not in names:
                fail(f"{path}: no column '{field}' (has {', '.join(names)})")
            values = data[:, names.index(field)]
    return time, data[:, :3], values, field


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--fps", type=int, default=25)
    ap.add_argument("--field", default=None)
    ap.add_argument("--view", default="auto", choices=["auto", "xy", "xz", "yz", "3d"])
    ap.add_argument("--title", default="")
    ap.add_argument("--every", type=int, default=1)
    ap.add_argument("--size", default="6x4.5")
    ap.add_argument("--dpi", type=int, default=100)
    a = ap.parse_args()

    ext = os.path.splitext(a.output)[1].lower()
    if ext not in (".mp4", ".gif"):
        fail(f"{a.output}: output must end in .mp4 or .gif")
    if not shutil.which("ffmpeg"):
        fail("ffmpeg not found (scripts/setup.sh installs it)")
    cells = os.path.join(a.dir, "cells.csv")
    if not os.path.isfile(cells):
        fail(f"{cells}: missing")
    files = sorted(glob.glob(os.path.join(a.dir, "frame_*.csv")))[:: max(1, a.every)]
    if not files:
        fail(f"{a.dir}: no frame_*.csv files")
    lines, polys = read_cells(cells)
    reading = Progress("render_frames: reading frame", len(files))
    frames = []
    for k, f in enumerate(files):
        frames.append(read_frame(f, a.field))
        reading.step(k + 1)
    reading.done()
    n = frames[0][1].shape[0]
    for f, fr in zip(files, frames):
        if fr[1].shape[0] != n:
            fail(f"{f}: {fr[1].shape[0]} nodes, the first frame has {n}")
    field = frames[0][3]
    allx = np.concatenate([fr[1] for fr in frames])
    lo, hi = allx.min(axis=0), allx.max(axis=0)
    view = a.view
    if view == "auto":
        z = frames[0][1][:, 2]
        view = "xy" if np.ptp(z) <= 1e-12 * max(np.ptp(frames[0][1], axis=0).max(), 1e-300) and np.ptp(allx[:, 2]) <= 1e-9 * max((hi - lo).max(), 1e-300) else "3d"
    vals = [fr[2] for fr in frames if fr[2] is not None]
    vmin, vmax = (min(v.min() for v in vals), max(v.max() for v in vals)) if vals else (0, 1)
    if vmax <= vmin:
        vmax = vmin + 1
    cmap = plt.get_cmap("viridis")
    norm = matplotlib.colors.Normalize(vmin, vmax)
    w, h = (float(v) for v in a.size.split("x"))
    pad = 0.05 * max((hi - lo).max(), 1e-12)

    # 3D: one length per axis unit (a cube around the bounding box), so that shapes are not distorted.
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2 + pad
    tmp = tempfile.mkdtemp(prefix="render_frames_")
    drawing = Progress("render_frames: drawing frame", len(frames))
    try:
        for k, (time, x, v, _) in enumerate(frames):
            drawing.step(k + 1)
            fig = plt.figure(figsize=(w, h), dpi=a.dpi)
            if view == "3d":
                from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

                ax = fig.add_subplot(projection="3d")
                if polys:
                    pc = Poly3DCollection([x[p] for p in polys], edgecolor="k", linewidths=0.2)
                    pc.set_facecolor(cmap(norm(np.array([v[p].mean() for p in polys]))) if v is not None else "C0")
                    ax.add_collection3d(pc)
                if len(lines):
                    lc = Line3DCollection(x[lines], linewidths=2)
                    lc.set_color(cmap(norm(v[lines].mean(axis=1))) if v is not None else "C0")
                    ax.add_collection3d(lc)
                ax.set_xlim(centre[0] - half, centre[0] + half)
                ax.set_ylim(centre[1] - half, centre[1] + half)
                ax.set_zlim(centre[2] - half, centre[2] + half)
                ax.set_box_aspect((1, 1, 1))
                ax.set_xlabel("x [m]")
                ax.set_ylabel("y [m]")
                ax.set_zlabel("z [m]")
            else:
                i, j = {"xy": (0, 1), "xz": (0, 2), "yz": (1, 2)}[view]
                ax = fig.add_subplot()
                if polys:
                    pc = PolyCollection([x[p][:, [i, j]] for p in polys], edgecolor="k", linewidths=0.2)
                    pc.set_facecolor(cmap(norm(np.array([v[p].mean() for p in polys]))) if v is not None else "C0")
                    ax.add_collection(pc)
                if len(lines):
                    lc = LineCollection(x[lines][:, :, [i, j]], linewidths=2)
                    lc.set_color(cmap(norm(v[lines].mean(axis=1))) if v is not None else "C0")
                    ax.add_collection(lc)
                ax.set_xlim(lo[i] - pad, hi[i] + pad)
                ax.set_ylim(lo[j] - pad, hi[j] + pad)
                ax.set_aspect("equal")
                ax.set_xlabel("xyz"[i] + " [m]")
                ax.set_ylabel("xyz"[j] + " [m]")
            if v is not None:
                fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax, label=field, shrink=0.8)
            label = (a.title + "  " if a.title else "") + (f"t = {time:.4g} s" if time is not None else f"frame {k}")
            ax.set_title(label)
            image = os.path.join(tmp, f"img_{k:05d}.png")
            try:
                fig.savefig(image)
            except OSError as err:
                if err.errno not in DISK_ERRORS:
                    raise
                write_failed(image, err)
            plt.close(fig)
        drawing.done()
        if PROGRESS is not None:
            print("render_frames: encoding with ffmpeg", file=PROGRESS, flush=True)
        src = ["-framerate", str(a.fps), "-i", os.path.join(tmp, "img_%05d.png")]
        if ext == ".mp4":
            cmd = ["ffmpeg", "-y", "-loglevel", "error", *src, "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                   "-c:v", "libx264", "-pix_fmt", "yuv420p", a.output]
        else:
            cmd = ["ffmpeg", "-y", "-loglevel", "error", *src, "-vf",
                   "split[s0][s1];[s0]palettegen[p];[s1][p]paletteuse", a.output]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode == -signal.SIGXFSZ:  # a file-size limit (subprocess restores its default action)
            write_failed(a.output, OSError(errno.EFBIG, os.strerror(errno.EFBIG)))
        if r.returncode != 0:
            reason = disk_error_text(r.stderr)
            if reason:  # ffmpeg could not write the animation (or read the frames back)
                write_failed(a.output, OSError(0, reason))
            fail("ffmpeg failed: " + (r.stderr.strip().splitlines() or ["?"])[-1])
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"render_frames: wrote {a.output} ({len(frames)} frames, view {view})")


if __name__ == "__main__":
    guarded(main)
