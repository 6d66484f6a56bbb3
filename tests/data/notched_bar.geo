// Bar 0.2 x 0.04 x 0.04 m with two 10 mm deep, 2 mm wide notches at mid-length (from
// y = 0 and from y = 0.04: a symmetric double-edge-notched bar), split into a central band
// (x in [0.07, 0.13], where cracks may form) and two ends.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.07, 0.04, 0.04};
Box(2) = {0.07, 0, 0, 0.06, 0.04, 0.04};
Box(3) = {0.13, 0, 0, 0.07, 0.04, 0.04};
Box(4) = {0.099, -0.01, -0.01, 0.002, 0.02, 0.06};
Box(6) = {0.099, 0.03, -0.01, 0.002, 0.02, 0.06};
BooleanDifference(5) = { Volume{2}; Delete; }{ Volume{4,6}; Delete; };
Coherence;
Mesh.MeshSizeMax = 0.008;
Physical Volume("ends") = {1, 3};
Physical Volume("band") = {5};
Physical Surface("left") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, 0.040001, 0.040001};
Physical Surface("right") = Surface In BoundingBox{0.199999, -1e-6, -1e-6, 0.200001, 0.040001, 0.040001};
