// Data: every buffer sized once from the Model, and the state set to the model's initial
// configuration (before assembly; initialize() makes it consistent).
#include "ffr/runtime/data.hpp"

#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/relative.hpp"
#include "../integrator/tangent_blocks.hpp"

#include <algorithm>

namespace ffr::runtime {
namespace {

void size_marker(MarkerData& md, int nb) {
  md.Jp = Matrix3N::Zero(3, nb);
  for (auto& J : md.Je) J = Matrix3N::Zero(3, nb);
  md.p = md.pd = md.pb = md.xbar = Vector3d::Zero();
  for (int k = 0; k < 3; ++k) md.e[k] = md.ed[k] = md.eb[k] = md.ebar[k] = Vector3d::Zero();
}

}  // namespace

Data::Data(const Model& model) : state(model), start(model) {
  const int n = model.ncoord, m = model.nconstraints;
  nf = n;
  na = m;
  nblocks = static_cast<int>(model.blocks.size());
  integrated.assign(model.bodies.size(), 1);
  drive_ref.assign(model.bodies.size(), DriveReference{});
  lambda_eff = lambda0 = reaction_lambda = VectorXd::Zero(m);
  Q = f = dq = r = tmp = vstar = q0 = qd0 = qdd0 = qd_hat = qdd_hat = VectorXd::Zero(n);
  sigma = c = alpha = VectorXd::Zero(m);
  state.k = trapezoidal_coefficients(model.settings.step);
  K = C = W = T = MatrixXd::Zero(n, n);
  Phiq = MatrixXd::Zero(m, n);
  lu.resize(n);
  unknowns.reserve(static_cast<std::size_t>(n));  // set_unknowns fills it without allocating
  lu_first.assign(static_cast<std::size_t>(n), 0);
  lu_last.assign(static_cast<std::size_t>(n), 0);
  lu_pos.assign(static_cast<std::size_t>(n), -1);
  body_pairs = detail::coupled_body_pairs(model);
  banded.assign(model.bodies.size(), 0);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) banded[i] = detail::banded_beam(model, static_cast<int>(i));
  lu_work = VectorXd::Zero(n);
  scale = VectorXd::Ones(n);
  Phi = Phit = gamma = VectorXd::Zero(m);
  projY = MatrixXd::Zero(n, m);
  projS = MatrixXd::Zero(m, m);
  proj_order.assign(static_cast<std::size_t>(m), 0);
  proj_mu = proj_w = VectorXd::Zero(m);
  if (model.relative) relative = Owned<RelativeWork>::make(model);  // FORMULATION.md 18

