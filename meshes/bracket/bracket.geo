// Angle bracket with two bolt holes in the base and a lightening hole in the web; source of
// bracket.step (exported with: gmsh bracket.geo -0 -format step -o bracket.step).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.12, 0.08, 0.01};        // base plate
Box(2) = {0, 0, 0.01, 0.01, 0.08, 0.09};     // web
Cylinder(3) = {0.04, 0.02, -0.01, 0, 0, 0.03, 0.006};
Cylinder(4) = {0.04, 0.06, -0.01, 0, 0, 0.03, 0.006};
Cylinder(5) = {-0.01, 0.04, 0.06, 0.03, 0, 0, 0.015};
Cylinder(6) = {0.09, 0.04, -0.01, 0, 0, 0.03, 0.008};
BooleanUnion(10) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
BooleanDifference(11) = { Volume{10}; Delete; }{ Volume{3, 4, 5, 6}; Delete; };
