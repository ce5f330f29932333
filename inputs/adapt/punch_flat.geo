// A flat punch (half width b = 1 mm, 1000 times stiffer than the half-plane: rigid to 0.1 %)
// pressed into an elastic half-plane, plane strain, ideal frictionless contact, P' = 100 N/mm
// (docs/adaptivity.md, "Validation"; the edge singularity p ~ (b^2 - x^2)^-1/2).  Half model,
// symmetry on x = 0.  Punch 0 <= x <= b, 0 <= y <= H; half-plane 0 <= x <= W, -D <= y <= 0
// (W = D = 40 b), clamped at its base.  A point at x = 0.9 b on both faces keeps a node there on
// every mesh (the edge band's border).  The bodies are meshed independently (MATCHING SEGMENT).
// 4-node quadrilaterals; the coarse start mesh of tools/adapt.py.
b = 1.0;  H = 1.0;  W = 40.0;  D = 40.0;
h_e = 0.1;       // at the punch edge (x = b)
h_p = 0.25;      // elsewhere in the punch and at the axis
h_f = 8.0;       // the half-plane's far corners

// punch
Point(1) = {0, 0, 0, h_p};
Point(2) = {0.9 * b, 0, 0, h_e};
Point(3) = {b, 0, 0, h_e};
Point(4) = {b, H, 0, h_p};
Point(5) = {0, H, 0, h_p};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Line(4) = {4, 5};  Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

// half-plane
Point(11) = {0, 0, 0, h_p};
Point(12) = {0.9 * b, 0, 0, h_e};
Point(13) = {b, 0, 0, h_e};
Point(14) = {W, 0, 0, h_f};
Point(15) = {W, -D, 0, h_f};
Point(16) = {0, -D, 0, h_f};
Line(11) = {11, 12};  Line(12) = {12, 13};  Line(13) = {13, 14};  Line(14) = {14, 15};  Line(15) = {15, 16};
Line(16) = {16, 11};
Curve Loop(2) = {11, 12, 13, 14, 15, 16};
Plane Surface(2) = {2};

Physical Surface("punch") = {1};
Physical Surface("halfplane") = {2};
Physical Curve("punch_bottom") = {1, 2};
Physical Curve("punch_top") = {4};
Physical Curve("punch_axis") = {5};
Physical Curve("hp_top") = {11, 12, 13};
Physical Curve("hp_axis") = {16};
Physical Curve("hp_bottom") = {15};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 1;
