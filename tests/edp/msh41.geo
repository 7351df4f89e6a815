// msh41.geo: a unit cube whose .geo asks gmsh for MSH 4.1 (test_gmsh_format.edp)
SetFactory("OpenCASCADE");
Mesh.MshFileVersion = 4.1;
DefineConstant[ h = 0.5 ];
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = h;
Physical Volume(1) = {1};
Physical Surface(7) = {1:6};
