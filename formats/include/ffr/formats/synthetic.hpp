#pragma once
// Synthetic SID bodies for tests: an independent oracle for everything that reads a SID.
//
// from_shapes() builds every SID member of a body made of point masses by *direct sums over
// the points*, written straight from the definitions of formats/SPEC.md (sections 6-8); it does not go through the integral -> member formulas
// the preprocessor uses, so the two can check each other.
//
// spring_chain() is a physically meaningful flexible body: a straight chain of lumped masses
// joined by Euler-Bernoulli beam segments (axial + bending in two planes, no torsion), reduced
// to its lowest elastic modes. It also returns the full, unreduced system (ChainModel) so a
// consumer can integrate or eigen-solve the same body independently and compare.

#include "ffr/formats/sid.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace ffr::formats::synthetic {

/// One mass point of the body. `inertia` is about the point's own centre, in the body frame;
/// a nonzero inertia gives the point rotational DOFs (Psi rows) that carry kinetic energy.
struct PointMass {
  double m = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();          ///< undeformed position in K [m]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();    ///< about the point's centre [kg m^2]
};

/// A point exported as a SID node (/nodes) under `name`.
struct ExportedNode {
  std::string name;
  Index point = 0;
};

/// Builds a Sid from point masses and mode shapes.
///  - Phi: [3n, nq], rows 3p..3p+2 are the translations of point p for each mode.
///  - Psi: [3n, nq] small rotations of each point, or an empty matrix (no rotations).
///  - omega_rad_s: [nq] circular frequencies; Ke = diag(omega^2), De = diag(2 zeta omega).
/// The shapes are first M-orthonormalised (M = sum m_p Phi_p^T Phi_p + Psi_p^T I_p Psi_p) by
/// Gram-Schmidt in the given order, so shapes that are already M-orthogonal are only rescaled;
/// then Me = I. Every member is a direct sum over the points. The rotary part (sum I_p,
/// sum Psi_p^T I_p, sum Psi_p^T I_p Psi_p) enters J.M0, Cr.M0 and Me only (SPEC.md, "rotary
/// part"). Throws std::invalid_argument on inconsistent sizes, m_p <= 0, or an M-singular set.
Sid from_shapes(const std::vector<PointMass>& masses, const Eigen::MatrixXd& Phi, const Eigen::MatrixXd& Psi,
                const Eigen::VectorXd& omega_rad_s, const std::vector<ExportedNode>& nodes,
                const std::string& reference = "free", double damping_ratio = 0.0);

