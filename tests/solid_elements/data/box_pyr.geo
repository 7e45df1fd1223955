SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.5, 0.8, 0.6};
Box(2) = {0.5, 0, 0, 0.5, 0.8, 0.6};
Coherence;
Transfinite Volume{1}; Transfinite Surface{:}; 
Transfinite Curve{:} = 3;
Recombine Surface{:};
Recombine Volume{1};
Physical Volume("body") = {1, 2};
// meshed with: gmsh box_pyr.geo -3 -order 1 -clscale 2 -format msh22 (tets + pyramids + hexes)
