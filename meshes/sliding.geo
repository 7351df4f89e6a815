// sliding.geo: a block resting on a larger plate (independent meshes on
// their common plane z = t1).  Plate [0,2] x [0,1] x [0,t1], block
// [0.4,1.0] x [0.2,0.8] x [t1, t1 + t2]: it can slide by -0.4 .. +1 in x
// and stay on the plate.
//   gmsh -3 -format msh2 -setnumber h1 0.1 -setnumber h2 0.1 sliding.geo
SetFactory("OpenCASCADE");
DefineConstant[ h1 = 0.1, h2 = 0.1, t1 = 0.4, t2 = 0.4 ];  // mesh sizes of plate and block; thicknesses
Mesh.MshFileVersion = 2.2;

Box(1) = {0, 0, 0, 2, 1, t1};
Box(2) = {0.4, 0.2, t1, 0.6, 0.6, t2};
// per-body sizes through restricted fields (as in blocks.geo)
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Field[1] = MathEval; Field[1].F = Sprintf("%g", h1);
Field[2] = Restrict; Field[2].InField = 1;
Field[2].VolumesList = {1}; Field[2].SurfacesList = {1:6}; Field[2].CurvesList = {1:12};
Field[3] = MathEval; Field[3].F = Sprintf("%g", h2);
Field[4] = Restrict; Field[4].InField = 3;
Field[4].VolumesList = {2}; Field[4].SurfacesList = {7:12}; Field[4].CurvesList = {13:24};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;

// OpenCASCADE box faces: x=min, x=max, y=min, y=max, z=min, z=max
Physical Volume("plate", 1) = {1};
Physical Volume("block", 2) = {2};
Physical Surface("plate_bottom", 11) = {5};
Physical Surface("plate_top", 12) = {6};
Physical Surface("plate_sides", 13) = {1, 2, 3, 4};
Physical Surface("block_bottom", 21) = {11};
Physical Surface("block_top", 22) = {12};
Physical Surface("block_sides", 23) = {7, 8, 9, 10};
