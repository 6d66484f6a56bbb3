// Cantilever 1.0 x 0.1 x 0.1 m, structured hexahedra (built-in kernel, extruded layers).
// Physical groups: beam (volume), clamp (x = 0 face), tip (x = L face).
L = 1.0; H = 0.1; W = 0.1;
nx = 40; ny = 4; nz = 4;
Point(1) = {0, 0, 0, 1};
l[] = Extrude{0, H, 0}{ Point{1}; Layers{ny}; };
s[] = Extrude{0, 0, W}{ Line{l[1]}; Layers{nz}; Recombine; };
v[] = Extrude{L, 0, 0}{ Surface{s[1]}; Layers{nx}; Recombine; };
Physical Volume("beam") = {v[1]};
Physical Surface("clamp") = {s[1]};
Physical Surface("tip") = {v[0]};
