// rigid_hertz.geo: one body of hertz.geo alone, for contact with a rigid
// obstacle.  part = 1: the quarter hemisphere (radius 1, centre (0,0,1),
// flat top z = 1) touching the plane z = 0 at the origin; part = 2: the
// quarter block [0,2] x [0,2] x [-2,0].  Labels and mesh size as hertz.geo
// (hc within r0 = 0.3 of the origin, growing with slope 0.5 up to 0.25).
//   gmsh -3 -format msh2 -setnumber hc 0.05 -setnumber part 1 rigid_hertz.geo
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.05, r0 = 0.3, part = 1 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;

If (part == 1)
  Sphere(1) = {0, 0, 1, 1};
  Box(2) = {0, 0, 0, 1.5, 1.5, 1};
  ball() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
  b_top() = Surface In BoundingBox{-e, -e, 1 - e, 1 + e, 1 + e, 1 + e};
  b_x0()  = Surface In BoundingBox{-e, -e, -e, e, 1 + e, 1 + e};
  b_y0()  = Surface In BoundingBox{-e, -e, -e, 1 + e, e, 1 + e};
  b_all() = Boundary{ Volume{ball()}; };
  b_curved() = b_all();
  b_curved() -= {b_top(), b_x0(), b_y0()};
  Physical Volume("ball", 1) = {ball()};
  Physical Surface("ball_contact", 1) = {b_curved()};
  Physical Surface("ball_top", 2) = {b_top()};
  Physical Surface("ball_x0", 3) = {b_x0()};
  Physical Surface("ball_y0", 4) = {b_y0()};
Else
  Box(3) = {0, 0, -2, 2, 2, 2};
  k_top() = Surface In BoundingBox{-e, -e, -e, 2 + e, 2 + e, e};
  k_bot() = Surface In BoundingBox{-e, -e, -2 - e, 2 + e, 2 + e, -2 + e};
  k_x0()  = Surface In BoundingBox{-e, -e, -2 - e, e, 2 + e, e};
  k_y0()  = Surface In BoundingBox{-e, -e, -2 - e, 2 + e, e, e};
  k_x2()  = Surface In BoundingBox{2 - e, -e, -2 - e, 2 + e, 2 + e, e};
  k_y2()  = Surface In BoundingBox{-e, 2 - e, -2 - e, 2 + e, 2 + e, e};
  Physical Volume("block", 2) = {3};
  Physical Surface("block_top", 11) = {k_top()};
  Physical Surface("block_bottom", 12) = {k_bot()};
  Physical Surface("block_x0", 13) = {k_x0()};
  Physical Surface("block_y0", 14) = {k_y0()};
  Physical Surface("block_x2", 15) = {k_x2()};
  Physical Surface("block_y2", 16) = {k_y2()};
EndIf

Field[1] = MathEval;
Field[1].F = Sprintf("Min(0.25, %g + 0.5 * Max(0, Sqrt(x*x + y*y + z*z) - %g))", hc, r0);
Background Field = 1;
