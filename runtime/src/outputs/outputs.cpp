#include "ffr/runtime/outputs.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/energy.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ffr::runtime {
namespace {

// Outputs that read the frames' and markers' kinematics (update_bodies, update_markers). These
// are recomputed from the state before such outputs are written: the state may have changed
// since the last evaluation (the projections after a step, a restored state).
bool reads_kinematics(const Output& o) {
  switch (o.type) {
    case OutputType::JointCoordinate:
    case OutputType::JointRate:
    case OutputType::JointReaction:
    case OutputType::NodeVelocity:
    case OutputType::BodyAngularVelocity:
    case OutputType::ElementForce:
      return true;
    default:
      return false;
  }
}

void update_kinematics(const Model& model, Data& data) {
  update_bodies(model, data);
  update_markers(model, data);
}

// Output `o` from the current state, its kinematics made current by the caller.
void write_output(const Model& model, Data& data, const Output& o, double* out) {
  switch (o.type) {
    case OutputType::NodeDeformation: {
      const Body& b = model.bodies[o.body];
      const Vector3d u = b.nodes[o.node].displacement(data.state.q.segment(b.offset + 12, b.nq));
      for (int i = 0; i < 3; ++i) out[i] = u(i);
      break;
    }
    case OutputType::NodePosition: {
      const Body& b = model.bodies[o.body];
      Vector3d x = o.point;
      if (o.node >= 0) x = b.nodes[o.node].origin + b.nodes[o.node].displacement(data.state.q.segment(b.offset + 12, b.nq));
      Matrix3d A;
      for (int a = 0; a < 3; ++a) A.col(a) = data.state.q.segment<3>(b.offset + 3 + 3 * a);
      const Vector3d p = data.state.q.segment<3>(b.offset) + A * x;
      for (int i = 0; i < 3; ++i) out[i] = p(i);
      break;
    }
    case OutputType::ModalCoordinates: {
      const Body& b = model.bodies[o.body];
      for (int k = 0; k < b.nq; ++k) out[k] = data.state.q(b.offset + 12 + k);
      break;
    }
    case OutputType::JointCoordinate:
      for (std::size_t i = 0; i < o.coords.size(); ++i) out[i] = joint_coordinate(model, data, o.joint, o.coords[i]);
      break;
    case OutputType::JointRate:
      for (std::size_t i = 0; i < o.coords.size(); ++i) out[i] = joint_coordinate_rate(model, data, o.joint, o.coords[i]);
      break;
    case OutputType::JointReaction: {
      const Vector6d w = joint_reaction(model, data, o.joint);
      for (int i = 0; i < 6; ++i) out[i] = w(i);
      break;
    }
    case OutputType::NodeVelocity: {
      // v = r0_dot + A_dot xbar + A Phi_p y_dot (xbar = the deformed local point).
      const Body& b = model.bodies[o.body];
      const BodyData& bd = data.bodies[o.body];
      Vector3d x = o.point;
      Vector3d v = data.state.qd.segment<3>(b.offset);
      if (o.node >= 0) {
        x = b.nodes[o.node].origin + b.nodes[o.node].displacement(data.state.q.segment(b.offset + 12, b.nq));
        v.noalias() += bd.A * b.nodes[o.node].displacement(data.state.qd.segment(b.offset + 12, b.nq));
      }
      v.noalias() += bd.Ad * x;
      for (int i = 0; i < 3; ++i) out[i] = v(i);
      break;
    }
    case OutputType::BodyAngularVelocity: {
      const BodyData& bd = data.bodies[o.body];
      const Vector3d w = bd.A * bd.omega;
      for (int i = 0; i < 3; ++i) out[i] = w(i);
      break;
    }
    case OutputType::ElementForce:
      element_force(model, data, o.element_kind, o.element, out);
      break;
    case OutputType::Energy: {
      const Energy e = energy(model, data);
      out[0] = e.kinetic;
      out[1] = e.potential;
      out[2] = e.total();
      if (o.size > 3) out[3] = e.dissipated;
      break;
    }
  }
}

}  // namespace

void evaluate_output(const Model& model, Data& data, const Output& o, double* out) {
  if (reads_kinematics(o)) update_kinematics(model, data);
  write_output(model, data, o, out);
}

Recorder::Recorder(const Model& model, std::int64_t max_rows) {
  t_ = VectorXd::Zero(max_rows);
  int widest = 0;
  for (const Output& o : model.outputs) {
    v_.push_back(MatrixXd::Zero(max_rows, o.size));
    widest = std::max(widest, o.size);
  }
  row_ = VectorXd::Zero(widest);
}

void Recorder::record(const Model& model, Data& data) {
  if (rows_ >= t_.size()) return;
  t_(rows_) = data.state.t;
  // The kinematics once for all outputs of the sample.
  if (std::any_of(model.outputs.begin(), model.outputs.end(), reads_kinematics)) update_kinematics(model, data);
  for (std::size_t i = 0; i < model.outputs.size(); ++i) {
    // Rows of a column-major matrix are strided: evaluate into a contiguous buffer first.
    write_output(model, data, model.outputs[i], row_.data());
    v_[i].row(rows_) = row_.head(model.outputs[i].size).transpose();
  }
  ++rows_;
}

void Recorder::append(double t, const std::vector<Eigen::VectorXd>& values) {
  if (rows_ >= t_.size()) throw std::invalid_argument("the recorder is full");
  if (values.size() != v_.size())
    throw std::invalid_argument(std::to_string(values.size()) + " outputs for the model's " + std::to_string(v_.size()));
  for (std::size_t i = 0; i < v_.size(); ++i)
    if (values[i].size() != v_[i].cols())
      throw std::invalid_argument("output " + std::to_string(i) + " has " + std::to_string(values[i].size()) +
                                  " components for the model's " + std::to_string(v_[i].cols()));
  t_(rows_) = t;
  for (std::size_t i = 0; i < v_.size(); ++i) v_[i].row(rows_) = values[i].transpose();
  ++rows_;
}

}  // namespace ffr::runtime
