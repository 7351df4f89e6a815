// pad.geo: a pad resting on a wider base (independent meshes on their
// common plane z = 0.5).  Base [0,1] x [0,1] x [0,0.5], pad [0.25,0.75] x
// [0.3,0.7] x [0.5,0.9]; the pad's face x = 0.25 has its own label, to be
// pushed along x.
//   gmsh -3 -format msh2 -setnumber hb 0.1 -setnumber hp 0.05 pad.geo
SetFactory("OpenCASCADE");
DefineConstant[ hb = 0.2, hp = 0.1 ];   // mesh sizes of base and pad
Mesh.MshFileVersion = 2.2;

Box(1) = {0, 0, 0, 1, 1, 0.5};
Box(2) = {0.25, 0.3, 0.5, 0.5, 0.4, 0.4};
// per-body sizes through restricted fields (as in sliding.geo)
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Field[1] = MathEval; Field[1].F = Sprintf("%g", hb);
Field[2] = Restrict; Field[2].InField = 1;
Field[2].VolumesList = {1}; Field[2].SurfacesList = {1:6}; Field[2].CurvesList = {1:12};
Field[3] = MathEval; Field[3].F = Sprintf("%g", hp);
Field[4] = Restrict; Field[4].InField = 3;
Field[4].VolumesList = {2}; Field[4].SurfacesList = {7:12}; Field[4].CurvesList = {13:24};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;

// OpenCASCADE box faces: x=min, x=max, y=min, y=max, z=min, z=max
Physical Volume("base", 1) = {1};
Physical Volume("pad", 2) = {2};
Physical Surface("base_bottom", 5) = {5};
Physical Surface("base_top", 6) = {6};
Physical Surface("pad_x0", 7) = {7};
Physical Surface("pad_bottom", 11) = {11};
Physical Surface("pad_top", 12) = {12};
