// A straight rod (strip centreline) of length L along +x from the origin, N equal segments, for
// the PBD angle bending model (CN104268305A). Clamped like the notes say: the rod starts one
// segment behind the clamp (a ghost segment from x = -L/N to 0); both of its nodes form the
// physical group "clamp", so pinning "clamp" fixes the position and the slope at x = 0.
// Parameters can be overridden from a case file ([pbd.mesh_parameters]).
DefineConstant[
  L = {0.5, Name "L"},   // rod length [m]
  N = {40,  Name "N"}    // segments along the rod
];
n = Round(N);
If (n < 2)
  Error("rod2d.geo: N must be at least 2");
  Abort;
EndIf
Point(1) = {-L / n, 0, 0};
Point(2) = {0, 0, 0};
Point(3) = {L, 0, 0};
Line(1) = {1, 2};   // ghost segment inside the clamp
Line(2) = {2, 3};   // the rod
Transfinite Curve{1} = 2;
Transfinite Curve{2} = n + 1;
Physical Curve("clamp") = {1};
Physical Curve("rod") = {2};
Physical Point("tip") = {3};
