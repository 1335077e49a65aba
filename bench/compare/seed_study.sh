#!/usr/bin/env bash
# The seed study's wall time, figures included, against the same work
# done one step after the other in the same run: the comparison without figures, then figures.py on
# its output (how the study ran before the figures were drawn beside the FEM reference). Prints the
# median of RUNS runs of each, the ratio, and the same with PDF files too (figure_formats).
#
#   bash bench/compare/seed_study.sh build 5
#   taskset -c 1 bash bench/compare/seed_study.sh build 5    # one core: no overlap possible
set -eu
build=$(realpath "${1:-build}")
runs=${2:-5}
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bin="$build/cli/workbench"
figures="$build/share/workbench/compare/figures.py"

sed "s#\.\./meshes#$src/meshes#" "$src/cases/seed_plate.toml" >"$work/png.toml"
cp "$work/png.toml" "$work/pdf.toml"
printf 'figure_formats = ["png", "pdf"]\n' >>"$work/pdf.toml"      # the [compare] table is the last
sed 's/^mask = .*/&\nfigures = false/' "$work/png.toml" >"$work/nofig.toml"

now() { date +%s.%N; }
median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
title=$(sed -n 's/^title = "\(.*\)"/\1/p' "$work/png.toml")

for formats in png pdf; do
  : >"$work/together" && : >"$work/apart"
  for r in $(seq "$runs"); do
    rm -rf "$work/out"
    t=$(now)
    "$bin" compare "$work/$formats.toml" -o "$work/out" >/dev/null 2>&1
    awk -v a="$(now)" -v b="$t" 'BEGIN {print a - b}' >>"$work/together"
    list=png && [ "$formats" = pdf ] && list=png,pdf
    rm -rf "$work/out"
    t=$(now)
    "$bin" compare "$work/nofig.toml" -o "$work/out" >/dev/null 2>&1
    /usr/bin/python3 "$figures" "$work/out" --title "$title" --formats "$list" >/dev/null
    awk -v a="$(now)" -v b="$t" 'BEGIN {print a - b}' >>"$work/apart"
  done
  together=$(median <"$work/together")
  apart=$(median <"$work/apart")
  awk -v l="$list" -v t="$together" -v a="$apart" -v n="$runs" 'BEGIN {
    printf "seed study, %s: figures beside the FEM %.2f s, one step after the other %.2f s, ratio %.2f (medians of %d)\n", l, t, a, t / a, n}'
done
