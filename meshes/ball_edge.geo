// ball_edge.geo: a small hemisphere (radius r) whose dome touches the edge
// x = 1, z = 1 of the unit cube [0,1]^3 at (1, 0.5, 1), its axis along the
// bisector (-1, 0, -1) / sqrt(2) of the edge; independent meshes, the cube
// refined near the touching point.
//   gmsh -3 -format msh2 -setnumber r 0.2 -setnumber hs 0.04 ball_edge.geo
SetFactory("OpenCASCADE");
DefineConstant[ r = 0.2, hs = 0.04, hb = 0.2, he = 0.04, gap0 = 0 ];  // radius, ball size, cube sizes
                                                                   // far and near the edge, gap along the axis
Mesh.MshFileVersion = 2.2;
e = 1e-6;

Box(1) = {0, 0, 0, 1, 1, 1};
Sphere(2) = {0, 0, 0, r};
Box(3) = {-2 * r, -2 * r, 0, 4 * r, 4 * r, 2 * r};
BooleanDifference(4) = {Volume{2}; Delete;}{Volume{3}; Delete;};   // the half z <= 0, flat face on z = 0
flat() = Surface In BoundingBox{-r - e, -r - e, -e, r + e, r + e, e};
dome() = Boundary{Volume{4};};
dome() -= flat();
Rotate {{0, 1, 0}, {0, 0, 0}, Pi / 4} { Volume{4}; }
c = 1 + (r + gap0) / Sqrt(2);
Translate {c, 0.5, c} { Volume{4}; }

cubeS() = Boundary{Volume{1};};
ballS() = Boundary{Volume{4};};
cubeC() = Unique(Abs(Boundary{Surface{cubeS()};}));
ballC() = Unique(Abs(Boundary{Surface{ballS()};}));
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Field[1] = MathEval;
Field[1].F = Sprintf("%g + (%g - %g) * Min(1, Sqrt((x - 1)^2 + (y - 0.5)^2 + (z - 1)^2) / 0.5)", he, hb, he);
Field[2] = Restrict; Field[2].InField = 1; Field[2].VolumesList = {1}; Field[2].SurfacesList = {cubeS()};
Field[2].CurvesList = {cubeC()};
Field[3] = MathEval; Field[3].F = Sprintf("%g", hs);
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {4}; Field[4].SurfacesList = {ballS()};
Field[4].CurvesList = {ballC()};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;

Physical Volume("cube", 1) = {1};
Physical Volume("ball", 2) = {4};
Physical Surface("cube_bottom", 11) = {Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e}};
Physical Surface("cube_top", 12) = {Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e}};
Physical Surface("cube_x1", 13) = {Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, 1 + e}};
cubeRest() = cubeS();
cubeRest() -= {Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e}};
cubeRest() -= {Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e}};
cubeRest() -= {Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, 1 + e}};
Physical Surface("cube_rest", 14) = {cubeRest()};
Physical Surface("ball_dome", 21) = {dome()};
Physical Surface("ball_flat", 22) = {flat()};
