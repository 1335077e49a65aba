// A disc of radius R (triangles of size lc), its rim in the group "rim": voxelized in the tests.
DefineConstant[ R = {1.0, Name "R"}, lc = {0.02, Name "lc"} ];
Point(1) = {0, 0, 0, lc}; Point(2) = {R, 0, 0, lc}; Point(3) = {0, R, 0, lc}; Point(4) = {-R, 0, 0, lc}; Point(5) = {0, -R, 0, lc};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Curve("rim") = {1:4}; Physical Surface("disc") = {1};
