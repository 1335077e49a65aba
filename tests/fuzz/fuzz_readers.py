#!/usr/bin/python3
"""A bounded, seeded mutation fuzzer over the case-file and mesh readers.

Takes the shipped cases/*.toml (shrunk to small meshes and few steps, so a run is cheap) and small
MSH 2.2 / 4.1 meshes, mutates them (numbers to nan/inf/huge/negative/zero, keys dropped,
duplicated or retyped, node tags and coordinates corrupted, lines dropped or repeated, the text
cut short) and runs `workbench agent|fem|pbd|compare` on each. Every run must end with exit code
0, 1 or 2 (no signal, no exit 3 = an unexpected exception), within the timeout (no hang), with one
"workbench: error:" line when it fails, an exit 0 must not have written a non-finite number
in a CSV, JSON or text file, and nothing of the workbench's (workbench-*) may be left in the run's
own TMPDIR (the .geo mesher's temporary folder). The runs are the same for the same seed.

Usage: fuzz_readers.py WORKBENCH_BINARY SOURCE_DIR [--runs N] [--first F] [--seed S] [--jobs J] [--long]

--long (outside CI: hours): 10,000 runs unless --runs says otherwise, the 3D cases added (the
3D bracket, the directional block), and a fifth of the runs mutate the .geo file a case reads
(a number, a line dropped or repeated, the text cut short) instead of the case file. Progress every
100 runs on stderr, so that a run stopped early still tells its count. --first F skips runs 0 to
F - 1 (done before: the plan is the same for the same seed whatever --runs).
"""
import argparse
import concurrent.futures
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile

SPECIAL_NUMBERS = ["nan", "inf", "-inf", "1e300", "-1e300", "1e-300", "0", "-1", "-0.0", "9223372036854775807",
                   "-9223372036854775808", "1e9", "2147483648"]
SPECIAL_MSH = ["-105", "2147483648", "0", "nan", "inf", "-inf", "1e300", "-1", "99999999", "1.5", "x"]
RETYPED = ['"x"', "[1, 2]", "true", "{ a = 1 }", "[]", '"nan"']
NUMBER = re.compile(r"(?<![\w.\"])[-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|\.\d+)(?![\w.\"])")
KEY_LINE = re.compile(r"^\s*[\w\"\.]+\s*=")
NON_FINITE = re.compile(r"(?<![A-Za-z_])(?:[-+]?(?:nan|inf|infinity))(?![A-Za-z_])", re.IGNORECASE)

# Shrink the shipped studies so that each run takes a fraction of a second: (pattern, replacement)
# per case file, and the subcommands that read it.
SHRINK = {
    "seed_plate.toml": ([(r"^h = .*", "h = 0.02"), (r"^lw = .*", "lw = 0.04"), (r"^count = .*", "count = 2")], ["agent", "fem"]),
    "seed_plate_conserving.toml": ([(r"^h = .*", "h = 0.02"), (r"^lw = .*", "lw = 0.04"), (r"^count = .*", "count = 2")], ["agent"]),
    "offcentre_plate.toml": ([(r"^h = .*", "h = 0.02"), (r"^lw = .*", "lw = 0.04"), (r"^xc = .*", "xc = 0.06"),
                              (r"^count = .*", "count = 2")], ["agent", "fem"]),
    "gate_plate.toml": ([(r"^h = .*", "h = 0.02"), (r"^lw = .*", "lw = 0.04")], ["agent", "compare"]),
    "block3d.toml": ([(r"^h = .*", "h = 0.01"), (r"^lw = .*", "lw = 0.02"), (r"^count = .*", "count = 2")], ["agent", "fem"]),
    "cook.toml": ([(r"^n = .*", "n = 4")], ["fem"]),
    "pbd_strip.toml": ([(r"N = \d+", "N = 8"), (r"^frames = .*", "frames = 3"), (r"^substeps = .*", "substeps = 4")], ["pbd"]),
    "pbd_sheet.toml": ([(r"n = \d+", "n = 4"), (r"^frames = .*", "frames = 3"), (r"^substeps = .*", "substeps = 4")], ["pbd"]),
    "pbd_strip_fem.toml": ([(r"N = \d+", "N = 8"), (r"^frames = .*", "frames = 3"), (r"^substeps = .*", "substeps = 4"),
                            (r"^nx = .*", "nx = 16")], ["pbd", "compare"]),
}
MSH_FILES = ["tests/fuzz/plate41.msh", "tests/fuzz/plate22.msh"]
# --long adds these (3D, slower): (pattern, replacement) per case file and the subcommands.
LONG_SHRINK = {
    "bracket3d.toml": ([(r"^count = .*", "count = 1")], ["agent", "fem", "compare"]),
    "directional_block.toml": ([(r"^h = .*", "h = 0.008"), (r"^lw = .*", "lw = 0.016")], ["agent", "fem"]),
}
GEO_FILE = re.compile(r'^file = "([^"]+\.geo)"', re.MULTILINE)


