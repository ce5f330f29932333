// Two aluminium plates 8 mm thick (x 5.5 to 40, a lap joint's plates without the bolt):
// plates_steep_law.dat clamps them by pressure next to the hole (curves "clamp1", "clamp2").
lp = 1.0; lo = 3.0;
// plate 1 z 8..16, plate 2 z 0..8, x 5.5..40
Point(21) = {5.5, 8, 0, lp}; Point(22) = {40, 8, 0, lo}; Point(23) = {40, 16, 0, lo}; Point(24) = {20, 16, 0, lo};
Point(25) = {16, 16, 0, lp}; Point(26) = {5.5, 16, 0, lp};
Point(31) = {5.5, 0, 0, lp}; Point(32) = {16, 0, 0, lp}; Point(33) = {20, 0, 0, lo}; Point(34) = {40, 0, 0, lo};
Point(35) = {40, 8, 0, lo}; Point(36) = {5.5, 8, 0, lp};
Line(21) = {21, 22}; Line(22) = {22, 23}; Line(23) = {23, 24}; Line(24) = {24, 25}; Line(25) = {25, 26};
Line(26) = {26, 21};
Line(31) = {31, 32}; Line(32) = {32, 33}; Line(33) = {33, 34}; Line(34) = {34, 35}; Line(35) = {35, 36};
Line(36) = {36, 31};
Curve Loop(3) = {21, 22, 23, 24, 25, 26}; Plane Surface(3) = {3};
Curve Loop(4) = {31, 32, 33, 34, 35, 36}; Plane Surface(4) = {4};
Physical Surface("plate1") = {3};
Physical Surface("plate2") = {4};
Physical Curve("plate1_top") = {23, 24, 25};
Physical Curve("plate1_bottom") = {21};
Physical Curve("plate2_top") = {35};
Physical Curve("plate2_bottom") = {31, 32, 33};
Physical Curve("load") = {23};
Physical Curve("support") = {33};
Physical Curve("clamp1") = {24, 25};
Physical Curve("clamp2") = {31, 32};
