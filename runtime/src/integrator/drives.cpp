// Driven bodies (FORMULATION.md section 9): a rigid body that a joint holds to the ground, or
// turns (slides) along a prescribed coordinate, moves as a known function of time. With such
// bodies eliminated, their coordinates leave the step's unknowns: the tangent, its factorisation
// and every product of the step shrink to the integrated bodies (on the benchmark's slider-crank,
// 46 to 34 coordinates and 39 to 27 rows), and their markers act like moving ground markers.
//
// The motion is exact, not integrated: a revolute drive turns the body's reference pose about
// the joint's axis through the joint's point by the change of the prescribed angle; a prismatic
// drive slides it along the axis by the change of the prescribed displacement.
//
// An ancf beam's frame is known the same way, where its rows hold it (known_frame.hpp).
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "tangent_blocks.hpp"
#include "../model/known_frame.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace ffr::runtime {
namespace {

// Once per set of unknowns: whether the step's passes go block by block (tangent_blocks.hpp).
void decide_block_passes(const Model& model, Data& data) {
  data.tangent_blocks_pay = detail::decide_tangent_blocks_pay(model, data);
  data.block_columns_pay = detail::decide_block_columns_pay(model, data);
  detail::tangent_row_spans(model, data);
}

Matrix3d skew(const Vector3d& w) {
  Matrix3d s;
  s << 0, -w(2), w(1), w(2), 0, -w(0), -w(1), w(0), 0;
  return s;
}

// The reference of body i's drive from the present state (markers up to date).
DriveReference reference(const Model& model, const Data& data, int i) {
  const Body& b = model.bodies[static_cast<std::size_t>(i)];
  const Joint& j = model.joints[static_cast<std::size_t>(b.drive.joint)];
  DriveReference ref;
  ref.r0 = data.state.q.segment<3>(b.offset);
  ref.A = Eigen::Map<const Matrix3d>(data.state.q.data() + b.offset + 3);
  // The ground's marker gives the fixed point; the axis is marker 1's e, the axis the joint's
  // coordinate is measured about (along): turning (moving) marker 2's body by +d, or marker 1's
  // body by -d, changes the coordinate by +d.
  const MarkerData& ground = data.markers[static_cast<std::size_t>(b.drive.side == 1 ? j.m2 : j.m1)];
  ref.point = ground.p;
  const Vector3d e1 = data.markers[static_cast<std::size_t>(j.m1)].e[0];
  ref.axis = (b.drive.side == 2 ? 1.0 : -1.0) * e1.normalized();
  ref.value = b.drive.motion >= 0 ? motion_target(model, data, b.drive.motion, data.state.t)(0) : 0.0;
  return ref;
}

}  // namespace

void set_unknowns(const Model& model, Data& data, bool eliminate) {
  // (A model whose bodies are all driven is integrated whole: nothing would be left to solve.)
  const bool any = (model.nfree < model.ncoord || model.nunknown < model.nfree) && model.nfree > 0;
  data.unknowns.clear();
  data.unknown_runs.clear();
  if (!eliminate || !any) {
    data.nf = model.ncoord;
    data.na = model.nconstraints;
    data.nblocks = static_cast<int>(model.blocks.size());
    std::fill(data.integrated.begin(), data.integrated.end(), 1);
    decide_block_passes(model, data);
    return;
  }
  update_bodies(model, data);
  update_markers(model, data);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    if (b.driven()) data.drive_ref[i] = reference(model, data, static_cast<int>(i));
    if (b.frame_locked) data.drive_ref[i].A = Eigen::Map<const Matrix3d>(data.state.q.data() + b.offset + 3);
  }
  data.nf = model.nfree;
  if (model.nunknown < model.nfree)
    for (const Body& b : model.bodies) {  // the integrated ones come in the order of their offsets
      if (b.driven()) continue;
      const int known = detail::first_known_frame_coord(model, b);
      for (int k = 0; k < b.ncoord(); ++k)
        if (k < known || k >= 12) data.unknowns.push_back(b.offset + k);
    }
  for (std::size_t i = 0; i < data.unknowns.size(); ++i) {
    const int at = static_cast<int>(i), u = data.unknowns[i];
    if (at > 0 && u == data.unknowns[i - 1] + 1)
      ++data.unknown_runs.back().len;
    else
      data.unknown_runs.push_back({at, u, 1});
  }
  data.na = model.nactive;
  data.nblocks = model.active_blocks;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) data.integrated[i] = model.bodies[i].driven() ? 0 : 1;
  // The evaluations clear only the Jacobian's blocks in use (constraints.cpp): the columns of the
  // bodies driven from now on and the rows of the blocks among them, once here. The rest is
  // kept: the first evaluation's interface loads (stiffening) read the last Jacobian.
  data.Phiq.bottomRows(data.Phiq.rows() - data.na).setZero();
  data.Phiq.rightCols(data.Phiq.cols() - data.nf).setZero();
  data.tangent_valid = false;
  decide_block_passes(model, data);
  drive_bodies(model, data, data.state.t);
}

