#!/usr/bin/env bash
# The hole cases of docs/agent-model.md ("Every shipped 2D plate case", the hole's shear on cases it
# was not built on): plate_hole at 5 mm agents, with R = 20 mm, with the hole at y = 35 mm, and the seed
# plate (5 mm agents) with a hole of 20 mm radius, centred and off centre. Writes the geometries, the
# staircases, the case files and the comparisons into OUT (nothing into the repository).
#   bench/research/hole_cases.sh OUT [WORKBENCH]    # then: compare_table.py OUT/out_*
set -euo pipefail
out=$1
repo=$(cd "$(dirname "$0")/../.." && pwd)
wb=$(realpath "${2:-$repo/build/cli/workbench}")
mkdir -p "$out" && cd "$out"
cp "$repo/meshes/plate_hole.geo" ph_R10.geo
sed 's/R  = {0.01, /R  = {0.02, /' ph_R10.geo > ph_R20.geo
sed 's|{W / 2, H / 2, 0|{W / 2, 0.035, 0|; s|{W / 2 + R, H / 2, 0|{W / 2 + R, 0.035, 0|; s|{W / 2, H / 2 + R, 0|{W / 2, 0.035 + R, 0|;
     s|{W / 2 - R, H / 2, 0|{W / 2 - R, 0.035, 0|; s|{W / 2, H / 2 - R, 0|{W / 2, 0.035 - R, 0|' ph_R10.geo > ph_low.geo
cat > seed_hole.geo <<'GEO'
// The seed plate (200 x 200 mm) with a circular hole of radius R at (xh, yh), loaded on a patch of
// the top edge centred at xc; rigid base.
DefineConstant[ W = {0.2, Name "W"}, H = {0.2, Name "H"}, R = {0.02, Name "R"}, xh = {0.1, Name "xh"},
  yh = {0.1, Name "yh"}, lw = {0.01, Name "lw"}, xc = {0.1, Name "xc"}, lc = {0.005, Name "lc"}, lh = {0.001, Name "lh"} ];
Point(1) = {0, 0, 0, lc}; Point(2) = {W, 0, 0, lc}; Point(3) = {W, H, 0, lc};
Point(4) = {xc + lw / 2, H, 0, lh}; Point(5) = {xc - lw / 2, H, 0, lh}; Point(6) = {0, H, 0, lc};
Point(7) = {xh, yh, 0, lh}; Point(8) = {xh + R, yh, 0, lh}; Point(9) = {xh, yh + R, 0, lh};
Point(10) = {xh - R, yh, 0, lh}; Point(11) = {xh, yh - R, 0, lh};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Circle(7) = {8, 7, 9}; Circle(8) = {9, 7, 10}; Circle(9) = {10, 7, 11}; Circle(10) = {11, 7, 8};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Curve Loop(2) = {7, 8, 9, 10};
Plane Surface(1) = {1, 2};
Physical Curve("base") = {1}; Physical Curve("load") = {4}; Physical Curve("free") = {2, 3, 5, 6};
Physical Curve("hole") = {7:10}; Physical Surface("plate") = {1};
GEO
sed 's/xh = {0.1,/xh = {0.07,/; s/yh = {0.1,/yh = {0.08,/; s/xc = {0.1,/xc = {0.05,/' seed_hole.geo > seed_hole_off.geo
for v in "ph5 ph_R10 0.005" "ph_R20 ph_R20 0.0025" "ph_low ph_low 0.0025" "seed_hole seed_hole 0.005" "seed_hole_off seed_hole_off 0.005"; do
  set -- $v
  [ -e "$1.msh" ] || "$wb" voxelize "$2.geo" -s "$3" -o "$1.msh" >/dev/null
done
for c in ph5:ph_R10 ph_R20:ph_R20 ph_low:ph_low; do
  name=${c%%:*} geo=${c##*:}
  sed "s|file = \"../meshes/plate_hole_staircase.msh\"|file = \"$name.msh\"|; s|mesh = \"../meshes/plate_hole.geo\"|mesh = \"$geo.geo\"|;
       s|rule_set = \"conserving\"|rule_set = \"directional\"|; s|count = 2|count = 1|" "$repo/cases/plate_hole.toml" > "$name.toml"
done
for name in seed_hole seed_hole_off; do
  sed "s|file = \"../meshes/plate2d.geo\"|file = \"$name.msh\"|; s|count = 20 .*|count = 1|" "$repo/cases/seed_plate_directional.toml" |
    sed '/^\[mesh.parameters\]/,/^$/d' > "$name.toml"
  printf '\n[compare.reference]\nmesh = "%s.geo"\n' "$name" >> "$name.toml"
done
for name in ph5 ph_R20 ph_low seed_hole seed_hole_off; do
  nice -n 19 "$wb" compare "$name.toml" -o "out_$name" > "$name.log" 2>&1
done
