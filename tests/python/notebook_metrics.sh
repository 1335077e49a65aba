#!/usr/bin/env bash
# notebooks/seed_plate_metrics.ipynb reproduces the seed plate's summary metrics: the command line
# runs the comparison (figures off), the notebook runs it through the Python module and requires
# every metric but the timings to be equal. Usage: notebook_metrics.sh WORKBENCH_BINARY SOURCE_DIR
# (PYTHONPATH names the module's folder).
. "$(dirname "$0")/../cli/common.sh"
sed -e "s#\.\./meshes#$src/meshes#" "$src/cases/seed_plate.toml" >"$work/seed_plate.toml"
echo "figures = false" >>"$work/seed_plate.toml"  # the last table of the case is [compare]
"$bin" compare "$work/seed_plate.toml" -o "$work/cli" 2>"$work/log"
check cli $? "$(tail -2 "$work/log")"
WORKBENCH_ROOT=$src WORKBENCH_CASE=$work/seed_plate.toml WORKBENCH_COMPARE_DIR=$work/cli PYDEVD_DISABLE_FILE_VALIDATION=1 \
  jupyter nbconvert --to notebook --execute --output-dir "$work/nb" "$src/notebooks/seed_plate_metrics.ipynb" 2>"$work/nb.log"
check notebook $? "$(tail -5 "$work/nb.log")"
grep -q "metrics equal to" "$work/nb/seed_plate_metrics.ipynb"
check equal $? "the notebook did not compare with the command line's summary.json"
echo "$passed checks passed, $failures failed"
[ "$failures" -eq 0 ]
