// A 3D bracket: an L-shaped block (a B x B x T base plate with an upright wall of thickness t at
// its back) with a round hole of radius rh through the base plate. Tetrahedra of size lc: the agent
// model takes it voxelized (workbench voxelize). Groups: "base" (the underside, y = 0), "load"
// (the wall's top), "hole" (the hole's wall), "free" (the rest). Units: metres.
SetFactory("OpenCASCADE");
DefineConstant[
  B = {0.06, Name "B"}, T = {0.012, Name "T"}, Hw = {0.06, Name "Hw"}, t = {0.012, Name "t"},
  rh = {0.008, Name "rh"}, lc = {0.003, Name "lc"}
];
Box(1) = {0, 0, 0, B, T, B};                 // base plate: x, y (up), z
Box(2) = {0, 0, 0, t, Hw, B};                // upright wall at x = 0
Cylinder(3) = {B / 2 + t / 2, -0.001, B / 2, 0, T + 0.002, 0, rh};
BooleanUnion(4) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
BooleanDifference(5) = { Volume{4}; Delete; }{ Volume{3}; Delete; };
Mesh.MeshSizeMax = lc;
e = 1e-6;
base() = Surface In BoundingBox{-e, -e, -e, B + e, e, B + e};
top() = Surface In BoundingBox{-e, Hw - e, -e, t + e, Hw + e, B + e};
hole() = Surface In BoundingBox{B / 2 + t / 2 - rh - e, -e, B / 2 - rh - e, B / 2 + t / 2 + rh + e, T + e, B / 2 + rh + e};
all() = Boundary{ Volume{5}; };
Physical Surface("base") = {base()};
Physical Surface("load") = {top()};
Physical Surface("hole") = {hole()};
Physical Surface("free") = {all()};
Physical Surface("free") -= {base(), top(), hole()};
Physical Volume("bracket") = {5};
