// The paper's example 5.3 (Altenbach & Buczkowski; inputs/cylinder_5_3.dat) as a .geo for the
// remeshing route of tools/adapt.py (docs/adaptivity.md, "The example decks"): a rigid hollow
// cylinder, R_I = 25 mm, R_A = 50 mm, on an elastic half-space (a quarter disc of radius
// 500 mm, its outer boundary fixed), axisymmetric (x = r, y = z), E = 40000, nu = 0.3.  The
// cylinder is the deck's rigid flat profile; the half-space's ring R_I <= r <= R_A is its
// contact surface.  8-node quadrilaterals.  A user's coarse start mesh: 5 mm on the ring,
// 100 mm at the far boundary -- no grading towards the ring's edges, which the hand model has.
RI = 25.0;  RA = 50.0;  rho = 500.0;
h_r = 5.0;        // on the ring
h_f = 100.0;      // the far boundary
Point(1) = {0, 0, 0, h_r};
Point(2) = {RI, 0, 0, h_r};
Point(3) = {RA, 0, 0, h_r};
Point(4) = {rho, 0, 0, h_f};
Point(5) = {0, -rho, 0, h_f};
Line(1) = {1, 2};  Line(2) = {2, 3};  Line(3) = {3, 4};  Circle(4) = {4, 1, 5};  Line(5) = {5, 1};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Surface("halfspace") = {1};
Physical Curve("hs_ring") = {2};
Physical Curve("hs_outer") = {4};

Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
