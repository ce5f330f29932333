// The paper's example 5.2 (Altenbach & Buczkowski; inputs/sphere_5_2.dat) as a .geo for the
// remeshing route of tools/adapt.py (docs/adaptivity.md, "The example decks"): an elastic
// hemisphere R = 15 mm, flat face up, on an elastic half-space (a quarter disc of radius
// 120 mm, its outer boundary fixed), axisymmetric (x = r, y = z), both E = 21000, nu = 0.3.
// The same bodies as the card deck; the two are meshed independently (the deck pairs them with
// MATCHING SEGMENT, not node to node).  4-node quadrilaterals.  A user's coarse start mesh:
// one size at the contact (the Hertz radius a_H = 0.5799 mm at P = 200 N), 3 mm in the sphere,
// 30 mm at the half-space's far boundary -- nobody's grading study.
R = 15.0;  rho = 120.0;  aH = 0.5799;  c = 3 * aH;
h_c = aH;         // at the first contact point and at r = 3 a_H
h_r = 3.0;        // the sphere's equator and flat face
h_f = 30.0;       // the half-space's far boundary
yc = R - Sqrt(R * R - c * c);

// hemisphere: the quarter disc of centre (0, R) below its flat face y = R
Point(1) = {0, 0, 0, h_c};
Point(2) = {c, yc, 0, h_c};
Point(3) = {R, R, 0, h_r};
Point(4) = {0, R, 0, h_r};
Circle(1) = {1, 4, 2};  Circle(2) = {2, 4, 3};
Line(3) = {3, 4};  Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};

// half-space: the quarter disc of centre (0, 0) and radius rho below y = 0
Point(11) = {0, 0, 0, h_c};
Point(12) = {c, 0, 0, h_c};
Point(13) = {rho, 0, 0, h_f};
Point(14) = {0, -rho, 0, h_f};
Line(11) = {11, 12};  Line(12) = {12, 13};  Circle(13) = {13, 11, 14};  Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};

Physical Surface("sphere") = {1};
Physical Surface("halfspace") = {2};
Physical Curve("sph_contact") = {1, 2};
Physical Curve("sph_top") = {3};
Physical Curve("sph_axis") = {4};
Physical Curve("hs_top") = {11, 12};
Physical Curve("hs_outer") = {13};
Physical Curve("hs_axis") = {14};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 1;
