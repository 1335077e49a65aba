// A structured square whose spacing is graded: agents of unequal size must be refused.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {1, 4};
Curve Loop(1) = {1, 2, -3, -4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 6 Using Progression 1.3; Transfinite Curve{2, 4} = 6;
Transfinite Surface{1}; Recombine Surface{1};
Physical Curve("base") = {1}; Physical Curve("load") = {3}; Physical Surface("body") = {1};
