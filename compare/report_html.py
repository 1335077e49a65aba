#!/usr/bin/python3
"""One page per study: report.html from a comparison's summary.json (a calibration's report.json, a
front's front.json) and its figures.

    /usr/bin/python3 compare/report_html.py OUT_DIR

`workbench compare`, `workbench calibrate` and `workbench front` run it once everything else is written, before the
output folder is committed. The page is rendered with Jinja2 (Debian's python3-jinja2) from
report.html.j2 beside this script and written through a temporary file renamed into place: a
page is whole or not there. The figures (PNG, GIF) are embedded as data: URIs, so report.html alone
is the whole report (a CI artifact, a mail attachment); the study's other files are linked relative
to it; nothing is loaded from the network. Every value the page shows carries data-key (a JSON
pointer into the summary) and data-format (how it is shown), so that tests/common/check_report.py
can check each one against the JSON. On error: one line on stderr, exit 1, no report.html.
"""
import base64
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
from child_report import DISK_ERRORS, write_failed  # noqa: E402  (scripts/child_report.py)

try:
    import jinja2
    from markupsafe import Markup, escape
except ImportError as e:
    raise SystemExit(f"report_html.py: {e.name} is missing: install Debian's python3-jinja2 (scripts/setup.sh)")

HERE = os.path.dirname(os.path.abspath(__file__))
TEMPLATE = "report.html.j2"
IMAGES = {".png": "image/png", ".gif": "image/gif"}  # embedded; other figure files (PDF) are linked
MANY = 12  # a folder with more files than this is listed folded


class Page:
    """The JSON and the helpers the template shows its values with."""

    def __init__(self, data):
        self.data = data

    def get(self, *path):
        value = self.data
        for p in path:
            value = value[p]
        return value

    def has(self, *path):
        try:
            self.get(*path)
            return True
        except (KeyError, IndexError, TypeError):
            return False

    def show(self, *path, fmt="num"):
        """A value of the JSON as text, marked with its pointer and format."""
        value = self.get(*path)
        text = {"num": number, "text": str, "list": lambda v: ", ".join(str(x) for x in v),
                "pass": lambda v: "ok" if v else "EXCEEDED",
                "flag": lambda v: path[-1].replace("_", " "),
                "modelled": lambda v: "modelled" if v else "not modelled"}[fmt](value)
        pointer = "".join("/" + str(p).replace("~", "~0").replace("/", "~1") for p in path)
        return Markup(f'<span data-key="{escape(pointer)}" data-format="{fmt}">{escape(text)}</span>')

    def flags(self, name):
        """A metric's boolean marks other than the gate's verdict (e.g. an error worse than a zero
        model), each shown when true."""
        entry = self.data["metrics"][name]
        return [k for k, v in entry.items() if isinstance(v, bool) and k != "passed" and v]


def number(v):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ValueError(f"not a number: {v!r}")
    if isinstance(v, int):
        return str(v)
    if not math.isfinite(v):
        raise ValueError(f"not a finite number: {v!r}")
    return f"{v:.4g}"


def figures(out):
    """The figures to embed: (file name, data URI), in the order the study draws them."""
    folder = os.path.join(out, "figures")
    found = []
    def order(name):  # fig8, fig9, fig10, ..., then the animation
        return name.endswith(".gif"), [int(t) if t.isdigit() else t for t in re.split(r"(\d+)", name)]

    for name in sorted(os.listdir(folder) if os.path.isdir(folder) else [], key=order):
        mime = IMAGES.get(os.path.splitext(name)[1])
        if mime:
            with open(os.path.join(folder, name), "rb") as f:
                found.append((name, f"data:{mime};base64,{base64.b64encode(f.read()).decode()}"))
    return found


def files(out):
    """Every file of the study but the page itself, by folder: [(folder, [relative path])]."""
    groups = {}
    for root, dirs, names in os.walk(out):
        dirs.sort()
        rel = os.path.relpath(root, out)
        for name in sorted(names):
            if rel == "." and name in ("report.html", "report.log") or name.startswith("."):
                continue
            groups.setdefault("" if rel == "." else rel, []).append(name if rel == "." else f"{rel}/{name}")
    return sorted(groups.items())


def template():
    """report.html.j2 beside this script, compiled (figures.py compiles it while its other drawing
    process finishes, then renders the page itself: no second interpreter at the study's end)."""
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(HERE), undefined=jinja2.StrictUndefined,
                             autoescape=True, trim_blocks=True, lstrip_blocks=True)
    try:
        return env.get_template(TEMPLATE)
    except jinja2.TemplateError as e:
        raise SystemExit(f"report_html.py: {os.path.join(HERE, TEMPLATE)}: cannot compile it ({type(e).__name__}: {e})")


def render(out, page_template=None):
    """Writes OUT/report.html with `page_template` (template() when None)."""
    page_template = page_template or template()
    sources = [os.path.join(out, name) for name in ("summary.json", "report.json", "front.json")]
    source = next((s for s in sources if os.path.exists(s)), sources[1])
    try:
        with open(source) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        raise SystemExit(f"report_html.py: {source}: cannot read it ({e})")
    kind = {"report.json": "calibration", "front.json": "front"}.get(os.path.basename(source), data.get("model", "agent"))
    try:
        html = page_template.render(
            kind=kind, page=Page(data), d=data, source=os.path.basename(source),
            figures=figures(out), files=files(out), many=MANY)
    except (jinja2.TemplateError, KeyError, IndexError, TypeError, ValueError) as e:
        raise SystemExit(f"report_html.py: {source}: the page cannot be rendered ({type(e).__name__}: {e})")
    target = os.path.join(out, "report.html")
    temporary = target + ".part"
    try:
        with open(temporary, "w", encoding="utf-8") as f:
            f.write(html)
        os.replace(temporary, target)
    except OSError as e:
        if os.path.exists(temporary):
            os.remove(temporary)
        if e.errno in DISK_ERRORS:  # a full disk, a file-size limit: reported as every failed write is
            write_failed(temporary, e)
        raise SystemExit(f"report_html.py: {target}: cannot write it ({e.strerror})")
    print(f"report_html.py: wrote {target} ({len(html)} bytes)")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit("usage: report_html.py OUT_DIR")
    render(sys.argv[1])
