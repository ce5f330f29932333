// The Hertz model of hertz_adapt.geo meshed with 8-node quadrilaterals: the reference solution
// (an overkill mesh of the same bodies, refined adaptively to an energy estimate of 0.2 %) against
// which tools/adapt_validation.py measures the true energy-norm error of the Q4 meshes of
// hertz_adapt and hertz_uniform (docs/adaptivity.md, "True energy error").  Quadratic edges put
// the midside nodes on the cylinder's circle.
Include "hertz_adapt.geo";
Mesh.RecombinationAlgorithm = 3;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
