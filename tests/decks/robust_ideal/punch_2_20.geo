// Plane-strain flat punch on a foundation, half model (symmetry on x = 0), units mm.
// Punch x 0..10, y 0..5: two 4-node quadrilaterals; foundation x 0..20, y -10..0:
// twenty elements along its top (ten of them under the punch), five through its depth.
// The meshes do not match along the contact y = 0 (MATCHING SEGMENT).
// gmsh -2 -format msh41 punch_2_20.geo -o punch_2_20.msh
Point(1) = {0, 0, 0};
Point(2) = {10, 0, 0};
Point(3) = {10, 5, 0};
Point(4) = {0, 5, 0};
Line(1) = {1, 2};    // punch bottom
Line(2) = {2, 3};
Line(3) = {3, 4};    // punch top: the pressure
Line(4) = {4, 1};    // punch symmetry line
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve {1, 3} = 3;
Transfinite Curve {2, 4} = 2;
Transfinite Surface {1};
Point(11) = {0, -10, 0};
Point(12) = {20, -10, 0};
Point(13) = {20, 0, 0};
Point(14) = {10, 0, 0};
Point(15) = {0, 0, 0};
Line(11) = {11, 12};  // foundation bottom
Line(12) = {12, 13};
Line(13) = {13, 14};  // foundation top beyond the punch
Line(14) = {14, 15};  // foundation top under the punch: contact surface A
Line(15) = {15, 11};  // foundation symmetry line
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};
Transfinite Curve {11} = 21;
Transfinite Curve {13, 14} = 11;
Transfinite Curve {12, 15} = 6;
Transfinite Surface {2} = {11, 12, 13, 15};
Physical Surface("punch") = {1};
Physical Surface("foundation") = {2};
Physical Curve("punch_bottom") = {1};
Physical Curve("punch_top") = {3};
Physical Curve("punch_sym") = {4};
Physical Curve("found_contact") = {14};
Physical Curve("found_bottom") = {11};
Physical Curve("found_sym") = {15};
Mesh.RecombineAll = 1;
