// A plane-strain section through a bolted lap joint (mm): two aluminium plates 6 mm thick, cut by
// the slot of the bolt |x| < 5.5 (each plate is two pieces in the section), a steel bolt |x| < 5
// with head and nut |x| < 8, 4 mm thick; the shank is cut at y = -3 by the pretension section.
// newuser/bolt_lap_shear_cycles.dat; gmsh -2 -format msh22 (Q4 and T3 from recombination).
h = 1.0; hf = 3.0;
// lower plate y -6..0, two parts: left x -40..-5.5 and right 5.5..40
Point(1) = {-40,-6,0,hf}; Point(2) = {-5.5,-6,0,h}; Point(3) = {-5.5,0,0,h}; Point(4) = {-40,0,0,hf};
Point(5) = {5.5,-6,0,h}; Point(6) = {40,-6,0,hf}; Point(7) = {40,0,0,hf}; Point(8) = {5.5,0,0,h};
Point(41) = {-8,-6,0,h}; Point(42) = {8,-6,0,h};
Line(1) = {1,41}; Line(41) = {41,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Line(5) = {5,42}; Line(42) = {42,6}; Line(6) = {6,7}; Line(7) = {7,8}; Line(8) = {8,5};
Curve Loop(1) = {1,41,2,3,4}; Plane Surface(1) = {1};
Curve Loop(2) = {5,42,6,7,8}; Plane Surface(2) = {2};
// upper plate y 0..6
Point(11) = {-40,0,0,hf}; Point(12) = {-5.5,0,0,h}; Point(13) = {-5.5,6,0,h}; Point(14) = {-40,6,0,hf};
Point(15) = {5.5,0,0,h}; Point(16) = {40,0,0,hf}; Point(17) = {40,6,0,hf}; Point(18) = {5.5,6,0,h};
Point(43) = {-8,6,0,h}; Point(44) = {8,6,0,h};
Line(11) = {11,12}; Line(12) = {12,13}; Line(13) = {13,43}; Line(43) = {43,14}; Line(14) = {14,11};
Line(15) = {15,16}; Line(16) = {16,17}; Line(17) = {17,44}; Line(44) = {44,18}; Line(18) = {18,15};
Curve Loop(3) = {11,12,13,43,14}; Plane Surface(3) = {3};
Curve Loop(4) = {15,16,17,44,18}; Plane Surface(4) = {4};
// bolt: nut y -10..-6 |x|<8, shank y -6..6 |x|<5, head y 6..10 |x|<8; cut at y=-3
Point(21) = {-8,-10,0,h}; Point(22) = {8,-10,0,h}; Point(23) = {8,-6,0,h}; Point(24) = {5,-6,0,h};
Point(25) = {5,-3,0,h}; Point(26) = {-5,-3,0,h}; Point(27) = {-5,-6,0,h}; Point(28) = {-8,-6,0,h};
Point(29) = {5,6,0,h}; Point(30) = {8,6,0,h}; Point(31) = {8,10,0,h}; Point(32) = {-8,10,0,h};
Point(33) = {-8,6,0,h}; Point(34) = {-5,6,0,h};
Point(35) = {-5.5,-6,0,h}; Point(36) = {5.5,-6,0,h}; Point(37) = {-5.5,6,0,h}; Point(38) = {5.5,6,0,h};
Line(21) = {21,22}; Line(22) = {22,23}; Line(23) = {23,36}; Line(36) = {36,24}; Line(24) = {24,25};
Line(25) = {25,26}; Line(26) = {26,27}; Line(27) = {27,35}; Line(35) = {35,28}; Line(28) = {28,21};
Curve Loop(5) = {21,22,23,36,24,25,26,27,35,28}; Plane Surface(5) = {5};
Line(29) = {25,29}; Line(30) = {29,38}; Line(37) = {38,30}; Line(31) = {30,31}; Line(32) = {31,32};
Line(33) = {32,33}; Line(34) = {33,37}; Line(38) = {37,34}; Line(39) = {34,26};
Curve Loop(6) = {-25,29,30,37,31,32,33,34,38,39}; Plane Surface(6) = {6};
Recombine Surface{1,2,3,4,5,6};
Mesh.Algorithm = 6; Mesh.RecombineAll = 1;
Physical Surface("lower") = {1,2};
Physical Surface("upper") = {3,4};
Physical Surface("bolt") = {5,6};
Physical Curve("cut") = {25};
Physical Curve("lower_top") = {3,7};
Physical Curve("upper_bottom") = {11,15};
Physical Curve("upper_top") = {13,44};     // under the head |x| 5.5..8
Physical Curve("head_face") = {34,37};
Physical Curve("lower_bottom") = {41,5};   // on the nut |x| 5.5..8
Physical Curve("nut_face") = {23,35};
Physical Curve("fixed") = {4,6};
Physical Curve("pull") = {16};
