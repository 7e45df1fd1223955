// Solid cantilever beam: L = 1 m along x, 50 mm wide (y), 20 mm thick (z); clamped at x = 0.
SetFactory("OpenCASCADE");
L = 1.0; b = 0.05; h = 0.02;
Box(1) = {0, 0, 0, L, b, h};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("tip") = Surface In BoundingBox{L - 1e-6, -1, -1, L + 1e-6, 1, 1};
