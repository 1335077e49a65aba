// Three structured unit squares in an L: the fourth slot of the bounding box is empty.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {2, 0, 0}; Point(4) = {0, 1, 0};
Point(5) = {1, 1, 0}; Point(6) = {2, 1, 0}; Point(7) = {0, 2, 0}; Point(8) = {1, 2, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 5}; Line(4) = {5, 6}; Line(5) = {7, 8};
Line(6) = {1, 4}; Line(7) = {2, 5}; Line(8) = {3, 6}; Line(9) = {4, 7}; Line(10) = {5, 8};
Curve Loop(1) = {1, 7, -3, -6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 8, -4, -7}; Plane Surface(2) = {2};
Curve Loop(3) = {3, 10, -5, -9}; Plane Surface(3) = {3};
Transfinite Curve{1:10} = 3; Transfinite Surface{1:3}; Recombine Surface{1:3};
Physical Curve("base") = {1, 2}; Physical Curve("load") = {5}; Physical Surface("body") = {1:3};
