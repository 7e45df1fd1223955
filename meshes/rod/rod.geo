// Connecting rod: two eyes (bores of radius 8 mm) 0.3 m apart, joined by a 12 x 20 mm shank.
// Eye A is centred at the origin, eye B at x = 0.3 m; thickness 12 mm (z from -6 to 6 mm).
SetFactory("OpenCASCADE");
t = 0.012; R = 0.02; r = 0.008; Lc = 0.3; w = 0.02;
Cylinder(1) = {0, 0, -t/2, 0, 0, t, R};
Cylinder(2) = {Lc, 0, -t/2, 0, 0, t, R};
Box(3) = {0, -w/2, -t/2, Lc, w, t};
Cylinder(4) = {0, 0, -t, 0, 0, 2*t, r};
Cylinder(5) = {Lc, 0, -t, 0, 0, 2*t, r};
BooleanUnion(10) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
BooleanDifference(11) = { Volume{10}; Delete; }{ Volume{4, 5}; Delete; };
Physical Volume("rod") = {11};
eps = 1e-4;
Physical Surface("boreA") = Surface In BoundingBox{-r - eps, -r - eps, -t/2 - eps, r + eps, r + eps, t/2 + eps};
Physical Surface("boreB") = Surface In BoundingBox{Lc - r - eps, -r - eps, -t/2 - eps, Lc + r + eps, r + eps, t/2 + eps};
