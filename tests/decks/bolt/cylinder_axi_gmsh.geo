// Solid cylinder r 0..1, z 0..4, cut at z = 2 (physical curve "cut"): two surfaces meshed as
// 8-node quadrilaterals, 3 x 2 elements each.
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 2, 0}; Point(4) = {0, 2, 0};
Point(5) = {1, 4, 0}; Point(6) = {0, 4, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {3, 5}; Line(6) = {5, 6}; Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {-3, 5, 6, 7}; Plane Surface(2) = {2};
Transfinite Curve{1, 3, 6} = 4; Transfinite Curve{2, 4, 5, 7} = 3;
Transfinite Surface{1, 2}; Recombine Surface{1, 2};
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
Physical Surface("shank") = {1, 2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {6};
Physical Curve("cut") = {3};
