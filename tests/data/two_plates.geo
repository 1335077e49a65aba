// Two structured plates of 10 x 5 agents (h = 1 mm) 1 m apart along x: the compressed lattice
// keeps the 20 occupied columns and one air column for the gap (21 x 5 slots, not 1020 x 5).
h = 0.001;
gap = 1.0;
Point(1) = {0, 0, 0}; Point(2) = {10 * h, 0, 0}; Point(3) = {10 * h, 5 * h, 0}; Point(4) = {0, 5 * h, 0};
Point(5) = {10 * h + gap, 0, 0}; Point(6) = {20 * h + gap, 0, 0}; Point(7) = {20 * h + gap, 5 * h, 0}; Point(8) = {10 * h + gap, 5 * h, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = 11; Transfinite Curve{2, 4, 6, 8} = 6;
Transfinite Surface{1:2}; Recombine Surface{1:2};
Physical Curve("base") = {1, 5}; Physical Curve("top_a") = {3}; Physical Curve("top_b") = {7};
Physical Surface("body") = {1, 2};
