// blocks.geo: two stacked unit cubes with independent (non-matching) meshes
// on their common face z = 1.  Lower block [0,1]^3, upper block
// [xshift, 1 + xshift] x [0,1] x [1 + gap0, 2 + gap0].
//   gmsh -3 -format msh2 -setnumber h1 0.25 -setnumber h2 0.2 blocks.geo
SetFactory("OpenCASCADE");
DefineConstant[ h1 = 0.25, h2 = 0.2, gap0 = 0, xshift = 0 ];  // mesh sizes of the lower and upper block;
                                                  // initial gap between them (< 0: overlap); shift of the upper one
Mesh.MshFileVersion = 2.2;

Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {xshift, 0, 1 + gap0, 1, 1, 1};
// OpenCASCADE box faces: x=min, x=max, y=min, y=max, z=min, z=max
// Per-body sizes through restricted fields: point sizes would be shared by
// the coincident corners of the two boxes and make the interface match.
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

Physical Volume("lower", 1) = {1};
Physical Volume("upper", 2) = {2};
Physical Surface("lower_x0", 11) = {1};
Physical Surface("lower_x1", 12) = {2};
Physical Surface("lower_y0", 13) = {3};
Physical Surface("lower_y1", 14) = {4};
Physical Surface("lower_bottom", 15) = {5};
Physical Surface("lower_top", 16) = {6};
Physical Surface("upper_x0", 21) = {7};
Physical Surface("upper_x1", 22) = {8};
Physical Surface("upper_y0", 23) = {9};
Physical Surface("upper_y1", 24) = {10};
Physical Surface("upper_bottom", 25) = {11};
Physical Surface("upper_top", 26) = {12};
