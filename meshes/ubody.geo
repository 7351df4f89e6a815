// ubody.geo: a U-shaped body, slice of thickness t along y: a base
// [0, 0.5] x [0, t] x [0, 0.2] and two arms [0, 0.2] and [0.3, 0.5] in x up
// to z = 1, a slot 0.1 wide between them. Labels: the slot's faces, left
// arm 1 (x = 0.2), right arm 2 (x = 0.3), bottom 3 (z = 0.2); the arms' tops
// 4 (left) and 5 (right); the base's bottom 6; the faces y = 0 and y = t 7;
// the outer faces 8. Mesh size h.
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.05, t = 0.2 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
e = 1e-6;
Box(1) = {0, 0, 0, 0.5, t, 0.2};
Box(2) = {0, 0, 0.2, 0.2, t, 0.8};
Box(3) = {0.3, 0, 0.2, 0.2, t, 0.8};
u() = BooleanUnion{ Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
s_left() = Surface In BoundingBox{0.2 - e, -e, 0.2 - e, 0.2 + e, t + e, 1 + e};
s_right() = Surface In BoundingBox{0.3 - e, -e, 0.2 - e, 0.3 + e, t + e, 1 + e};
s_bot() = Surface In BoundingBox{0.2 - e, -e, 0.2 - e, 0.3 + e, t + e, 0.2 + e};
top_l() = Surface In BoundingBox{-e, -e, 1 - e, 0.2 + e, t + e, 1 + e};
top_r() = Surface In BoundingBox{0.3 - e, -e, 1 - e, 0.5 + e, t + e, 1 + e};
bottom() = Surface In BoundingBox{-e, -e, -e, 0.5 + e, t + e, e};
y0() = Surface In BoundingBox{-e, -e, -e, 0.5 + e, e, 1 + e};
yt() = Surface In BoundingBox{-e, t - e, -e, 0.5 + e, t + e, 1 + e};
rest() = Boundary{ Volume{u()}; };
rest() -= {s_left(), s_right(), s_bot(), top_l(), top_r(), bottom(), y0(), yt()};
Physical Volume("body", 1) = {u()};
Physical Surface("slot_left", 1) = {s_left()};
Physical Surface("slot_right", 2) = {s_right()};
Physical Surface("slot_bottom", 3) = {s_bot()};
Physical Surface("top_left", 4) = {top_l()};
Physical Surface("top_right", 5) = {top_r()};
Physical Surface("bottom", 6) = {bottom()};
Physical Surface("sides", 7) = {y0(), yt()};
Physical Surface("outer", 8) = {rest()};
