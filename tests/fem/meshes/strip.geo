// A slender strip L x D (centred on y = 0) of structured quadrilaterals: the cantilever of the
// Timoshenko-Goodier test, read through gmsh. Groups: root (x = 0), tip (x = L), top, bottom.
DefineConstant[
  L = {10, Name "L"}, D = {1, Name "D"},
  nx = {40, Name "nx"}, ny = {4, Name "ny"},
  skew = {0, Name "skew"}   // moves the interior of the mesh (x offset of the mid-line points)
];
Point(1) = {0, -D/2, 0}; Point(2) = {L, -D/2, 0}; Point(3) = {L, D/2, 0}; Point(4) = {0, D/2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1; Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("tip") = {2};
Physical Curve("top") = {3};
Physical Curve("root") = {4};
Physical Surface("strip") = {1};
