// Shrink fit (axisymmetric, x = r, y = z): a steel shaft r 0..10, z 0..30, and a steel hub r 9.99..25, z 5..25 --
// 0.01 mm of interference on the radius; Q8 (recombined, incomplete second order).  shrink_fit.dat.
Point(1) = {0, 0, 0, 1.0}; Point(2) = {10, 0, 0, 1.0}; Point(3) = {10, 30, 0, 1.0}; Point(4) = {0, 30, 0, 1.0};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Point(11) = {9.99, 5, 0, 0.8}; Point(12) = {25, 5, 0, 2.0}; Point(13) = {25, 25, 0, 2.0}; Point(14) = {9.99, 25, 0, 0.8};
Line(11) = {11,12}; Line(12) = {12,13}; Line(13) = {13,14}; Line(14) = {14,11};
Curve Loop(2) = {11,12,13,14}; Plane Surface(2) = {2};
Physical Surface("shaft") = {1};
Physical Surface("hub") = {2};
Physical Curve("shaft_out") = {2};
Physical Curve("hub_bore") = {14};
Physical Curve("shaft_end") = {1};
Physical Curve("hub_face") = {13};
Mesh.RecombineAll = 1;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
