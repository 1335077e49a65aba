// A 3D cantilever: a W x H x D beam (x along its length, load along -y, z across), clamped on its
// end x = 0 (group "clamp"), loaded on a patch of length lw at the far end of its top face y = H,
// across its whole depth (group "load"), every other face free. Units: metres. Structured cubes of
// edge h (the agent size); W, H, D and lw must be multiples of h.
DefineConstant[
  W  = {0.1,    Name "W"},    // length [m]
  H  = {0.02,   Name "H"},    // depth along y [m]
  D  = {0.02,   Name "D"},    // width along z [m]
  h  = {0.0025, Name "h"},    // agent (cube) size [m]
  lw = {0.0025, Name "lw"}    // loaded patch at the free end [m]
];
nx = Round(W / h); ny = Round(H / h); nz = Round(D / h); nl = Round(lw / h);
If (Fabs(nx * h - W) > 1e-9 * W || Fabs(ny * h - H) > 1e-9 * H || Fabs(nz * h - D) > 1e-9 * D ||
    Fabs(nl * h - lw) > 1e-9 * W || nl < 1 || nl >= nx)
  Error("cantilever3d.geo: W, H, D and lw must be multiples of h, the patch shorter than the beam");
EndIf
// The side profile (z = 0) as cantilever2d.geo's, extruded across z in nz layers.
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
out[] = Extrude {0, 0, D} { Surface{1}; Layers{nz}; Recombine; };
// out[]: the face at z = D, the volume, then the faces swept by lines 1 to 5.
Physical Surface("clamp") = {out[6]};
Physical Surface("load") = {out[4]};
Physical Surface("free") = {1, out[0], out[2], out[3], out[5]};
Physical Volume("beam") = {out[1]};
