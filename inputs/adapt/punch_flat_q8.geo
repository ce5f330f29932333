// The flat punch of punch_flat.geo meshed with 8-node quadrilaterals (docs/adaptivity.md).  A
// quadratic mesh must be all quadrilaterals (the program has no 6-node triangle): full-quad
// blossom recombination, also on the adaptive meshes made from this file.
Include "punch_flat.geo";
Mesh.RecombinationAlgorithm = 3;
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
