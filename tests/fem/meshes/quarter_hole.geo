// A quarter of a square plate (side 2 L) with a central hole of radius R, for Kirsch's check:
// the hole's quarter at the origin, symmetry edges "sym_x" (x = 0) and "sym_y" (y = 0), the far
// edge "pull" (x = L), the top "free" (y = L). Triangles (P2 in the test), graded from lc_hole at the rim to lc.
DefineConstant[ L = {0.2, Name "L"}, R = {0.01, Name "R"}, lc = {0.01, Name "lc"}, lc_hole = {0.0005, Name "lc_hole"} ];
Point(1) = {0, 0, 0, lc_hole}; Point(2) = {R, 0, 0, lc_hole}; Point(3) = {L, 0, 0, lc};
Point(4) = {L, L, 0, lc}; Point(5) = {0, L, 0, lc}; Point(6) = {0, R, 0, lc_hole};
Line(1) = {2, 3}; Line(2) = {3, 4}; Line(3) = {4, 5}; Line(4) = {5, 6}; Circle(5) = {6, 1, 2};
Curve Loop(1) = {1, 2, 3, 4, 5}; Plane Surface(1) = {1};
Physical Curve("sym_y") = {1}; Physical Curve("pull") = {2}; Physical Curve("free") = {3};
Physical Curve("sym_x") = {4}; Physical Curve("hole") = {5}; Physical Surface("plate") = {1};
