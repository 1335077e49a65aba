// A thin ring (mean radius R, wall t) squeezed across a diameter: a patch of the outer rim at the
// top (80 to 100 degrees) takes the load, the same patch at the bottom rests on a rigid base.
// Not built of squares: the agent model takes it voxelized (agent::voxelize); its staircase is a
// connected but sparse body (every lattice row and column holds agents, most of the box is air),
// which the agent grid holds on tiles (docs/agent-model.md, "Memory"). Units: metres.
DefineConstant[
  R  = {0.1,    Name "R"},    // mean radius [m]
  t  = {0.002,  Name "t"},    // wall thickness [m]
  lc = {0.0005, Name "lc"}    // triangle size [m]
];
If (t <= 0 || t >= R)
  Error("ring.geo: the wall must be thinner than the radius");
EndIf
ro = R + t / 2; ri = R - t / 2;
Point(1) = {0, 0, 0, lc};
// The outer rim, cut at the patches' ends (each arc below 180 degrees, as Circle needs).
angles[] = {0, 80, 100, 180, 260, 280};
For i In {0:5}
  Point(10 + i) = {ro * Cos(angles[i] * Pi / 180), ro * Sin(angles[i] * Pi / 180), 0, lc};
EndFor
For i In {0:5}
  Circle(10 + i) = {10 + i, 1, 10 + (i + 1) % 6};
EndFor
// The inner rim in three arcs.
For i In {0:2}
  Point(20 + i) = {ri * Cos(i * 2 * Pi / 3), ri * Sin(i * 2 * Pi / 3), 0, lc};
EndFor
For i In {0:2}
  Circle(20 + i) = {20 + i, 1, 20 + (i + 1) % 3};
EndFor
Curve Loop(1) = {10:15};
Curve Loop(2) = {20:22};
Plane Surface(1) = {1, 2};
Physical Curve("load") = {11};
Physical Curve("base") = {14};
Physical Curve("free") = {10, 12, 13, 15, 20:22};
Physical Surface("ring") = {1};
