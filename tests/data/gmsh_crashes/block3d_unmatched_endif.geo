// meshes/block3d.geo (h = 0.01, lw = 0.02) with an If line dropped: an unmatched EndIf in a For loop (run 239)
// Crashed gmsh 4.8 inside the workbench (SIGSEGV in gmsh's .geo parser, gmsh_yyparse); tests/cli/gmsh_crashes.sh.
DefineConstant[
  W  = {0.04,  Name "W"},    // width along x [m]
  H  = {0.04,  Name "H"},    // height along y [m]
  D  = {0.04,  Name "D"},    // depth along z [m]
  h  = {0.01, Name "h"},    // agent (cube) size [m]
  lw = {0.02, Name "lw"},   // edge of the square loaded patch [m]
  xc = {-1,    Name "xc"}    // x of the patch centre [m]; -1: the middle of the top face
];
If (xc < 0)
  xc = W / 2;
EndIf
nx = Round(W / h); ny = Round(H / h); nz = Round(D / h); nl = Round(lw / h);
sx = Round((xc - lw / 2) / h); sz = Round((nz - nl) / 2);
If (Fabs(nx * h - W) > 1e-9 * W || Fabs(ny * h - H) > 1e-9 * H || Fabs(nz * h - D) > 1e-9 * D ||
    Fabs(nl * h - lw) > 1e-9 * W || nl < 1 || sx < 1 || sz < 1 || nx - sx - nl < 1 || 2 * sz + nl != nz ||
    Fabs(sx * h - (xc - lw / 2)) > 1e-9 * W)
  Error("block3d.geo: W, H, D and lw must be multiples of h, xc - lw/2 and (D - lw)/2 multiples of h, the patch inside the top face");
EndIf
xs[] = {0, sx * h, (sx + nl) * h, W}; cx[] = {sx, nl, nx - sx - nl};
zs[] = {0, sz * h, (sz + nl) * h, D}; cz[] = {sz, nl, sz};
For i In {0:3}
  For k In {0:3}
    p[i * 4 + k] = newp; Point(p[i * 4 + k]) = {xs[i], 0, zs[k]};
  EndFor
EndFor
For i In {0:2}
  For k In {0:2}
    a = p[i * 4 + k]; b = p[(i + 1) * 4 + k]; c = p[(i + 1) * 4 + k + 1]; d = p[i * 4 + k + 1];
    l1 = newl; Line(l1) = {a, b}; l2 = newl; Line(l2) = {b, c};
    l3 = newl; Line(l3) = {c, d}; l4 = newl; Line(l4) = {d, a};
    Transfinite Curve{l1, l3} = cx[i] + 1; Transfinite Curve{l2, l4} = cz[k] + 1;
    cl = newll; Curve Loop(cl) = {l1, l2, l3, l4};
    s = news; Plane Surface(s) = {cl};
    Transfinite Surface{s}; Recombine Surface{s};
    base[i * 3 + k] = s;
  EndFor
EndFor
Coherence;
For n In {0:8}
  out[] = Extrude {0, H, 0} { Surface{base[n]}; Layers{ny}; Recombine; };
  top[n] = out[0]; vol[n] = out[1];
EndFor
Physical Surface("base") = {base[]};
Physical Surface("load") = {top[4]};
outer[] = CombinedBoundary{ Volume{vol[]}; };
freeFaces[] = {};
For n In {0:#outer[] - 1}
  isBase = 0;
  For m In {0:8}
      isBase = 1;
    EndIf
  EndFor
  If (isBase == 0)
    freeFaces[] += Fabs(outer[n]);
  EndIf
EndFor
Physical Surface("free") = {freeFaces[]};
Physical Volume("block") = {vol[]};
