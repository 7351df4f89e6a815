// line.geo: a half cylinder (radius 1, axis along y through (0, y, 1), flat
// top z = 1) slice of thickness t on a block [-2,2] x [0,t] x [-2,0]
// (plane strain: u_y = 0 on y = 0 and y = t). Mesh size hc within 0.3 of
// the contact line x = 0, z = 0, growing with slope 0.5 up to 0.25.
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.05, t = 0.1 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
Cylinder(1) = {0, 0, 1, 0, t, 0, 1};
Box(2) = {-1.5, 0, 0, 3, t, 1};
cyl() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Box(3) = {-2, 0, -2, 4, t, 2};
c_top() = Surface In BoundingBox{-1 - e, -e, 1 - e, 1 + e, t + e, 1 + e};
c_y0() = Surface In BoundingBox{-1 - e, -e, -e, 1 + e, e, 1 + e};
c_yt() = Surface In BoundingBox{-1 - e, t - e, -e, 1 + e, t + e, 1 + e};
c_all() = Boundary{ Volume{cyl()}; };
c_curved() = c_all();
c_curved() -= {c_top(), c_y0(), c_yt()};
k_top() = Surface In BoundingBox{-2 - e, -e, -e, 2 + e, t + e, e};
k_bot() = Surface In BoundingBox{-2 - e, -e, -2 - e, 2 + e, t + e, -2 + e};
k_y0() = Surface In BoundingBox{-2 - e, -e, -2 - e, 2 + e, e, e};
k_yt() = Surface In BoundingBox{-2 - e, t - e, -2 - e, 2 + e, t + e, e};
Physical Volume("cylinder", 1) = {cyl()};
Physical Volume("block", 2) = {3};
Physical Surface("cyl_contact", 1) = {c_curved()};
Physical Surface("cyl_top", 2) = {c_top()};
Physical Surface("cyl_sides", 4) = {c_y0(), c_yt()};
Physical Surface("block_top", 11) = {k_top()};
Physical Surface("block_bottom", 12) = {k_bot()};
Physical Surface("block_sides", 14) = {k_y0(), k_yt()};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g + 0.5 * Max(Sqrt(x^2 + z^2) - 0.3, 0), 0.25)", hc);
Background Field = 1;
