#pragma once
// Force elements (internal): each adds to data.Q, and its tangents to data.K / data.C.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime::detail {

/// The tension of a spring-damper in the current state (its element force).
double spring_force(const Model& model, const SpringDamper& s, const Data& data);
/// ends (optional): each end's generalized force over its body's 12 frame columns (column 0
/// marker 1's end, column 1 marker 2's; zero on the ground), for the interface-load stiffening
/// of an element between two points of one body (add_end_loads).
void spring_forces(const Model& model, const SpringDamper& s, Data& data, Eigen::Matrix<double, 12, 2>* ends = nullptr);
void spring_tangents(const Model& model, const SpringDamper& s, Data& data);
double spring_energy(const Model& model, const SpringDamper& s, const Data& data);

/// add_q: add the forces to data.Q; tangents: add -dQ/dq, -dQ/dqd to data.K, data.C.
void bushing_forces(const Model& model, const Bushing& b, Data& data, bool add_q, bool tangents,
                    Eigen::Matrix<double, 12, 2>* ends = nullptr);  // ends as spring_forces'
double bushing_energy(const Model& model, const Bushing& b, Data& data);
/// The six forces and torques (bushing axes; its element force) in the current state.
Vector6d bushing_force(const Model& model, const Bushing& b, const Data& data);
/// The six measures (displacement in marker 1's triad, small rotation) in the current state.
Vector6d bushing_measures(const Model& model, const Bushing& b, const Data& data);

/// Friction dampers (friction_damper.cpp). The tension (its element force) and the forces use
/// the slip committed at the last accepted step; commit_friction, after a step of length h (0:
/// at the start), commits the slip and adds the energy dissipated over the step, and the tyres'
/// sliding (commit_tire_sliding).
double friction_force(const Model& model, const FrictionDamper& f, const FrictionState& fs, const Data& data);
void friction_forces(const Model& model, const FrictionDamper& f, const FrictionState& fs, Data& data,
                     Eigen::Matrix<double, 12, 2>* ends = nullptr);  // ends as spring_forces'
void friction_tangents(const Model& model, const FrictionDamper& f, const FrictionState& fs, Data& data);
/// The series spring's elastic energy.
double friction_energy(const Model& model, const FrictionDamper& f, const FrictionState& fs, const Data& data);
void commit_friction(const Model& model, Data& data, double h);

/// Tyres (tire.cpp): the contact forces into data.Q, their tangents into data.K, data.C; the
/// contact quantities of the outputs (Fx, Fy, Fn in the contact frame, longitudinal slip, slip
/// angle, deflection); the vertical spring's energy.
void tire_forces(const Model& model, const Tire& ty, Data& data);
void tire_tangents(const Model& model, const Tire& ty, Data& data);
void tire_output(const Model& model, const Tire& ty, const Data& data, double* out);
double tire_energy(const Model& model, const Tire& ty, const Data& data);
/// Records which tyres slide well beyond their friction circle at the current (accepted) state,
/// for the next step's first tangent (Data::tire_sliding; called by commit_friction).
void commit_tire_sliding(const Model& model, Data& data);

/// A global force or torque at a marker (computed kinematics md).
void marker_load(const Model& model, const Marker& mk, const MarkerData& md, const Vector3d& f, bool torque,
                 Data& data, bool add_q, bool tangents);
void point_loads(const Model& model, Data& data, double t, bool add_q, bool tangents);
void external_loads(const Model& model, Data& data, bool add_q, bool tangents);

/// Interface-load stiffening (FORMULATION.md 7) of an element between two points of one body:
/// InterfaceLoadCapture leaves such an element out (both ends' loads are summed in the body's
/// frame entries of Q), so the element gives them end by end. True when markers m1 and m2 are on
/// one integrated body with stiffening interfaces and at least one of them on an interface node.
bool same_body_interfaces(const Model& model, const Data& data, int m1, int m2);
/// Adds ends.col(e), the generalized force of end e (marker m1, m2) over the body's 12 frame
/// columns (r0, then the columns of A), at the interface that end sits on (if any).
void add_end_loads(const Model& model, Data& data, int m1, int m2, const Eigen::Matrix<double, 12, 2>& ends);
/// r += -dQ/dlambda mu: the derivative of the interface-load stiffening force -KG y along the
/// multipliers mu (the joints' loads at the interfaces are linear in them), with the Jacobian
/// and state interface_loads used. Beside Phi_q^T mu, the multipliers' whole action on the
/// bodies (Newton's multiplier passes, FORMULATION.md 7).
void add_interface_multiplier_forces(const Model& model, const Data& data, const VectorXd& mu, VectorXd& r);

}  // namespace ffr::runtime::detail
