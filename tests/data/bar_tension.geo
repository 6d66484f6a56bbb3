// Bar 0.2 x 0.02 x 0.02 m, 20 x 2 x 2 hexahedra; groups bar, left (x = 0), right (x = L).
Point(1) = {0, 0, 0, 1};
l[] = Extrude{0, 0.02, 0}{ Point{1}; Layers{2}; };
s[] = Extrude{0, 0, 0.02}{ Line{l[1]}; Layers{2}; Recombine; };
v[] = Extrude{0.2, 0, 0}{ Surface{s[1]}; Layers{20}; Recombine; };
Physical Volume("bar") = {v[1]};
Physical Surface("left") = {s[1]};
Physical Surface("right") = {v[0]};
