// Writes plate_mm.step (`gmsh -0 make_plate_mm_step.geo` in tests/data): the patch plate of
// patch_plate.geo in millimetres, as a CAD file, its top edge split at the 10 mm patch at x = 200 mm.
SetFactory("OpenCASCADE");
Point(1) = {0, 0, 0}; Point(2) = {300, 0, 0}; Point(3) = {300, 150, 0}; Point(4) = {205, 150, 0};
Point(5) = {195, 150, 0}; Point(6) = {0, 150, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 1};
Curve Loop(1) = {1:6}; Plane Surface(1) = {1};
Disk(2) = {100, 75, 0, 20};
BooleanDifference(3) = {Surface{1}; Delete;}{Surface{2}; Delete;};
Save "plate_mm.step";
