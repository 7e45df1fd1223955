Point(1) = {0,0,0}; Point(2) = {1,0,0}; Point(3) = {1,0.8,0}; Point(4) = {0,0.8,0};
Line(1) = {1,2}; Line(2) = {2,3}; Line(3) = {3,4}; Line(4) = {4,1};
Curve Loop(1) = {1,2,3,4}; Plane Surface(1) = {1};
Transfinite Curve{1,3} = 3; Transfinite Curve{2,4} = 3; Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude{0,0,0.6}{ Surface{1}; Layers{2}; Recombine; };
Physical Volume("body") = {out[1]};
// meshed with: gmsh box_hex.geo -3 -format msh22 and -order 1 (box_hex8), -order 2 (box_hex27),
// -order 2 -string "Mesh.SecondOrderIncomplete=1;" (box_hex20)
