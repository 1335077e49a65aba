#!/usr/bin/python3
"""Figures 8-11 of WO2001052193 and the load-step animation, from a comparison's CSV output.

    /usr/bin/python3 compare/figures.py OUT_DIR [--title TITLE] [--mask 0.01] [--formats png,pdf] [--wait [--report]]

Reads OUT_DIR/{lines,cells,nodes,steps}.csv and lines.json (written by `workbench compare`) and
writes OUT_DIR/figures/fig8_ratio, fig9_stress_lines, fig9_stress_maps, fig10_deformed,
fig11_displacement (in each of --formats, default png) and agent_steps.gif. Lines are named by
their coordinates and described in the legends; 3D studies are drawn in the slice through the
first load's centre. With --wait (how `workbench compare` runs it, beside the FEM reference) it
loads matplotlib, takes the title from a line "title TEXT" on its standard input (instead of
--title), waits for a line "steps", draws the animation from steps.csv, lines.json and
agent/agent_nodes.csv, then waits for a line "draw" before it reads the other files. With --report
too, once the figures are written it says "drawn" back on its standard input (the workbench's
socket), waits for a line "report" (summary.json written) and renders report.html itself
(compare/report_html.py, its output into OUT_DIR/report.log): the study's last step then needs no
interpreter of its own.
Uses Debian's python3-matplotlib, python3-numpy and python3-pil only; call it with /usr/bin/python3.
"""
# glibc's malloc keeps the memory it frees and serves every block from its heap (no mmap of its own
# per large block, no trimming): each figure's canvas and image buffers (8-16 MB) reuse the pages of
# the last instead of mapping and zeroing new ones: 24 % fewer page faults, 0.93x the script's CPU
# (docs/performance.md). Before the imports, whose allocations it then covers too.
import ctypes
LIBC = ctypes.CDLL(None)
LIBC.mallopt(-4, 0)  # M_MMAP_MAX
LIBC.mallopt(-1, 1 << 30)  # M_TRIM_THRESHOLD, 1 GiB
import argparse  # noqa: E402
import csv  # noqa: E402
import gc  # noqa: E402
import json  # noqa: E402
import multiprocessing  # noqa: E402
import os  # noqa: E402
import signal  # noqa: E402
import sys  # noqa: E402
import textwrap  # noqa: E402
import time  # noqa: E402
import types  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.cm import ScalarMappable  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402  (matplotlib's own dependency)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from figure_files import fonts_from_memory, write_png  # noqa: E402
from child_report import DISK_ERRORS, WRITE_FAILED, guarded, tell_workbench, write_failed  # noqa: E402

# The cyclic garbage collector: the modules' objects, made once, are frozen out of its scans, and it
# runs after 10,000 new objects instead of 700 (a figure makes hundreds of thousands): 0.35 s of
# the script's CPU -> 0.08 s.
gc.freeze()
gc.set_threshold(10000, 20, 20)


def column_name(header):
    """A CSV column's name without its unit ("sigma_y [Pa]" -> "sigma_y")."""
    return header.split(" [")[0].strip()


def read_csv(path):
    with open(path, newline="") as f:
        header = [column_name(h) for h in f.readline().strip().split(",")]
        try:  # all-numeric files (cells, nodes, steps): numpy's C reader, much faster than csv
            data = np.loadtxt(f, delimiter=",", ndmin=2)
            if len(data) == 0:
                sys.exit(f"{path}: no rows")
            return {k: data[:, i] for i, k in enumerate(header)}
        except ValueError:
            pass
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{path}: no rows")
    columns = {}
    for k in rows[0]:
        column = np.array([r[k] for r in rows])
        try:
            columns[column_name(k)] = column.astype(float)
        except ValueError:
            columns[column_name(k)] = column
    return columns


def num(a):
    return a.astype(float) if a.dtype.kind != "f" else a


def progress(text):
    """A progress line for a person at a terminal: the workbench's terminal when it runs this script
    (descriptor WORKBENCH_PROGRESS_FD; everything else goes to figures.log), else stderr when that is
    a terminal; nothing otherwise."""
    fd = os.environ.get("WORKBENCH_PROGRESS_FD")
    if fd:
        os.write(int(fd), ("figures: " + text + "\n").encode())
    elif sys.stderr.isatty():
        print("figures: " + text, file=sys.stderr, flush=True)


def saving(path, write):
    """Runs write(path); a full disk or a file-size limit ends the script with the one report."""
    try:
        write(path)
    except OSError as err:
        if err.errno not in DISK_ERRORS:
            raise
        write_failed(path, err)


DPI = 150  # of the PNG figures; they are made at it, so that their layout is computed for it


# Fixed layouts, their margins in inches: room for tick labels and an axis label left of and below
# each axes, a title above each and the figure's title at the top, wrapped to the figure's width
# (each more line of it takes TITLE_LINE more). matplotlib's constrained layout measures every
# tick label's extent to place the axes: 30 % of the figures' CPU (docs/performance.md). The
# margins hold what these figures draw (tick labels of up to six characters).
LEFT, RIGHT, BOTTOM, TOP = 0.85, 0.25, 0.6, 0.65
BETWEEN = 0.95  # between two axes, across and down: the right one's labels, the lower one's title
TITLE_LINE = 0.22
CHARACTERS_PER_INCH = 9  # of the figure's title (12 pt)


def titled(fig, title):
    """Sets the figure's title, wrapped to its width; the margin above the axes it needs [in]."""
    lines = textwrap.wrap(title, width=int(CHARACTERS_PER_INCH * fig.get_figwidth())) or [""]
    fig.suptitle("\n".join(lines))
    return TOP + TITLE_LINE * (len(lines) - 1)


def panels(rows, cols, figsize, title):
    """A figure of rows x cols axes (an array of rows) under `title`, laid out as above."""
    width, height = figsize
    fig, axes = plt.subplots(rows, cols, figsize=figsize, dpi=DPI, squeeze=False)
    top = titled(fig, title)
    cell_w = (width - LEFT - RIGHT - (cols - 1) * BETWEEN) / cols
    cell_h = (height - BOTTOM - top - (rows - 1) * BETWEEN) / rows
    fig.subplots_adjust(left=LEFT / width, right=1 - RIGHT / width, bottom=BOTTOM / height, top=1 - top / height,
                        wspace=BETWEEN / cell_w, hspace=BETWEEN / cell_h)
    return fig, axes


def map_panels(rows, cols, figsize, aspect, title):
    """A figure of rows x cols maps of one data aspect (height / width) under `title`, each with a
    colour bar as tall as the map beside it: (figure, axes, colour bar axes), arrays of rows.
    Titles of two lines."""
    width, height = figsize
    bar, gap, bar_labels = 0.15, 0.1, 0.75  # the colour bar's width, its gap, its ticks and label
    fig = plt.figure(figsize=figsize, dpi=DPI)
    top, between_y = titled(fig, title) + 0.25, BETWEEN + 0.25
    cell_w = (width - LEFT - RIGHT - (cols - 1) * BETWEEN) / cols
    cell_h = (height - BOTTOM - top - (rows - 1) * between_y) / rows
    w = min(cell_w - gap - bar - bar_labels, cell_h / aspect)
    h = aspect * w
    axes = np.empty((rows, cols), dtype=object)
    bars = np.empty((rows, cols), dtype=object)
    for r in range(rows):
        y0 = height - top - (r + 1) * cell_h - r * between_y + (cell_h - h) / 2
        for c in range(cols):
            x0 = LEFT + c * (cell_w + BETWEEN)
            axes[r, c] = fig.add_axes([x0 / width, y0 / height, w / width, h / height])
            bars[r, c] = fig.add_axes([(x0 + w + gap) / width, y0 / height, bar / width, h / height])
    return fig, axes, bars


def save(fig, out, name, formats):
    for ext in formats:
        write = (lambda p: write_png(fig, p, DPI)) if ext == "png" else (lambda p: fig.savefig(p, dpi=DPI))
        saving(os.path.join(out, f"{name}.{ext}"), write)
    plt.close(fig)
    progress(f"{name} drawn")


def line_groups(meta):
    """The lines along a load (and the user's) and the lines across a load, as lines.json lists them."""
    along = [m for m in meta if m["kind"] in ("along", "user")]
    across = [m for m in meta if m["kind"] == "across"]
    return along, across


def line_data(lines, model, name):
    """One model's samples along one line, with a NaN row where the line crosses air (lines.csv has
    only the samples inside the agents, its `segment` column one more after each stretch of air), so
    that the plotted line stops at air instead of bridging it."""
    sel = (lines["model"] == model) & (lines["line"] == name)
    d = {k: num(v[sel]) for k, v in lines.items() if k not in ("model", "line", "segment")}
    gaps = np.nonzero(np.diff(num(lines["segment"][sel])))[0] + 1
    return {k: np.insert(v, gaps, np.nan) for k, v in d.items()}


def in_slice(table, zc):
    """The rows of a 3D table in the lattice plane nearest z = zc (all rows of a 2D table)."""
    if "z" not in table:
        return table
    z = num(table["z"])
    keep = np.isclose(z, z[np.argmin(abs(z - zc))])
    return {k: v[keep] for k, v in table.items()}


def agent_lattice(x, y, node_x, node_y):
    """The agents' lattice as the agent grid holds it (docs/agent-model.md, "Memory"), from the
    agents' centres and the nodes' coordinates [m]: a column or row that is all air keeps its
    place, a run of them is one air column as wide as the gap. Gives grid_of(values) (one value per
    agent at its slot, NaN elsewhere), draw(ax, grid, cmap, vmin, vmax) and update(artist, grid) for
    a map, the agent size h [m] (the nearest two node planes: every agent has two) and the drawn
    lattice's aspect (height / width)."""
    def axis(c, node_c):
        u = np.unique(c)
        h = np.diff(np.unique(node_c)).min()
        steps = np.rint(np.diff(u) / h).astype(np.int64)  # lattice steps between occupied columns
        column = np.concatenate(([0], np.cumsum(np.minimum(steps, 2))))  # a gap is one column
        edges = np.empty(column[-1] + 2)
        edges[column] = u - h / 2
        edges[column + 1] = u + h / 2
        return edges, column[np.searchsorted(u, c)], bool((steps > 2).any()), h

    (xe, ix, x_collapsed, h), (ye, iy, y_collapsed, _) = axis(x, node_x), axis(y, node_y)
    collapsed = x_collapsed or y_collapsed

    def grid_of(values):
        g = np.full((len(ye) - 1, len(xe) - 1), np.nan)
        g[iy, ix] = values
        return g

    # A regular lattice is drawn as an image; a collapsed one as a mesh with its columns at their
    # true places and widths (an image would draw a gap of 1 m as wide as one agent). The image is
    # coloured here, one pixel per agent, and given to matplotlib as RGBA bytes: it then only scales
    # it up (nearest pixel) instead of scaling the values in float64 and colouring every pixel of the
    # screen (the same picture, to one level of 255 in a few pixels; a quarter of the CPU, and
    # 15,000 fewer page faults for Fig. 9's eight maps). The artist keeps the norm and colour map
    # (artist.scale) for its colour bar and update().
    def draw(ax, values, cmap, vmin, vmax):
        if collapsed:
            ax.set_aspect("equal")  # as an image is drawn
            mesh = ax.pcolormesh(1e3 * xe, 1e3 * ye, values, shading="flat", cmap=cmap, vmin=vmin, vmax=vmax)
            mesh.scale = mesh
            return mesh
        extent = [1e3 * xe[0], 1e3 * xe[-1], 1e3 * ye[0], 1e3 * ye[-1]]
        scale = ScalarMappable(Normalize(vmin, vmax), cmap)
        image = ax.imshow(scale.to_rgba(values, bytes=True), origin="lower", extent=extent)
        image.scale = scale
        return image

    def update(artist, values):
        if collapsed:
            artist.set_array(values.ravel())
        else:
            artist.set_data(artist.scale.to_rgba(values, bytes=True))

    aspect = (ye[-1] - ye[0]) / (xe[-1] - xe[0])  # of the drawn lattice, height / width
    return types.SimpleNamespace(grid_of=grid_of, draw=draw, update=update, h=h, aspect=aspect)


def animation_gif(steps, agent_nodes, out, name="agent_steps.gif"):
    """The seed's animation: the agents' sigma_y as the load rises step by step (steps.csv and
    agent/agent_nodes.csv only)."""
    step = num(steps["step"]).astype(int)
    step_ids = np.unique(step)
    first = step == step_ids[0]  # every agent once, in cell order
    agents = agent_lattice(num(steps["x"][first]), num(steps["y"][first]), num(agent_nodes["x"]), num(agent_nodes["y"]))
    grid_of = agents.grid_of
    n = int(first.sum())
    sy = num(steps["sigma_y"])
    generation = num(steps["generation"])
    load = num(steps["load"])
    lim = max(np.abs(sy).max(), 1e-300)
    fig, ax = plt.subplots(figsize=(6, 5.5))
    # Compression -sigma_y from light (none) to dark (most); agents the load has not reached in grey,
    # air blank (white, drawn over the grey).
    cmap = plt.get_cmap("magma_r").copy()
    cmap.set_bad("0.85")
    image = agents.draw(ax, grid_of(np.zeros(n)), cmap=cmap, vmin=0, vmax=lim / 1e3)
    air = np.isnan(grid_of(np.zeros(n)))
    air_map = [agents.draw(ax, np.where(air, 1.0, np.nan), cmap="gray", vmin=0, vmax=1)] if air.any() else []
    fig.colorbar(image.scale, ax=ax, label="agent compression -sigma_y [kPa] (grey: not reached; white: air)")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    label = ax.set_title("")
    # Blitting: the figure is drawn once without the artists that change (the agents' image, the air
    # over it, the title) and the axes' frame drawn over them; each frame restores that and draws
    # only these, in a full draw's order (the same pixels, a third of the CPU of 20 full draws).
    changing = [image] + air_map + list(ax.spines.values()) + [label]  # in drawing order
    for artist in changing:
        artist.set_animated(True)
    fig.canvas.draw()
    background = fig.canvas.copy_from_bbox(fig.bbox)
    frames = []
    for k in step_ids:
        sel = step == k  # the same cell order in every step
        agents.update(image, grid_of(np.where(generation[sel] >= 0, -sy[sel] / 1e3, np.nan)))
        label.set_text(f"agents, load {load[sel][0]:.3g} N (step {k}/{step_ids[-1]})")
        fig.canvas.restore_region(background)
        for artist in changing:
            fig.draw_artist(artist)
        frames.append(Image.frombuffer("RGBA", fig.canvas.get_width_height(), bytes(fig.canvas.buffer_rgba()),
                                       "raw", "RGBA", 0, 1))
    plt.close(fig)
    # As matplotlib's PillowWriter saves them, at 4 frames per second, looping.
    saving(os.path.join(out, name),
           lambda p: frames[0].save(p, save_all=True, append_images=frames[1:], duration=250, loop=0))
    progress(f"{name} drawn")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--title", default="")
    ap.add_argument("--mask", type=float, default=0.01)
    ap.add_argument("--formats", default="png", help="comma-separated: png, pdf ([compare] figure_formats)")
    ap.add_argument("--wait", action="store_true",
                    help="draw the animation, then wait for 'draw' on stdin before reading the other files")
    ap.add_argument("--report", action="store_true",
                    help="with --wait: say 'drawn' back on stdin, wait for 'report', render report.html")
    args = ap.parse_args()
    if args.report and not args.wait:
        ap.error("--report needs --wait")
    out = os.path.join(args.dir, "figures")
    os.makedirs(out, exist_ok=True)
    title = args.title
    formats = args.formats.split(",")
    if set(formats) <= {"png"}:
        fonts_from_memory()

    def wait_for(word, what):
        """--wait: blocks until the workbench writes a line `word` [TEXT] on our input (what it
        names is ready); gives TEXT."""
        start = time.time()
        said, _, text = sys.stdin.readline().rstrip("\n").partition(" ")
        if said != word:
            sys.exit(f"figures: the workbench stopped before {what} was complete")
        print(f"figures: waited {time.time() - start:.2f} s for {what}", flush=True)
        return text

    if args.wait:
        title = wait_for("title", "the case's title")
        wait_for("steps", "steps.csv")
    with open(os.path.join(args.dir, "lines.json")) as f:
        meta = json.load(f)
    along, across = line_groups(meta)
    groups = ((along, "along the loads"), (across, "across the loads"))
    # 3D: the slice through the first load's centre (its along line's z).
    zc = along[0]["from"][2]
    steps = in_slice(read_csv(os.path.join(args.dir, "steps.csv")), zc)
    agent_nodes = read_csv(os.path.join(args.dir, "agent", "agent_nodes.csv"))  # for the agent size
    slice_note = f", slice z = {1e3 * zc:.4g} mm" if "z" in steps else ""
    print(f"figures: read steps.csv in {time.process_time():.2f} s CPU (with the imports)", flush=True)

    def animation():
        animation_gif(steps, agent_nodes, out)

    if args.wait:  # the animation needs only the agents: drawn while the workbench solves the FEM reference
        run_all([animation])
        wait_for("draw", "the comparison's data")
    start = time.process_time()

    lines = read_csv(os.path.join(args.dir, "lines.csv"))
    cells = in_slice(read_csv(os.path.join(args.dir, "cells.csv")), zc)
    nodes = in_slice(read_csv(os.path.join(args.dir, "nodes.csv")), zc)

    def legend(ax):
        ax.legend(fontsize=6, loc="best")
        ax.grid(alpha=0.3)

    def fig8():
        # Fig. 8: ratio agent / FEM of sigma_x and sigma_y along the lines, masked where |FEM| is small
        # against the line's own maximum (a ratio blows up at a sign change), and beside it the signed
        # error over the line's maximum |FEM|, which does not.
        fig, axes = panels(2, 4, (20, 8), f"Fig. 8 - agent against FEM stress ({title}{slice_note}); ratio masked "
                           f"where |FEM| < {args.mask:g} of the line's max|FEM|")
        for row, comp in enumerate(("sigma_x", "sigma_y")):
            for col, (group, what) in enumerate(groups):
                ax_r, ax_e = axes[row, 2 * col], axes[row, 2 * col + 1]
                for m in group:
                    a, f = line_data(lines, "agent", m["name"]), line_data(lines, "fem", m["name"])
                    ref = f[comp]
                    scale = np.nanmax(np.abs(ref))
                    with np.errstate(invalid="ignore"):  # NaN: the line crosses air
                        valid = np.abs(ref) >= args.mask * scale if scale > 0 else np.zeros(len(ref), bool)
                    ratio = np.where(valid, a[comp] / np.where(valid, ref, 1.0), np.nan)
                    s_mm = 1e3 * a["arc_length"]
                    ax_r.plot(s_mm, ratio, "o-", ms=2, label=m["description"])
                    ax_e.plot(s_mm, (a[comp] - ref) / (scale if scale > 0 else 1.0), "-", label=m["description"])
                ax_r.axhline(1.0, color="k", lw=0.8)
                ax_e.axhline(0.0, color="k", lw=0.8)
                for ax in (ax_r, ax_e):
                    ax.set_xlabel("distance along the line from its start [mm]")
                ax_r.set_ylabel(f"{comp} agent / FEM [-]")
                ax_e.set_ylabel(f"({comp} agent - FEM) / max|FEM| on the line [-]")
                ax_r.set_title(f"{what}: {comp} ratio")
                ax_e.set_title(f"{what}: {comp} signed error")
                legend(ax_r)
                legend(ax_e)
        save(fig, out, "fig8_ratio", formats)

    def fig9_lines():
        # Fig. 9: sigma_x and sigma_y of both models, along the lines and as maps side by side.
        fig, axes = panels(2, 2, (12, 8), f"Fig. 9 - stress of agent (dashed) and FEM (solid) ({title}{slice_note})")
        for row, comp in enumerate(("sigma_x", "sigma_y")):
            for col, (group, what) in enumerate(groups):
                ax = axes[row, col]
                for i, m in enumerate(group):
                    for model, style in (("fem", "-"), ("agent", "--")):
                        d = line_data(lines, model, m["name"])
                        label = ("FEM, " if model == "fem" else "agent, ") + m["description"]
                        ax.plot(1e3 * d["arc_length"], d[comp] / 1e3, style, color=f"C{i}", label=label)
                ax.set_xlabel("distance along the line from its start [mm]")
                ax.set_ylabel(f"{comp} [kPa]")
                ax.set_title(f"{what}: {comp}")
                legend(ax)
        save(fig, out, "fig9_stress_lines", formats)

    agents = agent_lattice(num(cells["x"]), num(cells["y"]), num(nodes["x"]), num(nodes["y"]))
    grid_of, draw_map, h, aspect = agents.grid_of, agents.draw, agents.h, agents.aspect

    def fig9_maps():
        # Every stress field the comparison has (cells.csv): the seed's sigma_x, sigma_y, then tau_xy and
        # von Mises. A field whose body error is not below the zero model's (relative L2 1) says so.
        comps = [c for c in ("sigma_x", "sigma_y", "tau_xy", "von_mises") if f"fem_{c}" in cells]
        fig, axes, bars = map_panels(len(comps), 2, (10, 4.5 * len(comps)), aspect,
                                     f"Fig. 9 - stress maps, FEM (left) and agent (right) ({title}{slice_note})")
        for row, comp in enumerate(comps):
            f, a = num(cells[f"fem_{comp}"]), num(cells[f"agent_{comp}"])
            rel_l2 = np.linalg.norm(a - f) / (np.linalg.norm(f) or 1.0)
            verdict = f"body rel. L2 {rel_l2:.3g}" + (": WORSE THAN ZERO" if rel_l2 >= 1 else "")
            lim = np.percentile(np.abs(f), 99) or 1.0
            sequential = comp == "von_mises"
            for col, model in enumerate(("fem", "agent")):
                ax = axes[row, col]
                im = draw_map(ax, grid_of(num(cells[f"{model}_{comp}"])) / 1e3, cmap="viridis" if sequential else "RdBu_r",
                              vmin=0 if sequential else -lim / 1e3, vmax=lim / 1e3)
                ax.set_title(f"{'FEM' if model == 'fem' else 'agent'}: {comp}\n" + ("" if model == "fem" else f"({verdict})"))
                ax.set_xlabel("x [mm]")
                ax.set_ylabel("y [mm]")
                fig.colorbar(im.scale, cax=bars[row, col], label=f"{comp} [kPa] (clipped at the FEM 99th percentile)")
        save(fig, out, "fig9_stress_maps", formats)

    def fig10():
        # Fig. 10: deformed shape, (a) FEM and (b) agents, one magnification for both.
        # nodes.csv has the body's nodes only: air stays NaN, so no grid line is drawn across it.
        ni, nj = num(nodes["i"]).astype(int), num(nodes["j"]).astype(int)
        nx_, ny_ = ni.max() + 1, nj.max() + 1

        def node_grid(values):
            g = np.full((ny_, nx_), np.nan)
            g[nj, ni] = values
            return g

        X, Y = node_grid(num(nodes["x"])), node_grid(num(nodes["y"]))
        span = max(np.nanmax(X) - np.nanmin(X), np.nanmax(Y) - np.nanmin(Y))
        u_max = max(np.abs(num(nodes["fem_u_x"])).max(), np.abs(num(nodes["fem_u_y"])).max(),
                    np.abs(num(nodes["agent_u_x"])).max(), np.abs(num(nodes["agent_u_y"])).max(), 1e-300)
        magnification = 0.1 * span / u_max
        every = max(1, (nx_ - 1) // 25)
        # A collapsed air column (row) lies between two node columns (rows) farther apart than an
        # agent: no grid line crosses it.
        wide_x = np.nonzero(np.diff(np.fmax.reduce(X, axis=0)) > 1.5 * h)[0] + 1
        wide_y = np.nonzero(np.diff(np.fmax.reduce(Y, axis=1)) > 1.5 * h)[0] + 1
        def columns(A):  # the drawn node columns, broken at wide rows
            return np.insert(A[:, ::every], wide_y, np.nan, axis=0)
        def rows(A):  # the drawn node rows, broken at wide columns
            return np.insert(A[::every, :], wide_x, np.nan, axis=1).T
        fig, axes = panels(1, 2, (12, 6), f"Fig. 10 - deformed shape, displacements magnified x{magnification:.3g} "
                           f"(grey: undeformed); every {every}. grid line drawn (every {every * 1e3 * h:.3g} mm) "
                           f"({title}{slice_note})")
        axes = axes[0]
        for ax, model, label in ((axes[0], "fem", "(a) FEM"), (axes[1], "agent", "(b) agents")):
            U, V = node_grid(num(nodes[f"{model}_u_x"])), node_grid(num(nodes[f"{model}_u_y"]))
            Xd, Yd = 1e3 * (X + magnification * U), 1e3 * (Y + magnification * V)
            ax.plot(1e3 * columns(X), 1e3 * columns(Y), color="0.85", lw=0.5)
            ax.plot(1e3 * rows(X), 1e3 * rows(Y), color="0.85", lw=0.5)
            ax.plot(columns(Xd), columns(Yd), color="C0", lw=0.6)
            ax.plot(rows(Xd), rows(Yd), color="C0", lw=0.6)
            ax.set_aspect("equal")
            ax.set_title(f"{label}, |u|max = {np.nanmax(np.hypot(U, V)):.3g} m")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
        save(fig, out, "fig10_deformed", formats)

    def fig11():
        # Fig. 11: displacement of both models along the lines, both components.
        fig, axes = panels(2, 2, (12, 9), f"Fig. 11 - displacement of agent (dashed) and FEM (solid) ({title}{slice_note})")
        for col, (group, what) in enumerate(groups):
            for row, comp in enumerate(("u_y", "u_x")):
                ax = axes[row, col]
                for i, m in enumerate(group):
                    for model, style in (("fem", "-"), ("agent", "--")):
                        d = line_data(lines, model, m["name"])
                        label = ("FEM, " if model == "fem" else "agent, ") + m["description"]
                        ax.plot(1e3 * d["arc_length"], 1e9 * d[comp], style, color=f"C{i}", label=label)
                ax.set_xlabel("distance along the line from its start [mm]")
                ax.set_ylabel(f"{comp} [nm]")
                ax.set_title(f"{what}: {comp}")
                legend(ax)
        save(fig, out, "fig11_displacement", formats)

    print(f"figures: read the comparison's data in {time.process_time() - start:.2f} s CPU", flush=True)
    # The figures are independent: drawn by two processes, this one and a forked child sharing the
    # data read above, which halves the wall time on two cores (docs/performance.md). Each takes the
    # next figure from a queue, the dearest first (their CPU times in figures.log), whenever it is
    # free: neither waits for a share the other was given in advance, whose cost varies with what
    # else runs. This process draws its share itself: a second child would copy the pages it shares
    # with this one as Python writes their reference counts. On one core (the CPUs this process
    # may run on, as taskset sets them) this process draws them all: two would cost more CPU for no
    # gain.
    jobs = [fig9_maps, fig8] + ([] if args.wait else [animation]) + [fig11, fig9_lines, fig10]
    # --report: the page's template is compiled (Jinja2 loaded) once the queue is empty, while the
    # other drawing process finishes its last figure.
    page = None
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    if cpus and cpus > 1:
        gc.freeze()  # the collector in the drawing processes does not write to (and copy) the pages they share
        queue = job_queue(len(jobs))
        parent = os.getpid()
        child = multiprocessing.get_context("fork").Process(target=run_share, args=(jobs, queue, parent), daemon=True)
        child.start()
        run_queue(jobs, queue)
        page = report_template() if args.report else None
        child.join()
        if child.exitcode == WRITE_FAILED:
            os._exit(WRITE_FAILED)  # the drawing process has sent the report
        if child.exitcode != 0:
            sys.exit("figures: a drawing process failed")
    else:
        run_all(jobs)
    print(f"figures: wrote {out}", flush=True)
    if args.report:
        page = page or report_template()
        tell_workbench("drawn")
        wait_for("report", "summary.json")
        render_report(args.dir, page)


def report_template():
    """report.html's template, compiled (Jinja2 is loaded only by a run that renders the page)."""
    import report_html  # compare/report_html.py, beside this script
    return report_html.template()


def render_report(out, page):
    """report.html, as `report_html.py OUT` writes it, its output into OUT/report.log."""
    import report_html
    log = os.open(os.path.join(out, "report.log"), os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    sys.stdout.flush()
    sys.stderr.flush()
    os.dup2(log, 1)
    os.dup2(log, 2)
    os.close(log)
    report_html.render(out, page)


def job_queue(n):
    """The numbers 0..n-1 in a pipe, its writing end closed: read one byte at a time by several
    processes, each number goes to exactly one (a read of one byte from a pipe is atomic)."""
    read_end, write_end = os.pipe()
    os.write(write_end, bytes(range(n)))
    os.close(write_end)
    return read_end


def run_queue(figures, queue):
    """Draws figures[k] for every number k it takes from `queue` (job_queue), until it is empty."""
    while k := os.read(queue, 1):
        run_all([figures[k[0]]])


def run_share(figures, queue, parent):
    """The forked child's share of the figures (run_queue). It ends with its parent, however the
    parent ends (a failed write ends it with os._exit, which runs no exit handler to end a daemon
    child)."""
    LIBC.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    if os.getppid() != parent:  # the parent ended before the line above
        os._exit(1)
    run_queue(figures, queue)


def run_all(figures):
    for draw in figures:
        start = time.process_time()
        draw()
        print(f"figures: {draw.__name__} {time.process_time() - start:.2f} s CPU", flush=True)


if __name__ == "__main__":
    guarded(main)
    # Its output flushed (guarded): ended without the interpreter's teardown, which frees every
    # object the figures made one by one (0.2 s of the script's CPU, docs/performance.md).
    os._exit(0)
