// Quarter of a square plate with a central circular hole under uniaxial
// tension (Kirsch), plane stress.  Units: mm.  Hole radius a = 10,
// half-width L = 100.  Symmetry on x = 0 and y = 0; tension on x = L.
a = 10.0;
L = 100.0;
h_hole = 1.5;   // element size at the hole
h_far = 12.0;   // element size at the outer edges

Point(1) = {0, 0, 0, h_hole};
Point(2) = {a, 0, 0, h_hole};
Point(3) = {L, 0, 0, h_far};
Point(4) = {L, L, 0, h_far};
Point(5) = {0, L, 0, h_far};
Point(6) = {0, a, 0, h_hole};

Line(1) = {2, 3};          // bottom symmetry line
Line(2) = {3, 4};          // loaded edge
Line(3) = {4, 5};          // free top edge
Line(4) = {5, 6};          // left symmetry line
Circle(5) = {6, 1, 2};     // the hole

Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};

Physical Surface("plate") = {1};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5};

// 8-node quadrilaterals
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
