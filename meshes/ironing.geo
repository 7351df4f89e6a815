// ironing.geo: the 3D ironing benchmark (Puso and Laursen 2004), half model
// about the mid-plane y = 2. A slab [0,9] x [0,2] x [0,3] (the full slab is
// 9 x 4 x 3) and a die: a segment of a cylindrical shell, outer radius 3,
// thickness 0.2, axis along y through (2.5, ., 6) (its outer, convex
// surface touches the slab top along x = 2.5), opening +-75 degrees about -z,
// y in [-0.6, 2] (the full die is 5.2 wide, 0.6 beyond each side). The slab
// is meshed with size hs, the die is structured: arc intervals of about hd,
// one element through the thickness, layers of about hd along y.
//   gmsh -3 -format msh2 -setnumber hs 0.5 ironing.geo
// (-setnumber ext e: the slab [-e, 9 + e] x [0,2] x [0,3], the die where it was;
//  -setnumber die 0: the slab alone, for a rigid die given by its shape)
SetFactory("OpenCASCADE");
DefineConstant[ hs = 0.5, hd = 0.25, ext = 0, die = 1 ];
Mesh.MshFileVersion = 2.2;
e = 1e-6;
Box(1) = {-ext, 0, 0, 9 + 2 * ext, 2, 3};   // ext > 0: the slab lengthened at both ends

cx = 2.5; cz = 6; R = 3; t = 0.2; th = 75 * Pi / 180; y0 = -0.6; w = 2.6;
If (die)
Point(101) = {cx, y0, cz};
Point(102) = {cx - R * Sin(th), y0, cz - R * Cos(th)};
Point(103) = {cx + R * Sin(th), y0, cz - R * Cos(th)};
Point(104) = {cx + (R - t) * Sin(th), y0, cz - (R - t) * Cos(th)};
Point(105) = {cx - (R - t) * Sin(th), y0, cz - (R - t) * Cos(th)};
Circle(101) = {102, 101, 103};   // outer arc (the contact surface)
Line(102) = {103, 104};
Circle(103) = {104, 101, 105};   // inner arc (moved)
Line(104) = {105, 102};
Curve Loop(101) = {101, 102, 103, 104};
Plane Surface(101) = {101};
narc = Ceil(2 * th * R / hd);
Transfinite Curve{101, 103} = narc + 1;
Transfinite Curve{102, 104} = 2;
Transfinite Surface{101};
die[] = Extrude {0, w, 0} { Surface{101}; Layers{ Ceil(w / hd) }; };
// die[0]: the face y = 2, die[1]: the volume, die[2..5]: the faces swept by
// curves 101 (outer), 102, 103 (inner), 104
EndIf

Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
Field[1] = MathEval; Field[1].F = Sprintf("%g", hs);
Field[2] = Restrict; Field[2].InField = 1;
Field[2].VolumesList = {1}; Field[2].SurfacesList = {1:6}; Field[2].CurvesList = {1:12};
Background Field = 2;

Physical Volume("slab", 1) = {1};
// slab faces (OpenCASCADE box order: x=0, x=9, y=0, y=2, z=0, z=3)
Physical Surface("slab_x0", 1) = {1};
Physical Surface("slab_x9", 2) = {2};
Physical Surface("slab_y0", 3) = {3};
Physical Surface("slab_sym", 4) = {4};
Physical Surface("slab_bottom", 5) = {5};
Physical Surface("slab_top", 6) = {6};
If (die)
Physical Volume("die", 2) = {die[1]};
Physical Surface("die_contact", 11) = {die[2]};
Physical Surface("die_top", 12) = {die[4]};
Physical Surface("die_sym", 13) = {die[0]};
Physical Surface("die_sides", 14) = {101, die[3], die[5]};
EndIf
