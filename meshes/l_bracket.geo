// An L-shaped bracket: a W x W plate with an N x N notch cut from its upper right corner, built
// of three structured patches of squares of size h (the agent size), on a rigid base and loaded
// from above on a patch of width lw centred on the upright arm's top. Units: metres.
// W, N, lw and the patch's ends must be multiples of h.
DefineConstant[
  W  = {0.2,   Name "W"},    // outer size [m]
  N  = {0.1,   Name "N"},    // notch size [m]
  h  = {0.005, Name "h"},    // agent (cell) size [m]
  lw = {0.01,  Name "lw"}    // width of the loaded patch [m]
];
A = W - N;  // width of the upright arm and height of the foot
xc = A / 2;
na = Round(A / h); nn = Round(N / h); nl = Round(lw / h); nleft = Round((xc - lw / 2) / h);
nright = na - nleft - nl;
If (Fabs(na * h - A) > 1e-9 * W || Fabs(nn * h - N) > 1e-9 * W || Fabs(nl * h - lw) > 1e-9 * W || nl < 1 ||
    Fabs(nleft * h - (xc - lw / 2)) > 1e-9 * W || nleft < 1 || nright < 1 || N <= 0 || N >= W)
  Error("l_bracket.geo: W - N, N, lw and the patch's left end must be multiples of h, the patch inside the arm's top");
EndIf
x1 = nleft * h; x2 = x1 + nl * h;
Point(1) = {0, 0, 0}; Point(2) = {A, 0, 0}; Point(3) = {W, 0, 0}; Point(4) = {W, A, 0};
Point(5) = {A, A, 0}; Point(6) = {0, A, 0}; Point(7) = {0, W, 0}; Point(8) = {A, W, 0};
Point(9) = {x2, W, 0}; Point(10) = {x1, W, 0};
Line(1) = {1, 2}; Line(2) = {2, 3};            // base
Line(3) = {3, 4};                              // end of the foot
Line(4) = {4, 5};                              // top of the foot (the notch's floor)
Line(5) = {5, 8};                              // the notch's wall
Line(6) = {8, 9}; Line(7) = {9, 10}; Line(8) = {10, 7};  // top of the arm: right, patch, left
Line(9) = {7, 6}; Line(10) = {6, 1};           // back
Line(11) = {2, 5}; Line(12) = {5, 6};          // patch borders inside
Curve Loop(1) = {1, 11, 12, 10}; Plane Surface(1) = {1};          // the corner block
Curve Loop(2) = {2, 3, 4, -11}; Plane Surface(2) = {2};           // the foot
Curve Loop(3) = {-12, 5, 6, 7, 8, 9}; Plane Surface(3) = {3};     // the upright arm
Transfinite Curve{1, 3, 10, 11, 12} = na + 1; Transfinite Curve{2, 4, 5, 9} = nn + 1;
Transfinite Curve{6} = nright + 1; Transfinite Curve{7} = nl + 1; Transfinite Curve{8} = nleft + 1;
Transfinite Surface{1}; Transfinite Surface{2}; Transfinite Surface{3} = {6, 5, 8, 7};
Recombine Surface{1:3};
Physical Curve("base") = {1, 2};
Physical Curve("load") = {7};
Physical Curve("free") = {3, 4, 5, 6, 8, 9, 10};
Physical Surface("bracket") = {1:3};
