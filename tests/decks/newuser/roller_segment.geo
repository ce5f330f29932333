// A steel half-roller (R = 10 mm) on an aluminium block 40 x 15 mm, plane strain: the deck
// roller_segment.dat (meshed by gmsh -2 -format msh41 roller_segment.geo -o roller_segment.msh)
lc = 1.0; lf = 0.25;
// block B: y in [-15, 0], x in [-20, 20]
Point(1) = {-20, -15, 0, lc*3};
Point(2) = { 20, -15, 0, lc*3};
Point(3) = { 20,   0, 0, lc*2};
Point(4) = {  3,   0, 0, lf};
Point(5) = { -3,   0, 0, lf};
Point(6) = {-20,   0, 0, lc*2};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,5}; Line(5) = {5,6}; Line(6) = {6,1};
Curve Loop(1) = {1,2,3,4,5,6}; Plane Surface(1) = {1};
// roller A: lower half disc centre (0,10) radius 10 touching y=0 at x=0
Point(10) = {0, 10, 0, lc};
Point(11) = {10, 10, 0, lc*2};
Point(12) = {-10, 10, 0, lc*2};
Point(13) = {0, 0, 0, lf};
Circle(11) = {11, 10, 13}; Circle(12) = {13, 10, 12};
Line(13) = {12, 10}; Line(14) = {10, 11};
Curve Loop(2) = {11, 12, 13, 14}; Plane Surface(2) = {2};
Physical Surface("block") = {1};
Physical Surface("roller") = {2};
Physical Curve("base") = {1};
Physical Curve("btop") = {3,4,5};
Physical Curve("rbottom") = {11,12};
Physical Curve("rtop") = {13,14};
Physical Point("centre") = {10};
Mesh.RecombineAll = 1;
