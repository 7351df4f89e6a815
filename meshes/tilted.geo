// tilted.geo: two blocks over the unit square, [0,1]^2, meeting on the
// tilted plane z = 1 + t (x - 1/2) with independent (non-matching) meshes
// there: the lower block from z = 0 up to the plane, the upper one from the
// plane up to z = 2.  Sizes h1 (lower) and h2 (upper).
// Face labels 10 b + k, b = 1 lower, 2 upper; k = 1 x = 0, 2 x = 1, 3 y = 0,
// 4 y = 1, 5 the flat face (z = 0 below, z = 2 above), 6 the tilted one.
//   gmsh -3 -format msh2 -setnumber h1 0.25 -setnumber h2 0.2 -setnumber t 0.4 tilted.geo
SetFactory("OpenCASCADE");
DefineConstant[ h1 = 0.25, h2 = 0.2, t = 0.4 ];
Mesh.MshFileVersion = 2.2;
a = Atan(t);
Box(1) = {0, 0, 0, 1, 1, 2};
Box(2) = {-2, -2, 1, 5, 5, 4};           // the half-space above the plane, before its rotation
Rotate {{0, 1, 0}, {0.5, 0.5, 1}, -a} { Volume{2}; }
BooleanDifference(3) = { Volume{1}; }{ Volume{2}; };      // lower
Box(4) = {0, 0, 0, 1, 1, 2};
Box(5) = {-2, -2, 1, 5, 5, 4};
Rotate {{0, 1, 0}, {0.5, 0.5, 1}, -a} { Volume{5}; }
BooleanIntersection(6) = { Volume{4}; Delete; }{ Volume{5}; Delete; };   // upper
Delete { Volume{1}; Volume{2}; }
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
// per-body sizes (restricted fields: the two bodies mesh independently)
s1() = Boundary{Volume{3};}; c1() = Unique(Abs(Boundary{Surface{s1()};}));
s2() = Boundary{Volume{6};}; c2() = Unique(Abs(Boundary{Surface{s2()};}));
Field[1] = MathEval; Field[1].F = Sprintf("%g", h1);
Field[2] = Restrict; Field[2].InField = 1; Field[2].VolumesList = {3};
Field[2].SurfacesList = {s1()}; Field[2].CurvesList = {c1()};
Field[3] = MathEval; Field[3].F = Sprintf("%g", h2);
Field[4] = Restrict; Field[4].InField = 3; Field[4].VolumesList = {6};
Field[4].SurfacesList = {s2()}; Field[4].CurvesList = {c2()};
Field[5] = Min; Field[5].FieldsList = {2, 4};
Background Field = 5;
// faces by the body and the box of each: x = 0, x = 1, y = 0, y = 1, z = 0 or 2, the tilted one
For body In {0:1}
  v = body ? 6 : 3;
  b() = Boundary{Volume{v};};
  For i In {0:#b()-1}
    bb() = BoundingBox Surface{b(i)};
    lab = 0;
    If (bb(3) - bb(0) < 1e-6 && bb(0) < 0.5) lab = 1; EndIf
    If (bb(3) - bb(0) < 1e-6 && bb(0) > 0.5) lab = 2; EndIf
    If (bb(4) - bb(1) < 1e-6 && bb(1) < 0.5) lab = 3; EndIf
    If (bb(4) - bb(1) < 1e-6 && bb(1) > 0.5) lab = 4; EndIf
    If (bb(5) - bb(2) < 1e-6) lab = 5; EndIf
    If (lab == 0) lab = 6; EndIf
    Physical Surface(10 * (body + 1) + lab) = {b(i)};
  EndFor
EndFor
Physical Volume("lower", 1) = {3};
Physical Volume("upper", 2) = {6};
