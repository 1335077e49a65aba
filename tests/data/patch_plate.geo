// A researcher's own part (tests): a 300 x 150 mm plate on its base ("base"), an off-centre hole of
// 40 mm ("hole"), a load patch of width lw centred at x = px on its top ("patch"), triangles of
// size lc. Lengths are given in metres times u: u = 1000 writes the same plate in millimetres.
DefineConstant[
  px = {0.2, Name "px"},   lw = {0.01, Name "lw"}, lc = {0.01, Name "lc"}, u = {1, Name "u"}
];
W = 0.3 * u; H = 0.15 * u; R = 0.02 * u; cx = 0.1 * u; cy = 0.075 * u; a = (px - lw / 2) * u; b = (px + lw / 2) * u;
Point(1) = {0, 0, 0, lc * u}; Point(2) = {W, 0, 0, lc * u}; Point(3) = {W, H, 0, lc * u};
Point(4) = {b, H, 0, lc * u}; Point(5) = {a, H, 0, lc * u}; Point(6) = {0, H, 0, lc * u};
Point(7) = {cx, cy, 0, lc * u}; Point(8) = {cx + R, cy, 0, lc * u}; Point(9) = {cx, cy + R, 0, lc * u};
Point(10) = {cx - R, cy, 0, lc * u}; Point(11) = {cx, cy - R, 0, lc * u};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Circle(7) = {8, 7, 9}; Circle(8) = {9, 7, 10}; Circle(9) = {10, 7, 11}; Circle(10) = {11, 7, 8};
Curve Loop(1) = {1:6}; Curve Loop(2) = {7:10};
Plane Surface(1) = {1, 2};
Physical Curve("base") = {1};
Physical Curve("patch") = {4};
Physical Curve("free") = {2, 3, 5, 6};
Physical Curve("hole") = {7:10};
Physical Surface("plate") = {1};
