// A W x H rectangular sheet (cloth) in the x-y plane, triangulated (structured), for the PBD angle
// bending model in 3D: gravity along -z makes it sag and fold out of its plane. The two corners
// of the edge y = H form the physical group "corners" (pin them to hang the sheet), the whole
// edge y = H the group "top".
DefineConstant[
  W = {1.0, Name "W"},   // width [m]
  H = {1.0, Name "H"},   // height [m]
  n = {20,  Name "n"}    // divisions per side
];
k = Round(n);
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = k + 1;
Transfinite Surface{1};
Physical Point("corners") = {3, 4};
Physical Curve("top") = {3};
Physical Surface("sheet") = {1};
