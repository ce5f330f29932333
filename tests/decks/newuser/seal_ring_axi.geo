// A new user's seal ring (tests/decks/newuser/seal_ring_axi.dat): axisymmetric, x = r, y = z (mm);
// a ring r 20..25, z 0..5 between two steel plates r 15..35, Q8 (recombined, incomplete second order).
Point(1) = {15,-5,0,1.5}; Point(2) = {35,-5,0,1.5}; Point(3) = {35,0,0,1.0}; Point(4) = {25,0,0,0.4}; Point(5) = {20,0,0,0.4}; Point(6) = {15,0,0,1.0};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,5}; Line(5) = {5,6}; Line(6) = {6,1};
Curve Loop(1) = {1,2,3,4,5,6}; Plane Surface(1) = {1};
Point(11) = {20,0,0,0.4}; Point(12) = {25,0,0,0.4}; Point(13) = {25,5,0,0.4}; Point(14) = {20,5,0,0.4};
Line(11) = {11,12}; Line(12) = {12,13}; Line(13) = {13,14}; Line(14) = {14,11};
Curve Loop(2) = {11,12,13,14}; Plane Surface(2) = {2};
Point(21) = {15,5,0,1.0}; Point(22) = {20,5,0,0.4}; Point(23) = {25,5,0,0.4}; Point(24) = {35,5,0,1.0}; Point(25) = {35,10,0,1.5}; Point(26) = {15,10,0,1.5};
Line(21) = {21,22}; Line(22) = {22,23}; Line(23) = {23,24}; Line(24) = {24,25}; Line(25) = {25,26}; Line(26) = {26,21};
Curve Loop(3) = {21,22,23,24,25,26}; Plane Surface(3) = {3};
Recombine Surface{1,2,3};
Mesh.Algorithm = 6; Mesh.RecombineAll = 1; Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
Physical Surface("lower") = {1}; Physical Surface("seal") = {2}; Physical Surface("upper") = {3};
Physical Curve("base") = {1}; Physical Curve("top") = {25};
Physical Curve("lower_face") = {3,4,5}; Physical Curve("seal_bottom") = {11};
Physical Curve("seal_top") = {13}; Physical Curve("upper_face") = {21,22,23};
