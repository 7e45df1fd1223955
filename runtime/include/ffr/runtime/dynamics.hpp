#pragma once
// Mass matrix and generalized forces of the unconstrained system (FORMULATION.md 3-7).
// Q collects everything on the right-hand side of M(q) q_dd = Q(q, q_d, t) - Phi_q^T lambda:
// velocity-dependent inertia forces, elastic and damping forces, gravity, stiffening, force
// elements, table loads and external inputs. K = -dQ/dq and C = -dQ/dq_d are analytic.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"

namespace ffr::runtime {

/// One body's mass matrix (bd.M) from bd.A, bd.md, bd.Jc, bd.S; its constant modal block
/// M_yy = b.Myy is not written (Data's constructor placed it).
void body_mass_matrix(const Body& b, BodyData& bd);

/// Every body's mass matrix into data.bodies[i].M. Needs update_bodies.
void mass_matrices(const Model& model, Data& data);

/// y = M x (block diagonal over bodies), over the bodies whose coordinates are unknowns now
/// (integrated()); a driven body's entries of y are left as they are.
void mass_times(const Model& model, const Data& data, const VectorXd& x, VectorXd& y);

/// T += scale * d(M(q) q_dd)/dy at frozen q_dd, for the modal block of each integrated flexible
/// body (FORMULATION.md 9): sum_ab (A_b . A_dd_a) PPdm[b][a]. Needs update_bodies (bd.A, bd.Add).
void add_modal_acceleration_tangent(const Model& model, Data& data, double scale, MatrixXd& T);

/// data.Q at time t. Needs update_bodies, update_markers and the mass matrices (for nothing
/// else than the stiffening accelerations, which come from data.state.qdd). A driven body's own terms
/// (while it is eliminated) are left out: nothing reads them.
void generalized_forces(const Model& model, Data& data, double t);

/// data.K and data.C at time t (same prerequisites). The stiffening terms enter K only through
/// their y-dependence at frozen accelerations (FORMULATION.md 7).
void force_tangents(const Model& model, Data& data, double t);

// ---- the parts, exposed for tests --------------------------------------------------------

/// The co-rotational path of a body with full_mass (see FullMass): mass matrix (and md, Jc, S
/// from it), then inertia forces into Qb, their tangents -dQ/dz, -dQ/dzd into Kb, Cb, and the
/// modal block of d(M(q) q_dd)/dy times scale into Tyy ([nq, nq]).
void fe_mass_matrix(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& z);
void fe_inertia_forces(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<VectorXd> Qb);
void fe_inertia_tangents(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<MatrixXd> Kb,
                         Eigen::Ref<MatrixXd> Cb);
void fe_modal_acceleration_tangent(const Body& b, BodyData& bd, double scale, Eigen::Ref<MatrixXd> Tyy);

/// Velocity-dependent inertia forces of one body (local vector, nb) added to Qb.
void body_inertia_forces(const Body& b, const BodyData& bd, const Eigen::Ref<const VectorXd>& zd,
                         Eigen::Ref<VectorXd> Qb);
/// Their tangents -dQ/dz, -dQ/dzd added to Kb, Cb ([nb, nb]).
void body_inertia_tangents(const Body& b, const BodyData& bd, const Eigen::Ref<const VectorXd>& zd,
                           Eigen::Ref<MatrixXd> Kb, Eigen::Ref<MatrixXd> Cb);
/// The forces and moments (body frame K, about the node) that the joints and motions apply at
/// each stiffening interface of each integrated flexible body, into bd.iface_load, from the
/// current multipliers and the last evaluated constraint Jacobian (FORMULATION.md 7).
void interface_loads(const Model& model, Data& data);
/// The load of one force element at the stiffening interfaces its markers m1, m2 sit on (-1: no
/// marker), into bd.iface_load: constructed before the element adds its force to data.Q, it keeps
/// the frame entries of Q of those bodies; add_to_interfaces() turns what the element added
/// there into the interface's F, M (FORMULATION.md 7). Call after interface_loads.
class InterfaceLoadCapture {
 public:
  InterfaceLoadCapture(const Model& model, const Data& data, int m1, int m2);
  InterfaceLoadCapture(const Model& model, const Data& data, const Marker* m1, const Marker* m2);
  void add_to_interfaces(const Model& model, Data& data) const;

 private:
  struct Side {
    int body = -1, node = -1, slot = -1;
    Eigen::Matrix<double, 12, 1> Q0 = Eigen::Matrix<double, 12, 1>::Zero();
  };
  Side side_[2];
};
/// bd.G1 = sum_k y_k M1[k] and bd.X1 (column k = M1[k] y) of a body with Ke/M1.
void modal_stress_terms(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y);
/// Gravity, elastic, damping and stiffening forces of one body.
void body_applied_forces(const Body& b, BodyData& bd, const Vector3d& gravity, const Eigen::Ref<const VectorXd>& z,
                         const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<VectorXd> Qb);
/// The load-case stiffening's dependence on the frame's accelerations (-dQ_y/dq_dd, added as is)
/// and spin (-dQ_y/dq_d, times kv) at frozen A and y, into the body's block Wb of the step's
/// tangent M + kv C + kq K (FORMULATION.md 7). Needs body_applied_forces at the same state.
void body_stiffening_rate_tangents(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y,
                                   const Eigen::Ref<const VectorXd>& yd, double kv, Eigen::Ref<MatrixXd> Wb);
/// The tangents -dQ/dz, -dQ/dz_dot of body_applied_forces at the body's coordinates z, rates zd
/// (the same as those forces were evaluated at), added to the body's blocks Kb, Cb.
void body_applied_tangents(const Body& b, const BodyData& bd, const Vector3d& gravity, const Eigen::Ref<const VectorXd>& z,
                           const Eigen::Ref<const VectorXd>& zd, Eigen::Ref<MatrixXd> Kb, Eigen::Ref<MatrixXd> Cb);

}  // namespace ffr::runtime
