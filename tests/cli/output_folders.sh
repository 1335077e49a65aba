#!/usr/bin/env bash
# Output folders never cost a user's files (docs/reliability.md, "Output folders", "Command line"):
# an existing folder the workbench did not write is refused (exit 2, one line, nothing touched);
# its own output is replaced; a staging folder left by a killed run is removed by the next run; an
# unwritable --junit and command-line misuse are refused before anything runs.
# Usage: output_folders.sh WORKBENCH_BINARY SOURCE_DIR
. "$(dirname "$0")/common.sh"

agent_case >"$work/case.toml"

# -o . and -o .. from a folder holding the case file and a user's file: refused, nothing touched.
mkdir -p "$work/project/sub" && cp "$work/case.toml" "$work/project/" && echo precious >"$work/project/sentinel"
cd "$work/project" || exit 1
refused dot "$work/project: is the current folder or holds it" "$work/project" "$bin" agent case.toml -o .
cd "$work/project/sub" || exit 1
refused dotdot "$work/project: is the current folder or holds it" "$work/project" "$bin" agent ../case.toml -o ..
cd "$work" || exit 1
[ "$(cat "$work/project/sentinel")" = precious ] && [ -z "$(ls -a "$work" | grep partial)" ]
check sentinel_survives $? "the sentinel beside the case file changed, or a staging folder was left"

# Any other folder with files in it and no stamp (a home folder, a thesis): refused.
mkdir -p "$work/thesis" && echo "years of work" >"$work/thesis/thesis.tex"
refused user_folder "$work/thesis: is a folder the workbench did not write" "$work" "$bin" agent "$work/case.toml" -o "$work/thesis"
refused file_target "$work/case.toml: exists and is not a folder" "$work" "$bin" agent "$work/case.toml" -o "$work/case.toml"

# An empty folder is used; the workbench's own output (stamped) is replaced whole.
mkdir -p "$work/empty"
"$bin" agent "$work/case.toml" -o "$work/empty" 2>/dev/null && [ -s "$work/empty/agent.pvd" ] &&
  grep -q '^program = "workbench"' "$work/empty/.workbench-output" && grep -qF "case = \"$work/case.toml\"" "$work/empty/.workbench-output"
check empty_folder_used $? "an empty folder was not used, or has no stamp naming the case"
touch "$work/empty/left_from_before"
"$bin" agent "$work/case.toml" -o "$work/empty" 2>/dev/null && [ -s "$work/empty/agent.pvd" ] && [ ! -e "$work/empty/left_from_before" ]
check own_output_replaced $? "the workbench's own output was not replaced whole"
[ -z "$(ls -a "$work" | grep -E '\.(partial|old)-')" ]
check nothing_beside $? "left beside: $(ls -a "$work" | grep -E '\.(partial|old)-')"

# A run killed with SIGKILL leaves its staging folder; the next run to the same target removes it.
fake_python
sed "s#\.\./meshes#$src/meshes#" "$src/cases/pbd_strip.toml" >"$work/pbd.toml"
FAKE_DIR="$work/fake" WORKBENCH_PYTHON="$work/fake/python" "$bin" pbd "$work/pbd.toml" --animate -o "$work/stale" 2>/dev/null &
pid=$!
wait_for "$work/fake/child.pid"
kill -KILL $pid
wait $pid 2>/dev/null
kill "$(cat "$work/fake/child.pid")" "$(cat "$work/fake/grandchild.pid")" 2>/dev/null  # orphaned by the SIGKILL
[ -d "$work/.stale.partial-$pid" ]
check killed_leaves_staging $? "no .stale.partial-$pid after SIGKILL (the test did not test anything)"
"$bin" agent "$work/case.toml" -o "$work/stale" 2>/dev/null && [ ! -e "$work/.stale.partial-$pid" ] && [ -s "$work/stale/agent.pvd" ]
check stale_staging_removed $? "the next run did not remove .stale.partial-$pid"

# --junit that cannot be written: refused before the study runs (no output folder, no FEM solve).
echo x >"$work/a_file"
refused junit_below_file "$work/a_file/junit.xml: --junit: $work/a_file is not a folder" "$work" \
  "$bin" compare "$work/case.toml" -o "$work/junit_out" --junit "$work/a_file/junit.xml"
refused junit_folder "$work/thesis: --junit: is a folder, not a file" "$work" \
  "$bin" compare "$work/case.toml" -o "$work/junit_out" --junit "$work/thesis"

# Command-line misuse exits 2 with one line (CLI11's own codes are 100+); --help exits 0.
refused unknown_option "command line: The following argument was not expected: --bogus" "$work" "$bin" agent "$work/case.toml" --bogus
refused missing_value "command line: --output: 1 required TEXT missing" "$work" "$bin" agent "$work/case.toml" -o
refused missing_case "command line: case is required" "$work" "$bin" agent
refused no_subcommand "command line: A subcommand is required" "$work" "$bin"
refused folder_as_case "$work/project: is a folder, not a case file" "$work" "$bin" agent "$work/project"
"$bin" --help >/dev/null 2>&1 && "$bin" agent --help >/dev/null 2>&1
check help_exit_0 $? "--help did not exit 0"

echo "cli output folders: $passed passed, $failures failed"
[ "$failures" -eq 0 ]
