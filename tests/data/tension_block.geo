// Block 0.1 x 0.05 x 0.05 m (long axis x), unstructured tetrahedra not aligned with any
// plane normal to x: a crack normal to the load must run through inclined faces.
// Groups: block, left (x = 0), right (x = 0.1), ymin, zmin.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.05, 0.05};
Mesh.MeshSizeMax = 0.011;
Mesh.MeshSizeMin = 0.011;
Physical Volume("block") = {1};
Physical Surface("left") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 1e-6, 0.050001, 0.050001};
Physical Surface("right") = Surface In BoundingBox{0.099999, -1e-6, -1e-6, 0.100001, 0.050001, 0.050001};
Physical Surface("ymin") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 0.100001, 1e-6, 0.050001};
Physical Surface("zmin") = Surface In BoundingBox{-1e-6, -1e-6, -1e-6, 0.100001, 0.050001, 1e-6};
