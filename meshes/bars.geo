// bars.geo: two bars of length L and square section a x a on the x axis,
// meshed independently, end to end: bar 1 on [-L, 0], bar 2 on
// [gap0, gap0 + L], both on [0, a] x [0, a] in y and z.
//   gmsh -3 -format msh2 -setnumber h 0.05 bars.geo
SetFactory("OpenCASCADE");
DefineConstant[ L = 1, a = 0.2, h = 0.05, gap0 = 0 ];
Mesh.MshFileVersion = 2.2;
Mesh.MeshSizeMin = h;
Mesh.MeshSizeMax = h;

Box(1) = {-L, 0, 0, L, a, a};
Box(2) = {gap0, 0, 0, L, a, a};
// OpenCASCADE box faces: x=min, x=max, y=min, y=max, z=min, z=max
Physical Volume("bar1", 1) = {1};
Physical Volume("bar2", 2) = {2};
Physical Surface("bar1_x0", 11) = {1};
Physical Surface("bar1_x1", 12) = {2};
Physical Surface("bar1_y", 13) = {3, 4};
Physical Surface("bar1_z", 14) = {5, 6};
Physical Surface("bar2_x0", 21) = {7};
Physical Surface("bar2_x1", 22) = {8};
Physical Surface("bar2_y", 23) = {9, 10};
Physical Surface("bar2_z", 24) = {11, 12};
