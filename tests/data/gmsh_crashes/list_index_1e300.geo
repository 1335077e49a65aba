// A list index of 1e300 (base[i * 1e300 + k] = s in block3d.geo, run 989)
// Crashed gmsh 4.8 inside the workbench (SIGSEGV in gmsh's .geo parser, assignVariable); tests/cli/gmsh_crashes.sh.
For i In {0:1}
  base[i * 1e300] = i;
EndFor
