// ball_block.geo: a ball of radius r (centre (0, 0, r + gap0)) above the
// block [-0.5, 0.5]^2 x [-0.3, 0], independent meshes; the whole sphere is
// one surface (label 1), the block's faces 2 (top) and 3 (the others).
//   gmsh -3 -format msh2 -setnumber h 0.05 -setnumber gap0 0.01 ball_block.geo
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.05, r = 0.2, gap0 = 0.01 ];  // mesh size, radius, initial gap
Mesh.MshFileVersion = 2.2;

Sphere(1) = {0, 0, r + gap0, r};
Box(2) = {-0.5, -0.5, -0.3, 1, 1, 0.3};
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;
e = 1e-6;
top() = Surface In BoundingBox{-0.5 - e, -0.5 - e, -e, 0.5 + e, 0.5 + e, e};
rest() = Boundary{Volume{2};};
rest() -= top();
Physical Volume("ball", 1) = {1};
Physical Volume("block", 2) = {2};
Physical Surface("sphere", 1) = Boundary{Volume{1};};
Physical Surface("top", 2) = {top()};
Physical Surface("block", 3) = {rest()};
