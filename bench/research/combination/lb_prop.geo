// Research variant of meshes/l_bracket_side.geo (docs/agent-model.md, "auto": a combination): groups below.
// An L-shaped bracket clamped at its side: a W x W plate with an N x N notch cut from its upper
// right corner (as l_bracket.geo: three structured patches of squares of size h, the agent size),
// its back side x = 0 clamped (a shelf bracket on a wall: the upright arm and the corner against
// it), loaded from above on a patch of width lw at the end of the foot's top (the notch's floor,
// x = W - lw .. W). Units: metres. W - N, N and lw must be multiples of h.
DefineConstant[
  W  = {0.2,   Name "W"},    // outer size [m]
  N  = {0.15,  Name "N"},    // notch size [m]
  h  = {0.005, Name "h"},    // agent (cell) size [m]
  lw = {0.005, Name "lw"}    // width of the loaded patch at the foot's end [m]
];
A = W - N;  // width of the upright arm and depth of the foot
na = Round(A / h); nn = Round(N / h); nl = Round(lw / h);
If (Fabs(na * h - A) > 1e-9 * W || Fabs(nn * h - N) > 1e-9 * W || Fabs(nl * h - lw) > 1e-9 * W || nl < 1 || nl >= nn ||
    N <= 0 || N >= W)
  Error("l_bracket_side.geo: W - N, N and lw must be multiples of h, the patch shorter than the foot's top");
EndIf
Point(1) = {0, 0, 0}; Point(2) = {A, 0, 0}; Point(3) = {W, 0, 0}; Point(4) = {W, A, 0};
Point(5) = {A, A, 0}; Point(6) = {0, A, 0}; Point(7) = {0, W, 0}; Point(8) = {A, W, 0};
Point(9) = {W - nl * h, A, 0}; Point(10) = {W - nl * h, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 10}; Line(14) = {10, 3};            // underside
Line(3) = {3, 4};                              // end of the foot
Line(4) = {4, 9}; Line(13) = {9, 5};           // top of the foot: the loaded patch, the rest
Line(5) = {5, 8};                              // the notch's wall
Line(6) = {8, 7};                              // top of the arm
Line(9) = {7, 6}; Line(10) = {6, 1};           // back (the clamp)
Line(11) = {2, 5}; Line(12) = {5, 6};          // patch borders inside
Curve Loop(1) = {1, 11, 12, 10}; Plane Surface(1) = {1};          // the corner block
Curve Loop(2) = {2, 14, 3, 4, 13, -11}; Plane Surface(2) = {2};       // the foot
Curve Loop(3) = {-12, 5, 6, 9}; Plane Surface(3) = {3};           // the upright arm
Transfinite Curve{1, 3, 6, 10, 11, 12} = na + 1; Transfinite Curve{5, 9} = nn + 1; Transfinite Curve{14} = nl + 1; Transfinite Curve{2} = nn - nl + 1;
Transfinite Curve{4} = nl + 1; Transfinite Curve{13} = nn - nl + 1;
Transfinite Surface{1}; Transfinite Surface{2} = {2, 3, 4, 5}; Transfinite Surface{3};
Recombine Surface{1:3};
Physical Curve("clamp") = {9, 10};
Physical Curve("load") = {4};
Physical Curve("prop") = {14};
Physical Curve("free") = {1, 2, 3, 13, 5, 6};
Physical Surface("bracket") = {1:3};
