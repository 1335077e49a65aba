// A square plate of linear triangles (unstructured): serial runs read it with P1/P2 simplices; a
// distributed run must refuse it. Groups as in meshes/plate2d.geo.
DefineConstant[ s = {0.1, Name "s"} ];   // element size
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0};
Point(4) = {0.6, 1, 0}; Point(5) = {0.4, 1, 0}; Point(6) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Mesh.MeshSizeMax = s;
Physical Curve("base") = {1};
Physical Curve("load") = {4};
Physical Curve("free") = {2, 3, 5, 6};
Physical Surface("plate") = {1};