void drive_bodies(const Model& model, Data& data, double t) {
  if (data.nf == model.ncoord && data.unknowns.empty()) return;  // everything integrated
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    if (detail::frame_known(model, b)) {  // an ancf beam's frame: where its rows hold it, r0 = 0, A = I, at rest
      const int o = b.offset;
      data.state.q.segment<3>(o).setZero();
      Eigen::Map<Matrix3d>(data.state.q.data() + o + 3).setIdentity();
      data.state.qd.segment<12>(o).setZero();
      data.state.qdd.segment<12>(o).setZero();
      continue;
    }
    if (b.frame_locked) {  // it slides only: the frame as it was, at rest
      const int o = b.offset;
      Eigen::Map<Matrix3d>(data.state.q.data() + o + 3) = data.drive_ref[i].A;
      data.state.qd.segment<9>(o + 3).setZero();
      data.state.qdd.segment<9>(o + 3).setZero();
      continue;
    }
    if (!b.driven()) continue;
    const DriveReference& ref = data.drive_ref[i];
    const Vector3d v = b.drive.motion >= 0 ? motion_target(model, data, b.drive.motion, t) : Vector3d::Zero();
    const double d = v(0) - ref.value;
    Vector3d r0 = ref.r0, r0d = Vector3d::Zero(), r0dd = Vector3d::Zero();
    Matrix3d A = ref.A, Ad = Matrix3d::Zero(), Add = Matrix3d::Zero();
    if (b.drive.kind == DriveKind::Revolute) {
      const Matrix3d R = Eigen::AngleAxisd(d, ref.axis).toRotationMatrix();
      const Vector3d arm = R * (ref.r0 - ref.point);
      const Vector3d w = v(1) * ref.axis, a = v(2) * ref.axis;
      const Matrix3d W = skew(w), W2 = W * W;
      r0 = ref.point + arm;
      A = R * ref.A;
      r0d = w.cross(arm);
      r0dd = a.cross(arm) + w.cross(r0d);
      Ad = W * A;
      Add = (skew(a) + W2) * A;
    } else if (b.drive.kind == DriveKind::Prismatic) {
      r0 += d * ref.axis;
      r0d = v(1) * ref.axis;
      r0dd = v(2) * ref.axis;
    }
    const int o = b.offset;
    data.state.q.segment<3>(o) = r0;
    data.state.qd.segment<3>(o) = r0d;
    data.state.qdd.segment<3>(o) = r0dd;
    Eigen::Map<Matrix3d>(data.state.q.data() + o + 3) = A;
    Eigen::Map<Matrix3d>(data.state.qd.data() + o + 3) = Ad;
    Eigen::Map<Matrix3d>(data.state.qdd.data() + o + 3) = Add;
  }
}

double driven_violation(const Model& model, const Data& data, int& block) {
  double worst = 0;
  block = -1;
  for (std::size_t bi = static_cast<std::size_t>(data.nblocks); bi < model.blocks.size(); ++bi) {
    const ConstraintBlock& b = model.blocks[bi];
    const double v = data.Phi.segment(b.row0, b.rows).cwiseAbs().maxCoeff() / model.length;
    if (v > worst) {
      worst = v;
      block = static_cast<int>(bi);
    }
  }
  return worst;
}

}  // namespace ffr::runtime