def shrunk_cases(src, shrink=SHRINK):
    cases = []
    for name, (rules, commands) in sorted(shrink.items()):
        with open(os.path.join(src, "cases", name)) as f:
            text = f.read()
        text = text.replace('"../', '"' + src + "/")
        for pattern, replacement in rules:
            text = re.sub(pattern, replacement, text, flags=re.MULTILINE)
        cases.append((name, text, commands))
    return cases


def mutate_case(rng, text):
    lines = text.split("\n")
    op = rng.choice(["number", "number", "number", "drop", "duplicate", "retype", "truncate"])
    key_lines = [i for i, l in enumerate(lines) if KEY_LINE.match(l)]
    if op == "number":
        spots = [(i, m) for i, l in enumerate(lines) if not l.lstrip().startswith("#")
                 for m in NUMBER.finditer(l.split("#")[0])]
        if spots:
            i, m = rng.choice(spots)
            lines[i] = lines[i][:m.start()] + rng.choice(SPECIAL_NUMBERS) + lines[i][m.end():]
    elif op == "drop" and key_lines:
        del lines[rng.choice(key_lines)]
    elif op == "duplicate" and key_lines:
        i = rng.choice(key_lines)
        lines.insert(i, lines[i])
    elif op == "retype" and key_lines:
        i = rng.choice(key_lines)
        lines[i] = lines[i].split("=")[0] + "= " + rng.choice(RETYPED)
    elif op == "truncate":
        return op, text[:rng.randrange(len(text) + 1)]
    return op, "\n".join(lines)


def mutate_geo(rng, text):
    """A .geo file mutated: a number, a line dropped or repeated, the text cut short."""
    lines = text.split("\n")
    code = [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith("//")]
    op = rng.choice(["number", "number", "number", "drop", "duplicate", "truncate"])
    if op == "number":
        spots = [(i, m) for i in code for m in NUMBER.finditer(lines[i].split("//")[0])]
        if spots:
            i, m = rng.choice(spots)
            lines[i] = lines[i][:m.start()] + rng.choice(SPECIAL_NUMBERS) + lines[i][m.end():]
    elif op == "drop" and code:
        del lines[rng.choice(code)]
    elif op == "duplicate" and code:
        i = rng.choice(code)
        lines.insert(i, lines[i])
    elif op == "truncate":
        return op, text[:rng.randrange(len(text) + 1)]
    return op, "\n".join(lines)


def mutate_msh(rng, text):
    lines = text.split("\n")
    start = next(i for i, l in enumerate(lines) if l.startswith("$Nodes"))
    body = [i for i in range(start, len(lines)) if lines[i] and not lines[i].startswith("$")]
    op = rng.choice(["token", "token", "token", "drop", "duplicate", "truncate"])
    if op == "token":
        elements = next(i for i, l in enumerate(lines) if l.startswith("$Elements"))
        # Half of them in $Elements, where a bad node tag crashed gmsh.
        i = rng.choice([j for j in body if j > elements] if rng.random() < 0.5 else body)
        tokens = lines[i].split()
        tokens[rng.randrange(len(tokens))] = rng.choice(SPECIAL_MSH)
        lines[i] = " ".join(tokens)
    elif op == "drop":
        del lines[rng.choice(body)]
    elif op == "duplicate":
        i = rng.choice(body)
        lines.insert(i, lines[i])
    else:
        return op, text[:rng.randrange(len(text) + 1)]
    return op, "\n".join(lines)


def non_finite_written(folder):
    for root, _, files in os.walk(folder):
        for name in files:
            if name.endswith((".csv", ".json", ".txt", ".toml")):
                with open(os.path.join(root, name), errors="replace") as f:
                    for line in f:
                        if NON_FINITE.search(line):
                            return os.path.join(root, name) + ": " + line.strip()[:200]
    return None


