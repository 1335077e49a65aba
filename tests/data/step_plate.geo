// The patch plate from a millimetre STEP file (plate_mm.step, made by make_plate_mm_step.geo): its groups picked
// by bounding boxes in millimetres; lc the element size [mm]. Run with [mesh] unit = "mm".
SetFactory("OpenCASCADE");
Merge "plate_mm.step";
DefineConstant[ lc = {10, Name "lc"} ];
Mesh.CharacteristicLengthMax = lc;
e = 1e-3;
Physical Curve("base") = Curve In BoundingBox{-e, -e, -e, 300 + e, e, e};
Physical Curve("patch") = Curve In BoundingBox{195 - e, 150 - e, -e, 205 + e, 150 + e, e};
Physical Surface("plate") = Surface{:};
