// stack.geo: three stacked blocks with independent (non-matching) meshes:
// a base [0,1.2] x [0,1] x [0,t], a middle block [0.2,1.0] x [0.1,0.9] x
// [t,2t] and a top block [0.3,0.9] x [0.2,0.8] x [2t,3t].
//   gmsh -3 -format msh2 -setnumber h 0.1 stack.geo
SetFactory("OpenCASCADE");
DefineConstant[ h = 0.1, t = 0.3 ];  // mesh size (the middle block's is 0.8 h, the top's 1.2 h); thickness
Mesh.MshFileVersion = 2.2;

Box(1) = {0, 0, 0, 1.2, 1, t};
Box(2) = {0.2, 0.1, t, 0.8, 0.8, t};
Box(3) = {0.3, 0.2, 2 * t, 0.6, 0.6, t};
// per-body sizes through restricted fields (as in blocks.geo)
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Field[1] = MathEval; Field[1].F = Sprintf("%g", h);
Field[2] = Restrict; Field[2].InField = 1;
Field[2].VolumesList = {1}; Field[2].SurfacesList = {1:6}; Field[2].CurvesList = {1:12};
Field[3] = MathEval; Field[3].F = Sprintf("%g", 0.8 * h);
Field[4] = Restrict; Field[4].InField = 3;
Field[4].VolumesList = {2}; Field[4].SurfacesList = {7:12}; Field[4].CurvesList = {13:24};
Field[5] = MathEval; Field[5].F = Sprintf("%g", 1.2 * h);
Field[6] = Restrict; Field[6].InField = 5;
Field[6].VolumesList = {3}; Field[6].SurfacesList = {13:18}; Field[6].CurvesList = {25:36};
Field[7] = Min; Field[7].FieldsList = {2, 4, 6};
Background Field = 7;

// OpenCASCADE box faces: x=min, x=max, y=min, y=max, z=min, z=max
Physical Volume("base", 1) = {1};
Physical Volume("middle", 2) = {2};
Physical Volume("top", 3) = {3};
Physical Surface("base_bottom", 11) = {5};
Physical Surface("base_top", 12) = {6};
Physical Surface("base_sides", 13) = {1, 2, 3, 4};
Physical Surface("middle_bottom", 21) = {11};
Physical Surface("middle_top", 22) = {12};
Physical Surface("middle_sides", 23) = {7, 8, 9, 10};
Physical Surface("top_bottom", 31) = {17};
Physical Surface("top_top", 32) = {18};
Physical Surface("top_sides", 33) = {13, 14, 15, 16};
