#!/usr/bin/python3
"""Every shipped case run by two builds of the workbench, and their outputs compared file by file.

    /usr/bin/python3 tests/same_outputs.py OLD_TREE NEW_TREE [--cases NAME ...] [--skip NAME ...]

OLD_TREE and NEW_TREE are checkouts with a build in build/ (e.g. `git worktree add ../old main~3`
and `bash scripts/build.sh` there). Each runs its own cases/*.toml (case keys may be renamed
between them) with the subcommands the case has sections for: `calibrate` for a [calibrate] case,
`pbd` for a PBD case without [compare], else `agent`, `fem` and `compare`. Then every file of every
output folder is compared:
- byte for byte; where the bytes differ,
- a JSON file key by key: every number bit for bit; timings (keys starting with "time") aside;
  keys only the new output has are listed as added (they are not differences), keys it lost are
  differences;
- a CSV file column by column, by header name: every column the old file has must hold the same
  text in every row; columns only the new file has are listed as added;
- a VTU file array by array, by name (the encoded data of each array; its range attributes
  follow from it): arrays only the new file has are listed as added;
- any other text file (TOML, the output stamp, logs) line by line, timing lines ("time",
  "seconds", "memory", " s)") aside.
Paths into OLD_TREE read as the same paths into NEW_TREE. A binary file that differs (PNG, GIF,
compressed VTU) and a file present in the old output only are differences; a file only the new
output has is listed as added. Prints one
line per case and exits 1 when any output differs.
"""
import argparse
import csv
import io
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

# Lines and JSON keys that measure the run, not its result.
TIMING = re.compile(r"time|seconds|waited|\d s\)|wall|cpu|memory", re.IGNORECASE)


def subcommands(case_path):
    text = open(case_path).read()
    if re.search(r"^\[calibrate\]", text, re.M):
        return ["calibrate"]
    if re.search(r"^\[pbd\]", text, re.M) and not re.search(r"^\[compare\]", text, re.M):
        return ["pbd"]
    return ["agent", "fem", "compare"]


