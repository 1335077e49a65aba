# Sourced by the command-line test scripts (arguments: WORKBENCH_BINARY SOURCE_DIR): the binary and
# the source folder, a scratch folder removed on exit, and check() counting passed and failed checks.
set -u
bin=$(realpath "$1")
src=$2
work=$(mktemp -d)
logs=$(mktemp -d)  # what refused() captures, kept out of $work so that $work can be compared
trap 'rm -rf "$work" "$logs"' EXIT
passed=0
failures=0
check() {  # check NAME CONDITION_EXIT_STATUS MESSAGE
  if [ "$2" -eq 0 ]; then passed=$((passed + 1)); else failures=$((failures + 1)); echo "FAIL $1: $3"; fi
}

# A listing of everything under a folder (names, sizes, times): equal before and after = untouched.
snapshot() { (cd "$1" && find . -printf '%p %s %T@\n' | sort); }

# refused NAME EXPECTED_TEXT FOLDER COMMAND...: COMMAND must exit 2 with exactly one line on stderr
# containing EXPECTED_TEXT, and leave FOLDER exactly as it was.
refused() {
  local name=$1 expected=$2 folder=$3
  shift 3
  local before
  before=$(snapshot "$folder")
  "$@" >"$logs/stdout" 2>"$logs/stderr"
  local rc=$? lines
  lines=$(wc -l <"$logs/stderr")
  if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || ! grep -qF -- "$expected" "$logs/stderr"; then
    check "$name" 1 "exit $rc, $lines stderr lines, expected '$expected', got: $(cat "$logs/stderr")"
  elif [ "$before" != "$(snapshot "$folder")" ]; then
    check "$name" 1 "$folder changed: $(diff <(echo "$before") <(snapshot "$folder") | head -5)"
  else
    check "$name" 0 ""
  fi
}

# A small agent case (the seed plate at 10 mm agents, quick) with the mesh found in SOURCE_DIR.
agent_case() {
  sed -e "s#\.\./meshes#$src/meshes#" -e 's/^h = 0.005/h = 0.01/' -e 's/^lw = 0.01/lw = 0.02/' "$src/cases/gate_plate.toml"
}

# Whether process PID is still running (a zombie, exited but not reaped, is not).
running() { [ -r "/proc/$1/stat" ] && [ "$(cut -d' ' -f3 "/proc/$1/stat")" != Z ]; }

# fake_python: $work/fake/python stands in for python running a figure script and ffmpeg: it starts
# a child, writes both pids into $FAKE_DIR (child.pid, grandchild.pid) and waits. Run the workbench
# with FAKE_DIR="$work/fake" WORKBENCH_PYTHON="$work/fake/python".
fake_python() {
  mkdir -p "$work/fake"
  cat >"$work/fake/python" <<'FAKE'
#!/bin/sh
# Stands in for python running figures/ffmpeg: records its pid and its child's, then waits.
sleep 300 &
echo $! >"$FAKE_DIR/grandchild.tmp" && mv "$FAKE_DIR/grandchild.tmp" "$FAKE_DIR/grandchild.pid"
echo $$ >"$FAKE_DIR/child.tmp" && mv "$FAKE_DIR/child.tmp" "$FAKE_DIR/child.pid"
wait
FAKE
  chmod +x "$work/fake/python"
}

# wait_for FILE: up to 60 s for FILE to appear.
wait_for() { for _ in $(seq 600); do [ -e "$1" ] && return 0; sleep 0.1; done; return 1; }
