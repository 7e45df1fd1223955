// The washing machine's cabinet: a box of 1.5 mm steel panels, 0.6 x 0.6 m, 0.85 m high (x from
// the back -0.3 to the front 0.3, y from -0.3 to 0.3, z from the floor 0 to 0.85), closed at the
// top and bottom, with the door's opening (radius 0.2 m, centred at z = 0.45) in the front panel.
SetFactory("OpenCASCADE");
a = 0.3; H = 0.85; zd = 0.45; rd = 0.2;
Rectangle(1) = {-a, -a, 0, 2 * a, 2 * a};            // floor
Rectangle(2) = {-a, -a, H, 2 * a, 2 * a};            // top
Rectangle(3) = {-a, 0, 0, 2 * a, H}; Rotate {{1, 0, 0}, {-a, 0, 0}, Pi / 2} { Surface{3}; } Translate {0, a, 0} { Surface{3}; }
Rectangle(4) = {-a, 0, 0, 2 * a, H}; Rotate {{1, 0, 0}, {-a, 0, 0}, Pi / 2} { Surface{4}; } Translate {0, -a, 0} { Surface{4}; }
Rectangle(5) = {0, -a, 0, H, 2 * a}; Rotate {{0, 1, 0}, {0, 0, 0}, -Pi / 2} { Surface{5}; } Translate {-a, 0, 0} { Surface{5}; }
Rectangle(6) = {0, -a, 0, H, 2 * a}; Rotate {{0, 1, 0}, {0, 0, 0}, -Pi / 2} { Surface{6}; } Translate {a, 0, 0} { Surface{6}; }
Disk(7) = {0, 0, 0, rd}; Rotate {{0, 1, 0}, {0, 0, 0}, Pi / 2} { Surface{7}; } Translate {a, 0, zd} { Surface{7}; }
BooleanDifference{ Surface{6}; Delete; }{ Surface{7}; Delete; }
// Cross members: two on the top (x = -0.0875 carries the left and right springs, x = 0.0875 the
// front one) and one on the floor (x = 0, the friction dampers), embedded lines of the panels.
Point(101) = {-0.0875, -a, H}; Point(102) = {-0.0875, a, H}; Line(101) = {101, 102};
Point(103) = {0.0875, -a, H}; Point(104) = {0.0875, a, H}; Line(102) = {103, 104};
Point(105) = {0, -a, 0}; Point(106) = {0, a, 0}; Line(103) = {105, 106};
s() = BooleanFragments{ Surface{1:6}; Delete; }{ Line{101:103}; Delete; };
Physical Surface("cabinet") = Surface{:};
Mesh.CharacteristicLengthMax = 0.075;
Mesh.RecombineAll = 1;
