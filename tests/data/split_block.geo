// A cube pre-split into four pieces with small gaps: four disjoint volumes in one group.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.1, 0.2};
Box(2) = {0.102, 0, 0, 0.1, 0.1, 0.2};
Box(3) = {0, 0.102, 0, 0.1, 0.1, 0.2};
Box(4) = {0.102, 0.102, 0, 0.1, 0.1, 0.2};
Mesh.MeshSizeMax = 0.05;
Physical Volume("pieces") = {1, 2, 3, 4};
