SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.8, 0.6};
// meshed with: gmsh box_tet.geo -3 -format msh22 and -order 1 -clscale 2 (box_tet4), -order 2 -clscale 4 (box_tet10)
Physical Volume("body") = {1};
