// The chamber's support frame: an L-shaped aluminium tube mast, a 0.6 m column (z) and a 0.3 m
// arm (x) carrying the target holder at its end; clamped at its foot on the moving base.
Point(1) = {0, 0, 0}; Point(2) = {0, 0, 0.6}; Point(3) = {0.3, 0, 0.6};
Line(1) = {1, 2}; Line(2) = {2, 3};
Transfinite Curve{1} = 25; Transfinite Curve{2} = 13;
Physical Curve("frame") = {1, 2};
Physical Point("foot") = {1};
