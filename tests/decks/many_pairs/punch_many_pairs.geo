// Many contact pairs on a small mesh: the rough punch of tools/bench_scaling.py with 401 pairs,
// about 6 400 equations (made by its make_mesh with 400 contact segments and 6 000 equations).
a = 50.0; H = 50.0; L = 120.0; D = 120.0;
hc = a/400; g = 0.46928582; hmax = 20.0;
// the punch
Point(1) = {0, 0, 0}; Point(2) = {a, 0, 0}; Point(3) = {a, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
// the foundation: under the punch and beside it (its own points: the bodies share no node)
Point(11) = {0, 0, 0}; Point(12) = {a, 0, 0}; Point(13) = {L, 0, 0};
Point(14) = {L, -D, 0}; Point(15) = {a, -D, 0}; Point(16) = {0, -D, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 15};
Line(15) = {15, 16}; Line(16) = {16, 11}; Line(17) = {12, 15};
Curve Loop(2) = {11, 17, 15, 16}; Plane Surface(2) = {2};
Curve Loop(3) = {12, 13, 14, -17}; Plane Surface(3) = {3};
// both contact lines: 400 equal segments, so that their nodes pair one to one
Transfinite Curve{1, 11} = 400 + 1;
Field[1] = Distance; Field[1].CurvesList = {1, 11}; Field[1].NumPointsPerCurve = 400;
Field[2] = MathEval; Field[2].F = Sprintf("Min(%g, %g + %g*F1)", hmax, hc, g);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6; Mesh.RecombineAll = 1; Mesh.RecombinationAlgorithm = 1;
Physical Surface("punch") = {1};
Physical Surface("foundation") = {2, 3};
Physical Curve("contact_a") = {1};
Physical Curve("contact_b") = {11};
Physical Curve("top") = {3};
Physical Curve("symmetry") = {4, 16};
Physical Curve("base") = {14, 15};
