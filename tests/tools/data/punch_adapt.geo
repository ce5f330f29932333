// A flat punch on an elastic foundation (the arrangement of the paper's example 5.1, smaller):
// half model, symmetry on x = 0.  Units: mm.  Punch 0 <= x <= B, 0 <= y <= H; foundation
// 0 <= x <= W, -D <= y <= 0.  The two bodies are meshed independently (their surface nodes do
// not match: the deck pairs them with MATCHING SEGMENT).  4-node quadrilaterals.
B = 25.0;  H = 25.0;  W = 60.0;  D = 50.0;
h_punch = 5.0;     // element size in the punch
h_top = 6.0;       // on the foundation's surface
h_far = 15.0;      // at the foundation's far edges

// punch
Point(1) = {0, 0, 0, h_punch};
Point(2) = {B, 0, 0, h_punch};
Point(3) = {B, H, 0, h_punch};
Point(4) = {0, H, 0, h_punch};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// foundation
Point(11) = {0, -D, 0, h_far};
Point(12) = {W, -D, 0, h_far};
Point(13) = {W, 0, 0, h_far};
Point(14) = {0, 0, 0, h_top};
Line(11) = {11, 12};  Line(12) = {12, 13};  Line(13) = {13, 14};  Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Physical Surface("punch") = {1};
Physical Surface("foundation") = {2};
Physical Curve("punch_bottom") = {1};
Physical Curve("punch_top") = {3};
Physical Curve("punch_axis") = {4};
Physical Curve("base_top") = {13};
Physical Curve("base_axis") = {14};
Physical Curve("base_bottom") = {11};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 1;
