// novolume.geo: a unit cube with a physical surface and no Physical Volume (err_gmshfile_novolume.edp)
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Mesh.MeshSizeMax = 0.5;
Physical Surface(7) = {1:6};
