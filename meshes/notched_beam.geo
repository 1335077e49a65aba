// A notched beam in three-point bending: L x H, a U-notch (width 2 r, depth d, round end of
// radius r) up from the middle of the bottom edge, supported on patches of width s at both ends
// of the bottom, loaded on a patch of width lw at the middle of the top. Triangles of size lc:
// not built of squares, the agent model takes it voxelized (workbench voxelize). Units: metres.
DefineConstant[
  L = {0.2, Name "L"}, H = {0.04, Name "H"}, r = {0.004, Name "r"}, d = {0.012, Name "d"},
  s = {0.01, Name "s"}, lw = {0.012, Name "lw"}, lc = {0.001, Name "lc"}
];
If (d <= r || d >= H || 2 * s + 2 * r >= L || lw >= L)
  Error("notched_beam.geo: the notch, the supports and the load patch must fit the beam");
EndIf
c = L / 2;
Point(1) = {0, 0, 0, lc}; Point(2) = {s, 0, 0, lc}; Point(3) = {c - r, 0, 0, lc};
Point(4) = {c - r, d - r, 0, lc}; Point(5) = {c, d - r, 0, lc}; Point(6) = {c + r, d - r, 0, lc};
Point(7) = {c + r, 0, 0, lc}; Point(8) = {L - s, 0, 0, lc}; Point(9) = {L, 0, 0, lc};
Point(10) = {L, H, 0, lc}; Point(11) = {c + lw / 2, H, 0, lc}; Point(12) = {c - lw / 2, H, 0, lc};
Point(13) = {0, H, 0, lc}; Point(14) = {c, d, 0, lc};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Circle(4) = {4, 5, 14}; Circle(5) = {14, 5, 6};
Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 9}; Line(9) = {9, 10}; Line(10) = {10, 11};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 1};
Curve Loop(1) = {1:13}; Plane Surface(1) = {1};
Physical Curve("supports") = {1, 8};
Physical Curve("load") = {11};
Physical Curve("notch") = {3, 4, 5, 6};
Physical Curve("free") = {2, 7, 9, 10, 12, 13};
Physical Surface("beam") = {1};