def run_one(binary, work, index, command, case_text, extra_file, timeout):
    folder = os.path.join(work, "run%04d" % index)
    os.makedirs(folder)
    if extra_file:
        name, text = extra_file
        with open(os.path.join(folder, name), "w") as f:
            f.write(text)
    case = os.path.join(folder, "case.toml")
    with open(case, "w") as f:
        f.write(case_text)
    out = os.path.join(folder, "out")
    # Its own temporary folder, in which nothing of the workbench's may be left (the .geo mesher's).
    tmp = os.path.join(folder, "tmp")
    os.makedirs(tmp)
    # Its own process group, so that a hang is ended with everything it started. A .geo that gmsh
    # does not finish meshing within half the timeout is the workbench's one error (its time limit).
    env = dict(os.environ, TMPDIR=tmp, WORKBENCH_MESH_TIME_LIMIT=str(max(1, timeout // 2)))
    p = subprocess.Popen([binary, command, case, "-o", out], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, errors="replace", start_new_session=True, env=env)
    try:
        _, stderr = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        _, stderr = p.communicate()
        # The last progress line says which step it was in (meshing, "fem: assembled ...", ...).
        last = stderr.strip().splitlines()[-1:] if stderr.strip() else ["no output"]
        return "hang (no exit within %d s) | last line: %s" % (timeout, last[0][:300])
    problem = None
    left = [n for n in os.listdir(tmp) if n.startswith("workbench-")]
    if p.returncode < 0:
        problem = "signal %s" % signal.Signals(-p.returncode).name
    elif p.returncode not in (0, 1, 2):
        problem = "exit %d" % p.returncode
    elif p.returncode == 2 and len([l for l in stderr.splitlines() if l.startswith("workbench: error:")]) != 1:
        problem = "exit 2 without exactly one error line"
    elif left:
        problem = "temporary files left: " + ", ".join(left)
    elif p.returncode == 0:
        bad = non_finite_written(out)
        if bad:
            problem = "exit 0 with a non-finite value written: " + bad
    if problem:
        tail = stderr.strip().splitlines()[-1:] if stderr.strip() else [""]
        return problem + " | " + tail[0][:300]
    shutil.rmtree(folder, ignore_errors=True)
    return None


def make_plan(src, runs, seed, long):
    """The runs: (description, command, case text, extra file); the same for the same seed, whatever runs."""
    rng = random.Random(seed)
    cases = shrunk_cases(src, dict(SHRINK, **LONG_SHRINK) if long else SHRINK)
    meshes = []
    for m in MSH_FILES:
        with open(os.path.join(src, m)) as f:
            meshes.append((os.path.basename(m), f.read()))
    plate = dict((n, t) for n, t, _ in cases)["seed_plate.toml"]
    msh_case_text = re.sub(r"\[mesh\.parameters\][^\[]*", "", plate)

    plan = []
    for index in range(runs):
        geo_cases = [(n, t, c) for n, t, c in cases if GEO_FILE.search(t)]
        if long and index % 5 == 4 and geo_cases:  # --long: a fifth of the runs mutate a case's .geo
            name, text, commands = rng.choice(geo_cases)
            geo_path = GEO_FILE.search(text).group(1)
            with open(geo_path) as f:
                op, mutated = mutate_geo(rng, f.read())
            geo_name = os.path.basename(geo_path)
            case_text = GEO_FILE.sub('file = "%s"' % geo_name, text, count=1)
            command = rng.choice(commands)
            plan.append(("%s %s %s %s" % (command, name, geo_name, op), command, case_text, (geo_name, mutated)))
        elif index % 3 == 2:  # a third of the runs: a corrupted mesh under the agent or FEM reader
            name, text = rng.choice(meshes)
            op, mutated = mutate_msh(rng, text)
            command = rng.choice(["agent", "fem"])
            case_text = re.sub(r'file = ".*"', 'file = "%s"' % name, msh_case_text, count=1)
            plan.append(("%s %s %s" % (command, name, op), command, case_text, (name, mutated)))
        else:
            name, text, commands = rng.choice(cases)
            op, mutated = mutate_case(rng, text)
            if rng.random() < 0.25:  # sometimes two mutations
                op2, mutated = mutate_case(rng, mutated)
                op += "+" + op2
            command = rng.choice(commands)
            plan.append(("%s %s %s" % (command, name, op), command, mutated, None))
    return plan


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("src")
    ap.add_argument("--runs", type=int, default=200)
    ap.add_argument("--first", type=int, default=0, help="skip the runs before this one (done before)")
    ap.add_argument("--seed", type=int, default=20261122)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=int, default=60)
    ap.add_argument("--keep", action="store_true", help="keep the folders of failing runs")
    ap.add_argument("--long", action="store_true", help="10,000 runs, 3D cases and .geo mutations (hours)")
    a = ap.parse_args()
    if a.long and a.runs == 200:
        a.runs = 10000
    plan = make_plan(os.path.abspath(a.src), a.runs, a.seed, a.long)
    todo = range(min(a.first, len(plan)), len(plan))

    work = tempfile.mkdtemp(prefix="workbench-fuzz-")
    findings = []
    try:
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = [(i, pool.submit(run_one, a.binary, work, i, plan[i][1], plan[i][2], plan[i][3], a.timeout))
                       for i in todo]
            for done, (i, fut) in enumerate(futures, 1):
                problem = fut.result()
                if problem:
                    findings.append("run %d (%s): %s" % (i, plan[i][0], problem))
                    if a.long:
                        print("FINDING " + findings[-1], file=sys.stderr, flush=True)
                if a.long and done % 100 == 0:
                    print("fuzz: runs %d to %d done (%d of %d), %d findings" % (todo[0], i, done, len(todo), len(findings)),
                          file=sys.stderr, flush=True)
    finally:
        if not (a.keep and findings):
            shutil.rmtree(work, ignore_errors=True)
    print("fuzz: seed %d, runs %d to %d (%d of them corrupted mesh or .geo files), %d findings" %
          (a.seed, todo.start, todo.stop - 1, sum(1 for i in todo if plan[i][3]), len(findings)))
    for f in findings:
        print("FINDING " + f)
    if a.keep and findings:
        print("fuzz: failing runs kept in " + work)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
