#!/usr/bin/env bash
# When the disk says no: a write failure at every file the workbench (and its scripts, and ffmpeg)
# writes, and file-size limits, under every subcommand. Each failed run: exit 2, exactly one line
# naming the file and the reason, no `.NAME.partial-PID` left, the earlier output byte for byte
# unchanged, no signal (docs/reliability.md, "When the disk says no").
#
# Usage: write_failures.sh WORKBENCH SOURCE_DIR FAIL_WRITE_SHIM [inject|ulimit|tmpfs]
#   inject: tests/support/fail_write.c preloaded; a counting run traces every write and fsync
#           below the output folder (and is the earlier output), then one run fails the first call
#           on each kind of file (below).
#   ulimit: `ulimit -f` at several sizes (a batch system's file-size limit): exit 2 naming the file
#           with "File too large", or exit 0 with the whole output when everything fits.
#   tmpfs:  a small tmpfs that fills up (root only; skipped otherwise).
source "$(dirname "$0")/common.sh"
shim=$(realpath "$3")
mode=${4:-inject}

# Small, quick studies, one per subcommand.
agent_case >"$work/plate.toml"
cat "$work/plate.toml" - >"$work/plate_steps.toml" <<<$'[steps]\ncount = 20'
sed -e 's/^figures = false/figures = true/' -e '/^\[compare.gate\]/,$d' "$work/plate.toml" >"$work/plate_figures.toml"
cat >"$work/calibrate.toml" <<EOF
[calibrate]
rule_set = "conserving"
starts = 1
seed = 1
max_evaluations = 3
[[calibrate.case]]
file = "plate.toml"
EOF
sed -e "s#\.\./meshes#$src/meshes#" -e 's/N = [0-9]*/N = 8/' -e 's/^frames = .*/frames = 3/' \
    -e 's/^substeps = .*/substeps = 4/' "$src/cases/pbd_strip.toml" >"$work/strip.toml"

# name | arguments (the output folder follows)
runs=(
  "agent|agent $work/plate.toml"
  "fem|fem $work/plate.toml"
  "compare|compare $work/plate_figures.toml"
  "calibrate|calibrate $work/calibrate.toml"
  "pbd|pbd $work/strip.toml --animate"
)

out="$work/out"
mkdir -p "$out"
digest() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum); }

# judge NAME TARGET RC EXPECTED_TEXT BEFORE: a failed run's promises. (Progress lines may come
# before the one error line; nothing else may: no second error, no traceback.)
judge() {
  local name=$1 target=$2 rc=$3 expected=$4 before=$5 errors
  errors=$(grep -c "^workbench: error\|Traceback\|^workbench: warning" "$logs/stderr")
  if [ "$rc" -ge 128 ]; then check "$name" 1 "killed by signal $((rc - 128))"; return; fi
  if [ "$rc" -ne 2 ] || [ "$errors" -ne 1 ] || ! tail -1 "$logs/stderr" | grep -q "^workbench: error: .*$expected"; then
    check "$name" 1 "exit $rc, $errors error lines, expected '$expected': $(grep -v '^[a-z]*: ' "$logs/stderr" | head -3) $(tail -1 "$logs/stderr")"
    return
  fi
  if ls -a "$out" | grep -q '\.partial-\|\.old-'; then check "$name" 1 "left $(ls -a "$out" | grep partial)"; return; fi
  [ "$(digest "$target")" == "$before" ]
  check "$name" $? "the earlier output changed"
}

# The kind of a traced path: below the output folder, digits collapsed, the staging folder's name
# as its target's.
kind_of() { sed -e "s#^$out/##" -e 's#^\.\([^/]*\)\.partial-[0-9]*#\1#' -e 's/[0-9]\+/#/g'; }

inject() {
  local name=$1 args=$2 target="$out/$1"
  local counter="$logs/counter" trace="$logs/trace"
  rm -f "$trace"
  truncate -s 0 "$counter" && truncate -s 4096 "$counter"
  # shellcheck disable=SC2086
  FAIL_WRITE_UNDER="$out" FAIL_WRITE_COUNTER="$counter" FAIL_WRITE_TRACE="$trace" LD_PRELOAD="$shim" \
    "$bin" $args -o "$target" >"$logs/stdout" 2>"$logs/stderr"
  # The counting run: it succeeds (nothing fails) and is the earlier output the others must keep.
  check "${name}_count" $? "$(cat "$logs/stderr")"
  local total kinds=0
  total=$(wc -l <"$trace")
  # The first call on each kind of file: a write into each file type (by extension) and a sync of
  # a file, of a folder and of the parent folder, each once over all subcommands;
  # WRITE_FAILURES_ALL=1: every file and folder of every subcommand (numbered series as one).
  local picks
  picks=$(while read -r n op path; do
            local k
            k=$(echo "$path" | kind_of)
            if [ -z "${WRITE_FAILURES_ALL:-}" ]; then
              local base=${k##*/}
              if [ "$path" == "$out" ]; then k="$op parent"
              elif [ "$op" == fsync ]; then
                case "$base" in *.*) k="fsync file" ;; *) k="fsync folder" ;; esac
              else k="$op ${base##*.}"; fi
              grep -qxF "$k" "$logs/seen" 2>/dev/null && continue
              echo "$k" >>"$logs/seen"
            else
              k="$name $op $k"
              grep -qxF "$k" "$logs/seen" 2>/dev/null && continue
              echo "$k" >>"$logs/seen"
            fi
            echo "$n"
          done <"$trace")
  for n in $picks; do
    [ -n "${ONLY_N:-}" ] && [ "$n" != "$ONLY_N" ] && continue
    kinds=$((kinds + 1))
    local before
    before=$(digest "$target")
    truncate -s 0 "$counter" && truncate -s 4096 "$counter"
    # shellcheck disable=SC2086
    FAIL_WRITE_UNDER="$out" FAIL_WRITE_COUNTER="$counter" FAIL_WRITE_AT="$n" LD_PRELOAD="$shim" \
      "$bin" $args -o "$target" >"$logs/stdout" 2>"$logs/stderr"
    local rc=$? failed
    failed=$(tail -c +65 "$counter" | tr -d '\0')
    if [ "$failed" == "$out" ]; then
      # The parent folder's sync after the rename: the new output is in place; a warning says so.
      [ "$rc" -eq 0 ] && grep -q "^workbench: warning: .*cannot\|^workbench: warning: .*write failed" "$logs/stderr"
      check "${name}_at_${n}_parent_sync" $? "exit $rc: $(head -3 "$logs/stderr")"
      continue
    fi
    local shown
    shown=$(basename "$(echo "$failed" | kind_of | sed 's/#/[0-9]*/g')")
    judge "${name}_at_${n}($(echo "$failed" | kind_of))" "$target" "$rc" "${shown}.*: write failed (No space left on device)\|${shown}: write failed (No space left on device)" "$before"
  done
  echo "$name: $total writes and syncs, $kinds kinds of file injected"
}

