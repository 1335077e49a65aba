// A square of second-order (6-node) triangles: an element type the FEM reference does not read.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.ElementOrder = 2;
Mesh.MeshSizeMax = 0.25;
Physical Curve("base") = {1};
Physical Curve("load") = {3};
Physical Surface("square") = {1};