def run(tree, sub, case, out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [os.path.join(tree, "build/cli/workbench"), sub, os.path.join(tree, "cases", case), "-o", out]
    r = subprocess.run(cmd, cwd=tree, env=env, capture_output=True, text=True)
    # compare exits 1 when a gate is exceeded: an outcome to compare, not a failure of the run
    return r.returncode, r.stderr.strip().splitlines()[-1:] if r.returncode not in (0, 1) else []


def json_diff(a, b, path=""):
    """(differences, added keys) between old `a` and new `b`."""
    diffs, added = [], []
    if isinstance(a, dict) and isinstance(b, dict):
        for k in a:
            if TIMING.search(k):
                continue
            if k not in b:
                moved = b.get("coefficients", {})  # the coefficients gathered in one table
                if isinstance(moved, dict) and moved.get(k) == a[k]:
                    added.append(f"{path}/{k} -> {path}/coefficients/{k}")
                else:
                    diffs.append(f"{path}/{k}: gone")
            else:
                d, ad = json_diff(a[k], b[k], f"{path}/{k}")
                diffs += d
                added += ad
        added += [f"{path}/{k}" for k in b if k not in a]
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            d, ad = json_diff(x, y, f"{path}[{i}]")
            diffs += d
            added += ad
    elif isinstance(a, float) and isinstance(b, float):
        if not (a == b or (math.isnan(a) and math.isnan(b))):
            diffs.append(f"{path}: {a!r} -> {b!r}")
    elif a != b:
        diffs.append(f"{path}: {a!r} -> {b!r}")
    return diffs, added


# A staging folder's name holds the process id (.compare.partial-1234): not a result.
STAGING = re.compile(r"\.partial-\d+")


def text_diff(a, b):
    keep = lambda text: [STAGING.sub(".partial", l) for l in text.splitlines() if not TIMING.search(l)]
    la, lb = keep(a), keep(b)
    return [] if la == lb else [f"first differing line: {x!r} -> {y!r}" for x, y in zip(la + [""], lb + [""]) if x != y][:1]


def csv_diff(a, b):
    """(differences, added columns) between two CSV texts, columns matched by header name."""
    ra, rb = list(csv.reader(io.StringIO(a))), list(csv.reader(io.StringIO(b)))
    if not ra or not rb:
        return ([] if ra == rb else ["one file is empty"]), []
    ha, hb = ra[0], rb[0]
    added = [h for h in hb if h not in ha]
    gone = [h for h in ha if h not in hb]
    if gone:
        return [f"columns gone: {gone}"], added
    if len(ra) != len(rb):
        return [f"{len(ra) - 1} rows -> {len(rb) - 1} rows"], added
    where = [hb.index(h) for h in ha]
    for i, (x, y) in enumerate(zip(ra[1:], rb[1:]), start=1):
        if x and TIMING.search(x[0]):  # a key-value table's timing row (fem_summary.csv)
            continue
        same = x == y if ha == hb else [y[j] if j < len(y) else None for j in where] == x
        if not same:
            return [f"row {i} differs in an old column: {x!r} -> {y!r}"], added
    return [], added


DATA_ARRAY = re.compile(r'<DataArray[^>]*Name="([^"]+)"[^>]*>(.*?)</DataArray>', re.S)


def vtu_diff(a, b):
    """(differences, added arrays) between two VTU texts, arrays matched by name."""
    aa, ab = dict(DATA_ARRAY.findall(a)), dict(DATA_ARRAY.findall(b))
    diffs = [f"array {n!r}: gone" for n in aa if n not in ab]
    diffs += [f"array {n!r}: data differ" for n in aa if n in ab and aa[n] != ab[n]]
    return diffs, [n for n in ab if n not in aa]


def compare_dirs(old, new, old_tree, new_tree):
    diffs, added = [], []
    files = lambda d: {os.path.relpath(os.path.join(r, f), d) for r, _, fs in os.walk(d) for f in fs}
    fo, fn = files(old), files(new)
    diffs += [f"{f}: only in the old output" for f in sorted(fo - fn)]
    added += [f"{f}" for f in sorted(fn - fo)]
    for f in sorted(fo & fn):
        a, b = open(os.path.join(old, f), "rb").read(), open(os.path.join(new, f), "rb").read()
        if a == b:
            continue
        try:  # text: the old tree's paths read as the new tree's
            ta = a.decode().replace(old_tree, new_tree).replace(os.path.dirname(old), os.path.dirname(new))
            tb = b.decode()
        except UnicodeDecodeError:
            diffs.append(f"{f}: bytes differ")
            continue
        if f.endswith(".json"):
            d, ad = json_diff(json.loads(ta), json.loads(tb))
            diffs += [f"{f}{x}" for x in d]
            added += [f"{f}{x}" for x in ad]
        elif f.endswith(".csv") or f.endswith(".vtu"):
            d, ad = (csv_diff if f.endswith(".csv") else vtu_diff)(ta, tb)
            diffs += [f"{f}: {x}" for x in d]
            added += [f"{f}: {x}" for x in ad]
        else:
            diffs += [f"{f}: {x}" for x in text_diff(ta, tb)]
    return diffs, added


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("old_tree")
    p.add_argument("new_tree")
    p.add_argument("--cases", nargs="*", help="case files by name (default: every cases/*.toml of the new tree)")
    p.add_argument("--skip", nargs="*", default=[], help="case names to leave out (e.g. ring.toml, 10 min)")
    a = p.parse_args()
    old, new = os.path.realpath(a.old_tree), os.path.realpath(a.new_tree)
    cases = a.cases or sorted(f for f in os.listdir(os.path.join(new, "cases")) if f.endswith(".toml"))
    work = tempfile.mkdtemp(prefix="same_outputs.")
    failed = 0
    for case in cases:
        if case in a.skip:
            print(f"{case}: skipped", flush=True)
            continue
        for sub in subcommands(os.path.join(new, "cases", case)):
            start = time.time()
            outs, codes, errors = [], [], []
            for side, tree in (("old", old), ("new", new)):
                out = os.path.join(work, side, case[:-5], sub)
                code, err = run(tree, sub, case, out)
                outs.append(out)
                codes.append(code)
                errors += err
            if codes[0] != codes[1] or errors:
                failed += 1
                print(f"{case} {sub}: exit {codes[0]} -> {codes[1]} {' '.join(errors)}", flush=True)
                continue
            diffs, added = compare_dirs(*outs, old, new) if os.path.isdir(outs[0]) else ([], [])
            failed += bool(diffs)
            verdict = "identical" if not diffs else f"{len(diffs)} differences"
            per_file = {}
            for x in added:  # "file: column", "file/json/key" or "file" (a new file)
                m = re.match(r"(.*?\.(?:json|csv|vtu))[:/]", x)
                f = m.group(1) if m else x
                per_file[f] = per_file.get(f, 0) + 1
            print(f"{case} {sub}: {verdict} ({time.time() - start:.0f} s)"
                  + (f"; added: {', '.join(f'{f} ({n})' for f, n in sorted(per_file.items()))}" if added else ""),
                  flush=True)
            for d in diffs[:10]:
                print(f"    {d}")
    print(f"{failed} case runs differ; outputs in {work}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
