// A cantilever: a W x H beam clamped on its left end (group "clamp"), loaded on a patch of width lw
// at the right end of its top edge (group "load"), every other face free. Units: metres.
// Structured squares of size h (the agent size); W, H and lw must be multiples of h.
DefineConstant[
  W  = {0.2,   Name "W"},    // length [m]
  H  = {0.04,  Name "H"},    // depth [m]
  h  = {0.005, Name "h"},    // agent (cell) size [m]
  lw = {0.005, Name "lw"}    // loaded patch at the free end [m]
];
nx = Round(W / h); ny = Round(H / h); nl = Round(lw / h);
If (Fabs(nx * h - W) > 1e-9 * W || Fabs(ny * h - H) > 1e-9 * H || Fabs(nl * h - lw) > 1e-9 * W || nl < 1 || nl >= nx)
  Error("cantilever2d.geo: W, H and lw must be multiples of h, the patch shorter than the beam");
EndIf
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0};
Point(4) = {W - nl * h, H, 0}; Point(5) = {0, H, 0};
Line(1) = {1, 2};            // underside
Line(2) = {2, 3};            // free end
Line(3) = {3, 4};            // loaded patch
Line(4) = {4, 5};            // top
Line(5) = {5, 1};            // clamped end
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Transfinite Curve{1} = nx + 1; Transfinite Curve{2, 5} = ny + 1;
Transfinite Curve{3} = nl + 1; Transfinite Curve{4} = nx - nl + 1;
Transfinite Surface{1} = {1, 2, 3, 5};
Recombine Surface{1};
Physical Curve("clamp") = {5};
Physical Curve("load") = {3};
Physical Curve("free") = {1, 2, 4};
Physical Surface("beam") = {1};
