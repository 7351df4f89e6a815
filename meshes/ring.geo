// ring.geo: half (x >= 0) of a ring slice (radii ri and ro about the y
// axis, thickness t along y) between two plates [0, 1.5] x [0, t] x 0.3, a
// gap apart above and below. The ring is cut at z = 0 into two halves
// meshed as one (shared nodes). Labels: the ring's inner surface above z =
// 0, 1, and below, 2; its outer surface above, 3, and below, 4; the faces
// y = 0 and y = t of every body, 5; the symmetry plane x = 0 of every
// body, 6; the top plate's bottom 11 and top 12, the bottom plate's top 13
// and bottom 14; the plates' far ends 17. Mesh size h.
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.05, ri = 0.4, ro = 1, t = 0.05, gap = 0.005 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
e = 1e-6;
Cylinder(1) = {0, 0, 0, 0, t, 0, ro};
Cylinder(2) = {0, 0, 0, 0, t, 0, ri};
r() = BooleanDifference{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(3) = {0, 0, -2, 2, t, 4};
rh() = BooleanIntersection{ Volume{r()}; Delete; }{ Volume{3}; Delete; };
Rectangle(10) = {0, -1, 0, 2, t + 2};
rf() = BooleanFragments{ Volume{rh()}; Delete; }{ Surface{10}; Delete; };
Box(4) = {0, 0, ro + gap, 1.5, t, 0.3};
Box(5) = {0, 0, -ro - gap - 0.3, 1.5, t, 0.3};
in_up() = Surface In BoundingBox{-e, -e, -e, ri + e, t + e, ri + e};
in_lo() = Surface In BoundingBox{-e, -e, -ri - e, ri + e, t + e, e};
sym() = Surface In BoundingBox{-e, -e, -ro - gap - 0.3 - e, e, t + e, ro + gap + 0.3 + e};
sides() = Surface In BoundingBox{-e, -e, -ro - gap - 0.3 - e, 1.5 + e, e, ro + gap + 0.3 + e};
sides() += Surface In BoundingBox{-e, t - e, -ro - gap - 0.3 - e, 1.5 + e, t + e, ro + gap + 0.3 + e};
mid() = Surface In BoundingBox{ri - e, -e, -e, ro + e, t + e, e};
out_up() = Surface In BoundingBox{-e, -e, -e, ro + e, t + e, ro + e};
out_up() -= {in_up(), sym(), sides(), mid()};
out_lo() = Surface In BoundingBox{-e, -e, -ro - e, ro + e, t + e, e};
out_lo() -= {in_lo(), sym(), sides(), mid()};
p_bot() = Surface In BoundingBox{-e, -e, ro + gap - e, 1.5 + e, t + e, ro + gap + e};
p_top() = Surface In BoundingBox{-e, -e, ro + gap + 0.3 - e, 1.5 + e, t + e, ro + gap + 0.3 + e};
q_top() = Surface In BoundingBox{-e, -e, -ro - gap - e, 1.5 + e, t + e, -ro - gap + e};
q_bot() = Surface In BoundingBox{-e, -e, -ro - gap - 0.3 - e, 1.5 + e, t + e, -ro - gap - 0.3 + e};
ends() = Surface In BoundingBox{1.5 - e, -e, -ro - gap - 0.3 - e, 1.5 + e, t + e, ro + gap + 0.3 + e};
Physical Volume("ring", 1) = {rf()};
Physical Volume("top_plate", 2) = {4};
Physical Volume("bottom_plate", 3) = {5};
Physical Surface("inner_up", 1) = {in_up()};
Physical Surface("inner_low", 2) = {in_lo()};
Physical Surface("outer_up", 3) = {out_up()};
Physical Surface("outer_low", 4) = {out_lo()};
Physical Surface("sides", 5) = {sides()};
Physical Surface("symmetry", 6) = {sym()};
Physical Surface("top_plate_bottom", 11) = {p_bot()};
Physical Surface("top_plate_top", 12) = {p_top()};
Physical Surface("bottom_plate_top", 13) = {q_top()};
Physical Surface("bottom_plate_bottom", 14) = {q_bot()};
Physical Surface("plate_ends", 17) = {ends()};
