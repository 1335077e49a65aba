// A plate with a circular hole in tension (Kirsch): W x H, a hole of radius R at its centre,
// triangles of size lc (finer, lc_hole, on the rim). Not built of squares: the agent model takes
// it voxelized (agent::voxelize, docs/agent-model.md), FEM takes it as it is. Units: metres.
DefineConstant[
  W  = {0.2,   Name "W"},       // width [m]
  H  = {0.1,   Name "H"},       // height [m]
  R  = {0.01,  Name "R"},       // hole radius [m]
  lc = {0.005, Name "lc"},      // element size away from the hole [m]
  lc_hole = {0.001, Name "lc_hole"}  // element size on the rim [m]
];
If (R <= 0 || 2 * R >= H || 2 * R >= W)
  Error("plate_hole.geo: the hole must fit inside the plate");
EndIf
Point(1) = {0, 0, 0, lc}; Point(2) = {W, 0, 0, lc}; Point(3) = {W, H, 0, lc}; Point(4) = {0, H, 0, lc};
Point(5) = {W / 2, H / 2, 0, lc_hole};
Point(6) = {W / 2 + R, H / 2, 0, lc_hole}; Point(7) = {W / 2, H / 2 + R, 0, lc_hole};
Point(8) = {W / 2 - R, H / 2, 0, lc_hole}; Point(9) = {W / 2, H / 2 - R, 0, lc_hole};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Physical Curve("fixed") = {4};
Physical Curve("pull") = {2};
Physical Curve("free") = {1, 3};
Physical Curve("hole") = {5:8};
Physical Surface("plate") = {1};
