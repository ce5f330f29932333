// The paper's example 5.1 (Altenbach & Buczkowski; inputs/punch_5_1.dat) as a .geo for the
// remeshing route of tools/adapt.py (docs/adaptivity.md, "The example decks"): an elastic punch
// of width B = 100 mm on an elastic foundation of width A = 190 mm, both 100 mm high, plane
// stress, thickness 10 mm.  Symmetric half model (x >= 0).  The same bodies as the card deck;
// the two are meshed independently (the deck pairs them with MATCHING SEGMENT).  8-node
// quadrilaterals.  A user's coarse start mesh: one size, 10 mm, everywhere -- no grading
// towards the punch corner (50, 0), which the hand model has.
hb = 50.0;  H = 100.0;  ha = 95.0;
h0 = 10.0;

// punch
Point(1) = {0, 0, 0, h0};
Point(2) = {hb, 0, 0, h0};
Point(3) = {hb, H, 0, h0};
Point(4) = {0, H, 0, h0};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// foundation
Point(11) = {0, 0, 0, h0};
Point(12) = {hb, 0, 0, h0};
Point(13) = {ha, 0, 0, h0};
Point(14) = {ha, -H, 0, h0};
Point(15) = {0, -H, 0, h0};
Line(11) = {11, 12};  Line(12) = {12, 13};  Line(13) = {13, 14};  Line(14) = {14, 15};  Line(15) = {15, 11};
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};

Physical Surface("punch") = {1};
Physical Surface("foundation") = {2};
Physical Curve("punch_bottom") = {1};
Physical Curve("punch_top") = {3};
Physical Curve("punch_axis") = {4};
Physical Curve("fd_top") = {11, 12};
Physical Curve("fd_axis") = {15};
Physical Curve("fd_base") = {14};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
