#!/usr/bin/env bash
# Drawing the figures shows progress on a terminal and nothing when stderr is not one:
# the same comparison run under a pseudo-terminal (`script`, util-linux) and with stderr to a file.
# Usage: progress.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"
sed -e "s#\.\./meshes#$src/meshes#" -e '/^figures *=/d' "$src/cases/gate_plate.toml" >"$work/case.toml"

script -qec "'$bin' compare '$work/case.toml' -o '$work/tty'" "$work/terminal.txt" >/dev/null
check terminal_run $? "compare under a pseudo-terminal failed: $(tail -3 "$work/terminal.txt")"
shown=$(grep -c "figures: fig8_ratio drawn" "$work/terminal.txt")
check progress_on_terminal $(( shown == 1 ? 0 : 1 )) "expected one 'fig8_ratio drawn' line on the terminal, got $shown"

"$bin" compare "$work/case.toml" -o "$work/file" 2>"$work/stderr.txt"
check file_run $? "compare with stderr to a file failed: $(tail -3 "$work/stderr.txt")"
quiet=$(grep -c " drawn" "$work/stderr.txt")
check quiet_otherwise $(( quiet == 0 ? 0 : 1 )) "progress lines written to a non-terminal stderr: $quiet"

# The agent model runs beside the FEM reference, on its own thread: the two write whole lines
# (workbench::LineLog), each line one model's, every one there.
steps=$(grep -c "agent: step" "$work/stderr.txt")
whole=$(grep -cE "^agent: step 1/1: load \(0, -2\) N \(2 N applied in all\), 1600 agents, .*, lost [-0-9.e+]+ N$" "$work/stderr.txt")
fem=$(grep -c "fem:" "$work/stderr.txt")
fem_whole=$(grep -cE "^fem: (mesh|[0-9]+ DoFs|assembled|solved|the coarse|applied)" "$work/stderr.txt")
check whole_lines $(( steps == 1 && whole == 1 && fem == fem_whole && fem >= 5 ? 0 : 1 )) \
  "agent step lines $steps (whole $whole), fem lines $fem (whole $fem_whole): $(grep -E "agent:|fem:" "$work/stderr.txt")"

echo "$passed checks passed, $failures failed"
[ "$failures" -eq 0 ]
