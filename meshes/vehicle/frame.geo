// The ladder frame: two rails along x (y = +-0.45 m) at height 0.6 m, from x = -0.8 m (rear) to
// x = 2.7 m (front), and five tubular cross members (x = -0.8, 0, 1.2, 2.0, 2.7). The rear axle
// lies under x = 0, the front axle under x = 2.0. The rails are split where something is mounted
// (points named below), so each mount is a mesh node:
//   spring_*: the axles' spring seats on the rails (x = 0 and 2.0);
//   guide_r, guide_f: the axles' guides at the middle of the cross members at x = 0 and 2.0;
//   cab_*: the cab's four rubber mounts on the rails (x = -0.6 and 1.0);
//   engine_fl, engine_fr: the engine's front mounts on the rails (x = 2.4); engine_r: its rear
//   mount under the gearbox, the middle of the cross member at x = 1.2.
z = 0.6; w = 0.45; lc = 0.1;
xs[] = {-0.8, -0.6, 0.0, 1.0, 1.2, 2.0, 2.4, 2.7};
n = #xs[];
For i In {0 : n - 1}
  Point(1 + i) = {xs[i], w, z, lc};        // left rail
  Point(101 + i) = {xs[i], -w, z, lc};     // right rail
EndFor
For i In {0 : n - 2}
  Line(1 + i) = {1 + i, 2 + i};
  Line(101 + i) = {101 + i, 102 + i};
EndFor
// cross members: left rail -> middle -> right rail (the middle a node of its own)
cx[] = {-0.8, 0.0, 1.2, 2.0, 2.7};
ci[] = {0, 2, 4, 5, 7};                    // their indices in xs
For j In {0 : 4}
  Point(201 + j) = {cx[j], 0, z, lc};
  Line(201 + j) = {1 + ci[j], 201 + j};
  Line(301 + j) = {201 + j, 101 + ci[j]};
EndFor
Physical Curve("rails") = {1 : n - 1, 101 : 100 + n - 1};
Physical Curve("cross") = {201 : 205, 301 : 305};
Physical Point("g_spring_rl") = {3};   Physical Point("g_spring_rr") = {103};
Physical Point("g_spring_fl") = {6};   Physical Point("g_spring_fr") = {106};
Physical Point("g_guide_r") = {202};   Physical Point("g_guide_f") = {204};
Physical Point("g_cab_rl") = {2};      Physical Point("g_cab_rr") = {102};
Physical Point("g_cab_fl") = {4};      Physical Point("g_cab_fr") = {104};
Physical Point("g_engine_fl") = {7};   Physical Point("g_engine_fr") = {107};
Physical Point("g_engine_r") = {203};
