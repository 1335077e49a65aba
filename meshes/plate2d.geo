// The seed's Fig. 7 plate (WO2001052193): a W x H plate resting on a rigid base,
// loaded from above on a patch of the top edge (centred unless xc says otherwise). Units: metres.
// Structured squares of size h (the agent size); the plate size, the patch width lw and the
// patch's ends must be multiples of h so that every agent is a square.
// Parameters can be overridden from a case file ([mesh.parameters]).
DefineConstant[
  W  = {0.2,   Name "W"},    // width [m]
  H  = {0.2,   Name "H"},    // height [m]
  h  = {0.002, Name "h"},    // agent (cell) size [m]
  lw = {0.004, Name "lw"},   // width of the loaded patch on the top edge [m]
  xc = {-1,    Name "xc"}    // centre of the patch [m]; -1: the middle of the top edge
];
If (xc < 0)
  xc = W / 2;
EndIf
nx = Round(W / h); ny = Round(H / h); nl = Round(lw / h);
nleft = Round((xc - lw / 2) / h); nright = nx - nleft - nl;
If (Fabs(nx * h - W) > 1e-9 * W || Fabs(ny * h - H) > 1e-9 * H || Fabs(nl * h - lw) > 1e-9 * W || nl < 1 ||
    Fabs(nleft * h - (xc - lw / 2)) > 1e-9 * W || nleft < 1 || nright < 1)
  Error("plate2d.geo: W, H, lw and the patch's left end xc - lw/2 must be multiples of h, the patch inside the top edge");
EndIf
x1 = nleft * h; x2 = x1 + nl * h;
Point(1) = {0, 0, 0}; Point(2) = {W, 0, 0}; Point(3) = {W, H, 0};
Point(4) = {x2, H, 0}; Point(5) = {x1, H, 0}; Point(6) = {0, H, 0};
Line(1) = {1, 2};            // base
Line(2) = {2, 3};            // right side
Line(3) = {3, 4};            // top, right of the patch
Line(4) = {4, 5};            // loaded patch
Line(5) = {5, 6};            // top, left of the patch
Line(6) = {6, 1};            // left side
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Transfinite Curve{1} = nx + 1; Transfinite Curve{2, 6} = ny + 1;
Transfinite Curve{3} = nright + 1; Transfinite Curve{5} = nleft + 1; Transfinite Curve{4} = nl + 1;
Transfinite Surface{1} = {1, 2, 3, 6};
Recombine Surface{1};
Physical Curve("base") = {1};
Physical Curve("load") = {4};
Physical Curve("free") = {2, 3, 5, 6};
Physical Surface("plate") = {1};
