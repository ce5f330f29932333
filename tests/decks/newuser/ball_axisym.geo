// A rigid ball (R = 10 mm) on a rough aluminium half-space, axisymmetric Q8: the deck ball_axisym.dat
// (meshed by gmsh -2 -format msh41 ball_axisym.geo -o ball_axisym.msh)
lc = 2.0; lf = 0.2;
Point(1) = {0, -15, 0, lc};
Point(2) = {20, -15, 0, lc};
Point(3) = {20, 0, 0, lc};
Point(4) = {3, 0, 0, lf};
Point(5) = {0, 0, 0, lf};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,5}; Line(5) = {5,1};
Curve Loop(1) = {1,2,3,4,5}; Plane Surface(1) = {1};
Physical Surface("block") = {1};
Physical Curve("base") = {1};
Physical Curve("axis") = {5};
Physical Curve("top") = {3,4};
Mesh.RecombineAll = 1; Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
