// A free-free machined link: a 200 x 40 x 10 mm bar with a pocket and two through holes.
SetFactory("OpenCASCADE");
Box(1) = {0, -0.02, -0.005, 0.2, 0.04, 0.01};
Box(2) = {0.05, -0.012, 0.0, 0.1, 0.024, 0.006};
Cylinder(3) = {0.02, 0, -0.01, 0, 0, 0.02, 0.006};
Cylinder(4) = {0.18, 0, -0.01, 0, 0, 0.02, 0.006};
BooleanDifference(10) = { Volume{1}; Delete; }{ Volume{2, 3, 4}; Delete; };
Physical Volume("link") = {10};
