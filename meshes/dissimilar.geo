// dissimilar.geo: half model (y >= 0) of two hemispheres touching at the
// origin: the upper one of radius R1 centred (0,0,R1) with its flat face
// z = R1 on top, the lower one of radius R2 centred (0,0,-R2) with its flat
// face z = -R2 below. Mesh size hc within distance 0.3 of the origin,
// growing with slope 0.5 up to 0.25.
//   gmsh -3 -format msh2 -setnumber hc 0.05 dissimilar.geo
SetFactory("OpenCASCADE");
DefineConstant[ hc = 0.05, R1 = 1, R2 = 2 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromCurvature = 0;
e = 1e-6;

Sphere(1) = {0, 0, R1, R1};
Box(2) = {-R1, 0, 0, 2 * R1, R1, R1};
upper() = BooleanIntersection{ Volume{1}; Delete; }{ Volume{2}; Delete; };
Sphere(3) = {0, 0, -R2, R2};
Box(4) = {-R2, 0, -R2, 2 * R2, R2, R2};
lower() = BooleanIntersection{ Volume{3}; Delete; }{ Volume{4}; Delete; };

u_top() = Surface In BoundingBox{-R1 - e, -e, R1 - e, R1 + e, R1 + e, R1 + e};
u_y0()  = Surface In BoundingBox{-R1 - e, -e, -e, R1 + e, e, R1 + e};
u_all() = Boundary{ Volume{upper()}; };
u_curved() = u_all();
u_curved() -= {u_top(), u_y0()};
l_bot() = Surface In BoundingBox{-R2 - e, -e, -R2 - e, R2 + e, R2 + e, -R2 + e};
l_y0()  = Surface In BoundingBox{-R2 - e, -e, -R2 - e, R2 + e, e, e};
l_all() = Boundary{ Volume{lower()}; };
l_curved() = l_all();
l_curved() -= {l_bot(), l_y0()};

Physical Volume("upper", 1) = {upper()};
Physical Volume("lower", 2) = {lower()};
Physical Surface("upper_contact", 1) = {u_curved()};
Physical Surface("upper_top", 2) = {u_top()};
Physical Surface("upper_y0", 3) = {u_y0()};
Physical Surface("lower_contact", 11) = {l_curved()};
Physical Surface("lower_bottom", 12) = {l_bot()};
Physical Surface("lower_y0", 13) = {l_y0()};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(0.25, %g + 0.5 * Max(0, Sqrt(x*x + y*y + z*z) - 0.3))", hc);
Background Field = 1;
