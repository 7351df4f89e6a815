// corner.geo: a unit cube in the inside (concave) corner of an L-shaped
// body: floor [-0.5,1.5] x [0,1] x [-0.5,0] and wall [1,1.5] x [0,1] x
// [0,1.5], fused; the cube [0,1]^3 touches the floor (z = 0) and the wall
// (x = 1), independent meshes; the cube's edge x = 1, z = 0 lies on the
// corner line.
//   gmsh -3 -format msh2 -setnumber hm 0.25 -setnumber hs 0.2 corner.geo
SetFactory("OpenCASCADE");
DefineConstant[ hm = 0.25, hs = 0.2 ];   // mesh sizes of the L body and of the cube
Mesh.MshFileVersion = 2.2;
e = 1e-6;

Box(1) = {-0.5, 0, -0.5, 2, 1, 0.5};
Box(2) = {1, 0, 0, 0.5, 1, 1.5};
BooleanUnion(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
Box(4) = {0, 0, 0, 1, 1, 1};
cube() = Boundary{Volume{4};};
lbody() = Boundary{Volume{3};};
cubeC() = Unique(Abs(Boundary{Surface{cube()};}));
lbodyC() = Unique(Abs(Boundary{Surface{lbody()};}));

Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Field[1] = MathEval; Field[1].F = Sprintf("%g", hm);
Field[2] = Restrict; Field[2].InField = 1; Field[2].VolumesList = {3}; Field[2].SurfacesList = {lbody()}; Field[2].CurvesList = {lbodyC()};
Field[3] = MathEval; Field[3].F = Sprintf("%g", hs);
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {4}; Field[4].SurfacesList = {cube()}; Field[4].CurvesList = {cubeC()};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;

floorTop() = Surface In BoundingBox{-0.5 - e, -e, -e, 1 + e, 1 + e, e};
floorTop() -= cube();
wallFace() = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, 1.5 + e};
wallFace() -= cube();
lRest() = lbody();
lRest() -= floorTop();
lRest() -= wallFace();
cubeBottom() = Surface In BoundingBox{-e, -e, -e, 1 + e, 1 + e, e};
cubeBottom() -= floorTop();
cubeRight() = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 1 + e, 1 + e};
cubeRight() -= wallFace();
cubeTop() = Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e};
cubeTop() -= wallFace();
cubeLeft() = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
cubeY0() = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 1 + e};
cubeY1() = Surface In BoundingBox{-e, 1 - e, -e, 1 + e, 1 + e, 1 + e};

Physical Volume("lbody", 1) = {3};
Physical Volume("cube", 2) = {4};
Physical Surface("floor_top", 11) = {floorTop()};
Physical Surface("wall_face", 12) = {wallFace()};
Physical Surface("lbody_rest", 13) = {lRest()};
Physical Surface("cube_bottom", 21) = {cubeBottom()};
Physical Surface("cube_right", 22) = {cubeRight()};
Physical Surface("cube_top", 23) = {cubeTop()};
Physical Surface("cube_left", 24) = {cubeLeft()};
Physical Surface("cube_y0", 25) = {cubeY0()};
Physical Surface("cube_y1", 26) = {cubeY1()};