  int nb_max = 12;
  bodies.resize(model.bodies.size());
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    BodyData& bd = bodies[i];
    const int nq = b.nq, nb = b.ncoord();
    nb_max = std::max(nb_max, nb);
    bd.A = b.A0;
    bd.Ad = bd.Add = Matrix3d::Zero();
    bd.md = b.rdm;
    bd.Jc = b.J0;
    for (int a = 0; a < 3; ++a) {
      bd.S[a] = Matrix3Xd::Zero(3, nq);
    }
    bd.Pyd = MatrixXd::Zero(nq, 9);
    bd.Py = MatrixXd::Zero(nq, 9);
    bd.M = MatrixXd::Zero(nb, nb);
    bd.omega = bd.alpha = bd.acc = Vector3d::Zero();
    bd.KG = MatrixXd::Zero(nq, nq);
    const int nm = b.modal_stress ? nq : 0;
    bd.G1 = MatrixXd::Zero(nm, nm);
    bd.X1 = MatrixXd::Zero(nm, nm);
    bd.iface_load = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, b.stiffening ? static_cast<Eigen::Index>(b.stiffening->interfaces.size()) : 0);
    bd.wq = VectorXd::Zero(nq);
    if (nq == 0) body_mass_matrix(b, bd);  // constant for a rigid body
    else if (!b.full_mass) bd.M.block(12, 12, nq, nq) = b.Myy;  // constant for every body (body_mass_matrix)
    if (b.full_mass) {
      const auto N3 = b.full_mass->X.size();
      bd.feB = bd.feG = bd.feD = MatrixXd::Zero(N3, nb);
      bd.few = bd.feg = VectorXd::Zero(N3);
    }

    // Initial state as given: frame, rates from the frame's velocity and angular velocity.
    const int o = b.offset;
    state.q.segment<3>(o) = b.r0;
    state.qd.segment<3>(o) = b.v0;
    for (int a = 0; a < 3; ++a) {
      state.q.segment<3>(o + 3 + 3 * a) = b.A0.col(a);
      state.qd.segment<3>(o + 3 + 3 * a) = b.w0.cross(Vector3d(b.A0.col(a)));
    }
    if (nq) {
      state.q.segment(o + 12, nq) = b.y0;
      state.qd.segment(o + 12, nq) = b.yd0;
    }
  }

  markers.resize(model.markers.size());
  for (std::size_t i = 0; i < model.markers.size(); ++i) {
    const int b = model.markers[i].body;
    size_marker(markers[i], b == kGround ? 0 : model.bodies[b].ncoord());
  }

  int pair_max = 0;
  int rows_max = 6, nb_all = 12;
  for (const auto& b : model.blocks) rows_max = std::max(rows_max, b.rows);
  for (const auto& b : model.bodies) nb_all = std::max(nb_all, b.ncoord());
  Jw = MatrixXd::Zero(rows_max, nb_all);
  penalty_rows = VectorXd::Zero(rows_max);
  auto pair = [&](int m1, int m2) {
    const int b1 = model.markers[m1].body, b2 = model.markers[m2].body;
    return (b1 == kGround ? 0 : model.bodies[b1].ncoord()) + (b2 == kGround ? 0 : model.bodies[b2].ncoord());
  };
  for (const auto& s : model.springs) pair_max = std::max(pair_max, pair(s.m1, s.m2));
  for (const auto& s : model.bushings) pair_max = std::max(pair_max, pair(s.m1, s.m2));
  for (const auto& s : model.friction_dampers) pair_max = std::max(pair_max, pair(s.m1, s.m2));
  fK = fC = fH = MatrixXd::Zero(pair_max, pair_max);
  int joint_pair = 0;
  for (const auto& j : model.joints) joint_pair = std::max(joint_pair, pair(j.m1, j.m2));
  // (a coupler's Hessian is its two joints', each over its own pair: coupler_hessian)
  cH = MatrixXd::Zero(joint_pair, joint_pair);
  cg = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, joint_pair);
  cl = VectorXd::Zero(6);
  fg = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, pair_max);
  fz = fhz = VectorXd::Zero(pair_max);
  for (auto& w : w3) w = Matrix3N::Zero(3, nb_max);
  lt = VectorXd::Zero(6 * nb_max);
  tJ = tV = tW = Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, model.tires.empty() ? 0 : nb_max);
  tire_sliding.assign(model.tires.size(), 0);
  for (auto& j : bJ) j = Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, model.bushings.empty() ? 0 : nb_max);
  bT = Eigen::Matrix<double, 12, Eigen::Dynamic>::Zero(12, model.bushings.empty() ? 0 : nb_max);
  bP = Eigen::Matrix<double, 6, Eigen::Dynamic>::Zero(6, model.bushings.empty() ? 0 : pair_max);
  bt = VectorXd::Zero(model.bushings.empty() ? 0 : 24 * nb_max);
  if (!model.bushings.empty()) bushing_K = bushing_C = MatrixXd::Zero(n, n);
  for (const Bushing& bu : model.bushings) {
    const int body[2] = {model.markers[bu.m1].body, model.markers[bu.m2].body};
    for (int a : body)
      for (int b : body)
        if (a != kGround && b != kGround) {
          const Body& ba = model.bodies[static_cast<std::size_t>(a)];
          const Body& bb = model.bodies[static_cast<std::size_t>(b)];
          bushing_blocks.push_back({ba.offset, ba.ncoord(), bb.offset, bb.ncoord()});
        }
  }
  std::sort(bushing_blocks.begin(), bushing_blocks.end());
  bushing_blocks.erase(std::unique(bushing_blocks.begin(), bushing_blocks.end()), bushing_blocks.end());

  motion_external.assign(model.motions.size(), 0);
  motion_value.assign(model.motions.size(), Eigen::Vector3d::Zero());

  ext_force.resize(model.bodies.size());
  ext_torque.resize(model.bodies.size());
  ext_list.resize(model.bodies.size());
  ext_marker.resize(model.bodies.size());
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const auto slots = static_cast<Eigen::Index>(model.load_slots.size() > i ? model.load_slots[i].size() : 1);
    ext_force[i] = Matrix3N::Zero(3, slots);
    ext_torque[i] = Matrix3N::Zero(3, slots);
    ext_list[i].clear();
    ext_list[i].reserve(static_cast<std::size_t>(slots));  // setting loads never allocates
    size_marker(ext_marker[i], model.bodies[i].ncoord());
  }
  state.t = model.settings.start;
}

void set_external_load(Data& data, int body, int slot, const Vector3d& force, const Vector3d& torque) {
  const auto b = static_cast<std::size_t>(body);
  data.ext_force[b].col(slot) = force;
  data.ext_torque[b].col(slot) = torque;
  auto& list = data.ext_list[b];
  if (std::find(list.begin(), list.end(), slot) == list.end()) list.push_back(slot);
}

void clear_external_loads(Data& data) {
  for (std::size_t b = 0; b < data.ext_list.size(); ++b) {
    data.ext_force[b].setZero();
    data.ext_torque[b].setZero();
    data.ext_list[b].clear();
  }
}

}  // namespace ffr::runtime
