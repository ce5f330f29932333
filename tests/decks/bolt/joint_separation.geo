// The joint of inputs/bolt_joint.geo with doubled element sizes (the test deck
// joint_separation.dat); meshed into joint_separation.msh by gmsh -2 -format msh41.
// An axisymmetric single-bolt joint (x = r, y = z; mm): an M10-like bolt on the axis -- head,
// shank and nut as one body, the nut modelled as an enlarged end of the shank -- through two
// steel plates 10 mm thick with a hole of radius 5.5 (clearance 0.5 mm), outer radius 30.
// The bolt's shank is cut at z = 5 by the physical curve "cut" (the pretension section).
lb = 3.0;    // element size in the bolt
lp = 3.0;   // element size in the plates near the hole (coarser outwards)
// bolt: nut z -8..0 (r 0..8), shank z 0..20 (r 0..5), head z 20..26 (r 0..8)
Point(1) = {0, -8, 0, lb}; Point(2) = {8, -8, 0, lb}; Point(3) = {8, 0, 0, lb};
Point(4) = {5, 0, 0, lb}; Point(5) = {5, 5, 0, lb}; Point(6) = {5, 20, 0, lb};
Point(7) = {8, 20, 0, lb}; Point(8) = {8, 26, 0, lb}; Point(9) = {0, 26, 0, lb};
Point(10) = {0, 5, 0, lb};
Point(21) = {5.5, 20, 0, lb}; Point(22) = {5.5, 0, 0, lb};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 22}; Line(23) = {22, 4}; Line(4) = {4, 5}; Line(5) = {5, 10};
Line(6) = {10, 1};
Line(7) = {5, 6}; Line(24) = {6, 21}; Line(8) = {21, 7}; Line(9) = {7, 8}; Line(10) = {8, 9}; Line(11) = {9, 10};
Curve Loop(1) = {1, 2, 3, 23, 4, 5, 6}; Plane Surface(1) = {1};      // nut and lower shank
Curve Loop(2) = {-5, 7, 24, 8, 9, 10, 11}; Plane Surface(2) = {2};   // upper shank and head
// plate 1 (upper) z 10..20, plate 2 (lower) z 0..10, r 5.5..30
Point(11) = {5.5, 10, 0, lp}; Point(12) = {30, 10, 0, 6.0}; Point(13) = {30, 20, 0, 6.0};
Point(14) = {5.5, 20, 0, lp};
Point(15) = {5.5, 0, 0, lp}; Point(16) = {30, 0, 0, 6.0}; Point(17) = {30, 10, 0, 6.0};
Point(18) = {5.5, 10, 0, lp};
Point(19) = {14, 20, 0, 3.0}; Point(20) = {14, 0, 0, 3.0};
Point(23) = {10, 20, 0, 3.0}; Point(24) = {10, 0, 0, 3.0};
Line(12) = {11, 12}; Line(13) = {12, 13}; Line(14) = {13, 19}; Line(25) = {19, 23}; Line(15) = {23, 14};
Line(16) = {14, 11};
Line(17) = {15, 24}; Line(26) = {24, 20}; Line(18) = {20, 16}; Line(19) = {16, 17}; Line(20) = {17, 18}; Line(21) = {18, 15};
Curve Loop(3) = {12, 13, 14, 25, 15, 16}; Plane Surface(3) = {3};
Curve Loop(4) = {17, 26, 18, 19, 20, 21}; Plane Surface(4) = {4};
Recombine Surface{1, 2, 3, 4};
Mesh.Algorithm = 6; Mesh.RecombineAll = 1; Mesh.SubdivisionAlgorithm = 1;
Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;
Physical Surface("bolt") = {1, 2};
Physical Surface("plate1") = {3};
Physical Surface("plate2") = {4};
Physical Curve("cut") = {5};
Physical Curve("head_face") = {8};       // under the head, r 5.5..8 at z = 20 (over the plate)
Physical Curve("nut_face") = {3};        // on the nut, r 5.5..8 at z = 0
Physical Curve("plate1_top") = {14, 25, 15};
Physical Curve("plate1_bottom") = {12};
Physical Curve("plate2_top") = {20};
Physical Curve("plate2_bottom") = {17, 26, 18};
Physical Curve("load") = {25};           // r 10..14 at z = 20: the service load pulls plate 1 up
Physical Curve("support") = {26};        // r 10..14 at z = 0: plate 2 held there
