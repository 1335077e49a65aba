// Two discs of radius 1 (triangles of size 0.05) 1000 apart along x: voxelized, their agents
// form a compressed lattice (each disc's columns and one air column for the gap between them).
lc = 0.05;
For d In {0:1}
  x = 1000 * d;
  p = 5 * d;
  Point(p + 1) = {x, 0, 0, lc}; Point(p + 2) = {x + 1, 0, 0, lc}; Point(p + 3) = {x, 1, 0, lc};
  Point(p + 4) = {x - 1, 0, 0, lc}; Point(p + 5) = {x, -1, 0, lc};
  Circle(4 * d + 1) = {p + 2, p + 1, p + 3}; Circle(4 * d + 2) = {p + 3, p + 1, p + 4};
  Circle(4 * d + 3) = {p + 4, p + 1, p + 5}; Circle(4 * d + 4) = {p + 5, p + 1, p + 2};
  Curve Loop(d + 1) = {4 * d + 1, 4 * d + 2, 4 * d + 3, 4 * d + 4}; Plane Surface(d + 1) = {d + 1};
EndFor
Physical Curve("rim") = {1:8}; Physical Surface("discs") = {1, 2};
