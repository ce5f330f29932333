// A stack held by its contact alone (fail_stack_reload.dat), plane strain half model (x >= 0, symmetry at x = 0):
// a steel flange x 0..20, y 3..13 on a fibre gasket x 0..15, y 0..3 on a steel flange x 0..20, y -10..0. Q8.
Point(1) = {0, -10, 0, 2.0}; Point(2) = {20, -10, 0, 2.0}; Point(3) = {20, 0, 0, 1.0}; Point(4) = {0, 0, 0, 1.0};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Point(11) = {0, 0, 0, 0.6}; Point(12) = {15, 0, 0, 0.6}; Point(13) = {15, 3, 0, 0.6}; Point(14) = {0, 3, 0, 0.6};
Line(11) = {11,12}; Line(12) = {12,13}; Line(13) = {13,14}; Line(14) = {14,11};
Curve Loop(2) = {11,12,13,14}; Plane Surface(2) = {2};
Point(21) = {0, 3, 0, 0.8}; Point(22) = {20, 3, 0, 0.8}; Point(23) = {20, 13, 0, 2.0}; Point(24) = {0, 13, 0, 2.0};
Line(21) = {21,22}; Line(22) = {22,23}; Line(23) = {23,24}; Line(24) = {24,21};
Curve Loop(3) = {21,22,23,24}; Plane Surface(3) = {3};
Physical Surface("lower") = {1};
Physical Surface("gasket") = {2};
Physical Surface("upper") = {3};
Physical Curve("lower_base") = {1};
Physical Curve("lower_top") = {3};
Physical Curve("gasket_bottom") = {11};
Physical Curve("gasket_top") = {13};
Physical Curve("upper_bottom") = {21};
Physical Curve("upper_top") = {23};
Physical Curve("sym") = {4, 14, 24};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