/// Parameters of spring_chain(). Units SI.
///
/// The chain: `points` mass points on the line start + s e_x, s in [0, length], equally spaced
/// h = length/(points-1). Lumped masses: mass/(points-1) at interior points, half that at the
/// two ends (a uniform bar of total `mass`). Consecutive points are joined by a 2-node
/// Euler-Bernoulli beam element (the exact cubic-Hermite stiffness): axial EA, bending about
/// the local y axis EIy (displacement w along z, rotation theta_y = -dw/dx) and about z EIz
/// (v along y, theta_z = dv/dx). There is no torsion: the rotation about x carries neither
/// stiffness nor mass and is left out. The nodal rotations carry no mass, so they are
/// condensed out statically, which is exact for the eigenproblem: the unreduced system is
/// M u'' + K u = f on the 3n translations (ChainModel::M, ChainModel::K), and the rotations
/// follow as theta = R u (ChainModel::rotation_recovery).
///
/// clamped = false: free-free; the 5 rigid-body modes (3 translations, 2 rotations about y
/// and z; a rotation about the chain's own axis moves no mass) are removed exactly by solving
/// the eigenproblem in their M-orthogonal complement, so Ct.M0 = Cr.M0 = 0 to rounding.
/// clamped = true: point 0 is held (translations and rotations); reference "clamped:A".
/// The lowest `modes` elastic modes are kept. Exported nodes default to "A" = point 0 and
/// "B" = last point; both are also interfaces (coupling "rigid", group = name).
///
/// stiffening = true adds /stiffening computed from the same model (SPEC.md section
/// "stiffening"): for each unit load case (frame acceleration e_c: load -m_p e_c; angular
/// acceleration e_c: -m_p e_c x c_p; each omega_bar product j: -m_p C_j c_p; unit force /
/// moment at each interface node) the static deflection under the reference conditions (free:
/// inertia relief, i.e. the load's rigid-body part is taken by the frame's acceleration) gives
/// the axial force N_e = EA (u_b - u_a).e_x / h of each segment, whose geometric stiffness on
/// the translations is the string form N_e/h (I - e_x e_x^T) [[1,-1],[-1,1]]; then
/// K0[k](i) = Phi_i^T K_G Phi_k. A moment about the chain axis loads nothing (no torsion).
/// It also adds /sid/Ke/M1 with the same string K_G, for the forces of each mode's own
/// stretch: Ke.M1[k] = Phi^T K_G(N(Phi_k)) Phi.
struct ChainParams {
  int points = 11;
  double length = 1.0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  double mass = 1.0;
  double EA = 1.0e6;
  double EIy = 1.0;
  double EIz = 1.0;
  bool clamped = false;
  int modes = 4;
  double damping_ratio = 0.0;
  bool stiffening = false;
  /// Exported nodes (name, point index; a negative index counts from the end: -1 = last).
  std::vector<std::pair<std::string, int>> nodes = {{"A", 0}, {"B", -1}};
};

/// The unreduced chain, for independent checks. DOF 3p+a is the translation of point p along
/// axis a (a = x, y, z). Fixed DOFs (clamped point 0) have zero rows and columns in K.
struct ChainModel {
  ChainParams params;
  std::vector<PointMass> points;
  Eigen::MatrixXd M;                  ///< [3n,3n] diagonal lumped mass
  Eigen::MatrixXd K;                  ///< [3n,3n] condensed stiffness (rotations eliminated)
  std::vector<Index> free_dofs;       ///< DOFs that move (all, or all but point 0's)
  Eigen::MatrixXd rotation_recovery;  ///< [3n,3n] small rotations of every point = R u
  Eigen::VectorXd omega;              ///< all elastic circular frequencies, ascending [rad/s]
  Eigen::MatrixXd Phi;                ///< [3n, n_el] all elastic modes, M-orthonormal
  Eigen::MatrixXd Psi;                ///< [3n, n_el] their small rotations (x component 0)

  /// Static deflection under load f [3n] with the reference conditions (clamped, or free with
  /// inertia relief): u = sum over all elastic modes Phi_j Phi_j^T f / omega_j^2.
  Eigen::VectorXd static_deflection(const Eigen::VectorXd& f) const;
  /// Axial force of each of the n-1 segments for a deflection u.
  Eigen::VectorXd axial_forces(const Eigen::VectorXd& u) const;
  /// Geometric stiffness [3n,3n] of the segments carrying axial forces N (string form).
  Eigen::MatrixXd geometric_stiffness(const Eigen::VectorXd& N) const;
  /// Load vector of unit omega_bar product j (OmegaBar order): f_p = -m_p C_j c_p, with
  /// w x (w x c) = sum_j omega_bar_j C_j c.
  Eigen::VectorXd centrifugal_load(int j) const;
};

struct Chain {
  Sid sid;
  ChainModel model;
};

/// Builds the chain and its reduced SID. Throws std::invalid_argument on bad parameters
/// (points < 2, nonpositive length/mass/stiffness, modes outside 1..number of elastic modes).
Chain spring_chain(const ChainParams& params);

/// The matrix C_j with w x (w x c) = sum_j omega_bar_j C_j c, omega_bar in OmegaBar order.
Eigen::Matrix3d centrifugal_matrix(int j);

}  // namespace ffr::formats::synthetic
