// A new user's bolted lap in plane strain (bolt_lap_plane.dat): half model (x >= 0, symmetry at
// x = 0), steel bolt (shank half-width 5, head and nut 9) through two aluminium plates 8 mm thick to x = 40.
lb = 1.0; lp = 1.0; lo = 3.0;
// bolt: nut z -6..0, shank 0..16, head 16..22
Point(1) = {0, -6, 0, lb}; Point(2) = {9, -6, 0, lb}; Point(3) = {9, 0, 0, lb}; Point(4) = {5.5, 0, 0, lb};
Point(5) = {5, 0, 0, lb}; Point(6) = {5, 8, 0, lb}; Point(7) = {5, 16, 0, lb}; Point(8) = {5.5, 16, 0, lb};
Point(9) = {9, 16, 0, lb}; Point(10) = {9, 22, 0, lb}; Point(11) = {0, 22, 0, lb}; Point(12) = {0, 8, 0, lb};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6}; Line(6) = {6, 12};
Line(7) = {12, 1}; Line(8) = {6, 7}; Line(9) = {7, 8}; Line(10) = {8, 9}; Line(11) = {9, 10};
Line(12) = {10, 11}; Line(13) = {11, 12};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7}; Plane Surface(1) = {1};
Curve Loop(2) = {-6, 8, 9, 10, 11, 12, 13}; Plane Surface(2) = {2};
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
Physical Surface("bolt") = {1, 2};
Physical Surface("plate1") = {3};
Physical Surface("plate2") = {4};
Physical Curve("cut") = {6};
Physical Curve("axis") = {7, 13};
Physical Curve("head_face") = {10};
Physical Curve("nut_face") = {3};
Physical Curve("plate1_top") = {23, 24, 25};
Physical Curve("plate1_bottom") = {21};
Physical Curve("plate2_top") = {35};
Physical Curve("plate2_bottom") = {31, 32, 33};
Physical Curve("load") = {23};
Physical Curve("support") = {33};
