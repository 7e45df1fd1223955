// The washing machine's tub: a cylinder of radius 0.3 m and depth 0.35 m along x (the drum's
// axis), open at the front (x = 0.35), closed by a flat rear wall at x = 0 whose central disk
// (radius 0.12 m, a surface of its own) carries the bearing; quads on the mantle (24 around,
// 4 deep: nodes every 15 degrees and every 87.5 mm), triangles on the rear wall.
R = 0.3; Ri = 0.12; L = 0.35; lc = 0.08;
Point(1) = {0, 0, 0, lc};
Point(2) = {0, R, 0, lc}; Point(3) = {0, 0, R, lc}; Point(4) = {0, -R, 0, lc}; Point(5) = {0, 0, -R, lc};
Point(6) = {0, Ri, 0, lc}; Point(7) = {0, 0, Ri, lc}; Point(8) = {0, -Ri, 0, lc}; Point(9) = {0, 0, -Ri, lc};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Transfinite Curve{1:4} = 7;
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Plane Surface(2) = {2};
out[] = Extrude {L, 0, 0} { Curve{1:4}; Layers{4}; Recombine; };
Physical Surface("tub") = {1, 2, out[1], out[5], out[9], out[13]};
