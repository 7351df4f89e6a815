// fused.geo: two unit cubes stacked, one geometric surface between them
// (built-in kernel): their nodes there are shared, the bodies are meshed as
// one. The interface carries two physical tags (6: the lower cube's top,
// 15: the upper cube's bottom), so it appears twice as a boundary face.
h = 0.5;
Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {1, 1, 0, h}; Point(4) = {0, 1, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
lower[] = Extrude {0, 0, 1} { Surface{1}; };
upper[] = Extrude {0, 0, 1} { Surface{lower[0]}; };
Physical Volume(1) = {lower[1]};
Physical Volume(2) = {upper[1]};
Physical Surface(5) = {1};
Physical Surface(6) = {lower[0]};
Physical Surface(15) = {lower[0]};
Physical Surface(16) = {upper[0]};
