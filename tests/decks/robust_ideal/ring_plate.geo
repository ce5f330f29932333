// Axisymmetric flange ring on a plate (x = r, y = z), units mm.
// Ring r 20..40, z 0..10, meshed with h = 2.5; plate r 0..60, z -10..0,
// h = 4: the meshes do not match along the contact z = 0 (MATCHING SEGMENT).
// gmsh -2 -format msh41 ring_plate.geo -o ring_plate.msh
hr = 2.5;
hp = 4.0;
// ring
Point(1) = {20, 0, 0, hr};
Point(2) = {40, 0, 0, hr};
Point(3) = {40, 10, 0, hr};
Point(4) = {20, 10, 0, hr};
Line(1) = {1, 2};   // ring bottom: contact surface A
Line(2) = {2, 3};
Line(3) = {3, 4};   // ring top: the pressure
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// plate
Point(11) = {0, -10, 0, hp};
Point(12) = {60, -10, 0, hp};
Point(13) = {60, 0, 0, hp};
Point(14) = {0, 0, 0, hp};
Line(11) = {11, 12};  // plate bottom: held axially
Line(12) = {12, 13};
Line(13) = {13, 14};  // plate top: contact surface B
Line(14) = {14, 11};  // the axis
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Physical Surface("ring") = {1};
Physical Surface("plate") = {2};
Physical Curve("ring_bottom") = {1};
Physical Curve("ring_top") = {3};
Physical Curve("plate_top") = {13};
Physical Curve("plate_bottom") = {11};
Physical Curve("axis") = {14};
// 8-node quadrilaterals
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
