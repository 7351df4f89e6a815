// spheres.geo: two equal spheres of radius R touching at the origin,
// sphere 1 centred at (0, 0, -R), sphere 2 at (0, 0, R), meshed
// independently. quarter = 1: the part x >= 0, y >= 0 (two symmetry
// planes, for a head-on impact along z); quarter = 0: the half y >= 0 (one
// symmetry plane, for an oblique impact with sliding along x). Mesh size
// hc within distance 0.1 of the origin, growing with slope 0.5 up to hmax.
//   gmsh -3 -format msh2 -setnumber hc 0.02 -setnumber quarter 1 spheres.geo
SetFactory("OpenCASCADE");
DefineConstant[ R = 0.5, hc = 0.02, hmax = 0.1, r0 = 0.1, quarter = 1 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;
x0 = quarter ? 0 : -R;

Sphere(1) = {0, 0, -R, R};
Sphere(2) = {0, 0, R, R};
Box(3) = {x0, 0, -2 * R, R - x0, R, 2 * R};
Box(4) = {x0, 0, 0, R - x0, R, 2 * R};
s1() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{3}; Delete; };
s2() = BooleanIntersection{ Volume{2}; Delete; }{ Volume{4}; Delete; };

// the flat faces on the symmetry planes, the curved rest
y1() = Surface In BoundingBox{-R - e, -e, -2 * R - e, R + e, e, e};
y2() = Surface In BoundingBox{-R - e, -e, -e, R + e, e, 2 * R + e};
x1() = {};
x2() = {};
If (quarter)
  x1() = Surface In BoundingBox{-e, -e, -2 * R - e, e, R + e, e};
  x2() = Surface In BoundingBox{-e, -e, -e, e, R + e, 2 * R + e};
EndIf
c1() = Boundary{ Volume{s1()}; };
c1() -= {y1(), x1()};
c2() = Boundary{ Volume{s2()}; };
c2() -= {y2(), x2()};

Physical Volume("sphere1", 1) = {s1()};
Physical Volume("sphere2", 2) = {s2()};
Physical Surface("sphere1_curved", 11) = {c1()};
Physical Surface("sphere1_x0", 13) = {x1()};
Physical Surface("sphere1_y0", 14) = {y1()};
Physical Surface("sphere2_curved", 21) = {c2()};
Physical Surface("sphere2_x0", 23) = {x2()};
Physical Surface("sphere2_y0", 24) = {y2()};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + 0.5 * Max(0, Sqrt(x*x + y*y + z*z) - %g))", hmax, hc, r0);
Background Field = 1;