limits() {
  local name=$1 args=$2 target="$out/$1"
  local blocks
  # 100000 blocks first: the whole output fits, and is the earlier output the others must keep.
  for blocks in 100000 1 16 200; do
    local before="" rc
    [ -d "$target" ] && before=$(digest "$target")
    # shellcheck disable=SC2086
    (ulimit -f "$blocks" && exec "$bin" $args -o "$target" >"$logs/stdout" 2>"$logs/stderr")
    rc=$?
    if [ "$rc" -eq 0 ]; then
      carries_stamp=$([ -f "$target/.workbench-output" ] && ! ls -a "$out" | grep -q partial && echo 0 || echo 1)
      [ "$blocks" -gt 1 ] || carries_stamp=1  # every subcommand writes a file over 1 KB
      check "${name}_ulimit_${blocks}_fits" "$carries_stamp" "exit 0 without a whole output, or under a 1 KB limit"
    else
      judge "${name}_ulimit_${blocks}" "$target" "$rc" "write failed (File too large)" "$before"
    fi
  done
}

# Space up front: a VTU series that would not fit is refused before its first file, with the estimate.
room() {
  local target="$out/agent" before
  "$bin" agent "$work/plate.toml" -o "$target" >"$logs/stdout" 2>"$logs/stderr"
  check room_first $? "$(cat "$logs/stderr")"
  before=$(digest "$target")
  WORKBENCH_FREE_BYTES=100000 "$bin" agent "$work/plate_steps.toml" -o "$target" >"$logs/stdout" 2>"$logs/stderr"
  judge room_agent_series "$target" $? "the series of 20 VTU files (.*) needs an estimated .* MB, the file system has 0.1 MB free" "$before"
  ls "$out" | grep -q . && ! ls -a "$out" | grep -q partial
  check room_nothing_written $? "$(ls -a "$out")"
}

case "$mode" in
  inject)
    for entry in "${runs[@]}"; do
      [ -n "${ONLY:-}" ] && [ "${entry%%|*}" != "$ONLY" ] && continue
      inject "${entry%%|*}" "${entry#*|}"
    done ;;
  ulimit)
    room
    for entry in "${runs[@]}"; do
      [ -n "${ONLY:-}" ] && [ "${entry%%|*}" != "$ONLY" ] && continue
      limits "${entry%%|*}" "${entry#*|}"
    done ;;
  tmpfs)
    if [ "$(id -u)" -ne 0 ]; then echo "tmpfs: skipped (not root)"; exit 0; fi
    mkdir -p "$work/small"
    if ! mount -t tmpfs -o size=1m tmpfs "$work/small" 2>/dev/null; then echo "tmpfs: skipped (mount failed)"; exit 0; fi
    trap 'umount "$work/small"; rm -rf "$work" "$logs"' EXIT
    # An earlier output that fits, then the larger study that does not (the agent at 20 steps).
    out="$work/small"
    "$bin" agent "$work/plate.toml" -o "$out/agent" >"$logs/stdout" 2>"$logs/stderr"
    check tmpfs_first $? "$(cat "$logs/stderr")"
    before=$(digest "$out/agent")
    head -c 600000 /dev/zero >"$out/filler"  # leaves less room than the studies need
    refused=0
    # The agent's 20 load steps: refused up front by the real statvfs.
    for entry in "${runs[@]}" "agent20|agent $work/plate_steps.toml"; do
      name=${entry%%|*}
      [ "$name" == calibrate ] && continue
      [ -d "$out/agent" ] && before=$(digest "$out/agent")
      # shellcheck disable=SC2086
      "$bin" ${entry#*|} -o "$out/agent" >"$logs/stdout" 2>"$logs/stderr"
      rc=$?
      echo "tmpfs: $name: exit $rc: $(tail -1 "$logs/stderr")"
      if [ "$rc" -eq 0 ]; then check "tmpfs_$name" 0 ""; continue; fi
      refused=$((refused + 1))
      judge "tmpfs_$name" "$out/agent" "$rc" "No space left on device\|needs an estimated" "$before"
    done
    [ "$refused" -gt 0 ]
    check tmpfs_some_run_did_not_fit $? "every study fitted in the small tmpfs: the test proves nothing" ;;
esac
echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
