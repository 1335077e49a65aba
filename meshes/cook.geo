// Cook's membrane: the tapered panel (0,0), (48,44), (48,60), (0,44), clamped on the left edge and
// sheared on the right edge (the standard plane-stress benchmark: E = 1, nu = 1/3, total shear 1;
// the published 23.96 is the vertical displacement of the right edge's mid-point (48, 52), see
// docs/fem-reference.md). Structured n x n quadrilaterals; n even puts a node at (48, 52).
DefineConstant[
  n = {8, Name "n"}    // elements per edge
];
Point(1) = {0, 0, 0}; Point(2) = {48, 44, 0}; Point(3) = {48, 60, 0}; Point(4) = {0, 44, 0};
Line(1) = {1, 2};   // bottom
Line(2) = {2, 3};   // right (loaded)
Line(3) = {3, 4};   // top
Line(4) = {4, 1};   // left (clamped)
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1};
Recombine Surface{1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Surface("membrane") = {1};
