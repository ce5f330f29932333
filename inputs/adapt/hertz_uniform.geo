// Hertz (plane strain), uniform start mesh: an elastic cylinder R = 15 mm on an elastic
// half-plane, both E = 21000, nu = 0.3, ideal frictionless contact, P' = 200 N/mm
// (docs/adaptivity.md, "Validation").
// Half model, symmetry on x = 0.  The cylinder is the quarter disc of centre (0, R) with its flat
// top y = R loaded; the half-plane is the rectangle 0 <= x <= W, -D <= y <= 0 (W = D = 4 R, about
// 100 contact half widths), clamped at its base.  The two bodies are meshed independently (the
// deck pairs them with MATCHING SEGMENT).  4-node quadrilaterals.
// UNIFORM start mesh: one size h_u = 3 mm everywhere (1 142 DOFs, about the 926 of
// hertz_adapt.geo's graded start mesh; 5 contact half widths), the fair start of a comparison
// of uniform refinement (--uniform halves h_u) with adaptive refinement (docs/adaptivity.md).
R = 15.0;  a = 0.5754;  c = 3 * a;  W = 60.0;  D = 60.0;
h_u = 3.0;        // everywhere
h_c = h_u;  h_e = h_u;  h_r = h_u;  h_f = h_u;
yc = R - Sqrt(R * R - c * c);

// cylinder
Point(1) = {0, 0, 0, h_c};
Point(2) = {c, yc, 0, h_e};
Point(3) = {R, R, 0, h_r};
Point(4) = {0, R, 0, h_r};
Circle(1) = {1, 4, 2};  Circle(2) = {2, 4, 3};
Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// half-plane
Point(11) = {0, 0, 0, h_c};
Point(12) = {c, 0, 0, h_e};
Point(13) = {W, 0, 0, h_f};
Point(14) = {W, -D, 0, h_f};
Point(15) = {0, -D, 0, h_f};
Line(11) = {11, 12};  Line(12) = {12, 13};  Line(13) = {13, 14};  Line(14) = {14, 15};  Line(15) = {15, 11};
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};

Physical Surface("cylinder") = {1};
Physical Surface("halfplane") = {2};
Physical Curve("cyl_contact") = {1};
Physical Curve("cyl_top") = {3};
Physical Curve("cyl_axis") = {4};
Physical Curve("hp_top") = {11, 12};
Physical Curve("hp_axis") = {15};
Physical Curve("hp_bottom") = {14};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 1;
