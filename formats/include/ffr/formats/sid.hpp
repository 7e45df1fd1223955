#pragma once
// The in-memory form of a SID ("standard input data") file: the reduced flexible body that
// ffr-reduce writes and the runtime reads. Names, shapes, meaning and mathematics follow
// formats/SPEC.md (docs/contract.md lists the names outside scripts rely on).
//
// Conventions used throughout:
//  - nq = number of modes, N = number of exported nodes.
//  - Every Taylor member is X(q) = M0 + sum_k q_k M1[k]; M1 is indexed by the mode k first,
//    exactly like the file (C order). A member with a 3-index M1 of shape [nq, a, b] is held
//    as std::vector (size nq) of (a x b) matrices.
//  - All quantities are resolved in the body frame K (the mesh frame), about its origin O.

#include "ffr/formats/modal_stress.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ffr::formats {

using Index = std::int64_t;
using MatX3 = Eigen::Matrix<double, Eigen::Dynamic, 3>;
using MatX6 = Eigen::Matrix<double, Eigen::Dynamic, 6>;

/// 2: content checksums (SPEC.md section 4). Version 1 files are still read, with a warning.
inline constexpr int kFormatVersion = 2;
inline constexpr const char* kFormatName = "ffr-sid";

enum class ModeType { Normal, Constraint };

const char* to_string(ModeType t);
/// Parses "normal" / "constraint"; throws std::invalid_argument otherwise.
ModeType mode_type_from_string(const std::string& s);

/// Column order of the centrifugal terms: omega_bar = (wx^2, wy^2, wz^2, wx*wy, wy*wz, wx*wz).
enum OmegaBar : int { kXX = 0, kYY = 1, kZZ = 2, kXY = 3, kYZ = 4, kXZ = 5 };

/// /refmod: what the reduced body is.
struct RefMod {
  double mass = 0.0;                 ///< m [kg]
  Eigen::VectorXd frequency_hz;      ///< [nq]; Rayleigh quotient for a static (constraint) mode
  std::vector<ModeType> mode_type;   ///< [nq]
  std::string reference = "free";    ///< "free", "clamped:<interface>" or "craig-bampton"
};

/// /integrals: the minimal generating set (SPEC.md section 8). These cover the
/// distributed (translational) mass only; point rotary inertia is in Rotary.
struct Integrals {
  Eigen::Vector3d rdm = Eigen::Vector3d::Zero();   ///< int c dm                 [3]
  Eigen::Matrix3d rrdm = Eigen::Matrix3d::Zero();  ///< int c c^T dm             [3,3]
  Eigen::Matrix3Xd Pdm;                            ///< int Phi dm               [3,nq]
  std::array<Eigen::Matrix3Xd, 3> rPdm;            ///< rPdm[a] = int c_a Phi dm [3,3,nq]
  std::array<std::array<Eigen::MatrixXd, 3>, 3> PPdm;  ///< PPdm[a][b] = int Phi_a^T Phi_b dm [3,3,nq,nq]
};

/// /integrals/rotary: the rotary parts of nodes with rotational DOFs (SPEC.md section 7),
/// kept apart from the distributed-mass integrals. Zero for a body without them.
struct Rotary {
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();  ///< sum I_p                 [3,3]
  MatX3 PsiI;                                   ///< sum Psi_p^T I_p         [nq,3]
  Eigen::MatrixXd PsiIPsi;                      ///< sum Psi_p^T I_p Psi_p   [nq,nq]
};

/// Geometric stiffening (SPEC.md section 10), stored apart from the pure-inertia terms
/// so the runtime can switch it off. Present only when the part asked for it.
struct Stiffening {
  std::vector<MatX3> K0t;   ///< [nq][nq,3]: K0t[k](i,c), scales frame acceleration a_c
  std::vector<MatX3> K0r;   ///< [nq][nq,3]: K0r[k](i,c), scales angular acceleration alpha_c
  std::vector<MatX6> K0om;  ///< [nq][nq,6]: K0om[k](i,j), scales omega_bar_j
  /// Per interface (name): unit forces and moments at the interface node (optional).
  struct Interface {
    std::string name;
    std::vector<MatX3> K0F;  ///< [nq][nq,3]
    std::vector<MatX3> K0M;  ///< [nq][nq,3]
  };
  std::vector<Interface> interfaces;
};

/// Prestress from a static preload (SPEC.md section 6: ksigma). Zero without prestress.
struct KSigma {
  Eigen::VectorXd M0;  ///< [nq]
  Eigen::MatrixXd M1;  ///< [nq,nq]
};

/// One exported node (SID "frame").
struct Node {
  std::string name;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();     ///< c_p, undeformed position in K
  Eigen::Matrix3Xd phi;                                 ///< [3,nq] translational slice
  Eigen::Matrix3Xd psi;                                 ///< [3,nq] small-rotation slice
  Eigen::Matrix3d AP0 = Eigen::Matrix3d::Identity();    ///< node orientation in K
};

/// An interface of the part (a 6-DOF node tied to a group of mesh nodes).
struct Interface {
  std::string name;
  Index node = -1;            ///< index into Sid::nodes
  std::string coupling;       ///< "rigid" or "averaged"
  std::string group;          ///< the physical group it was made from
};

/// Optional surface mesh with the mode shapes on it, for viewers.
struct Visual {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> vertices;        ///< [Nv,3]
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor> triangles; ///< [Nt,3]
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> modes;  ///< [nq][Nv,3]
  bool empty() const { return vertices.rows() == 0; }
};

/// Where the file came from. Free-form attributes are kept; the named ones have fixed keys.
struct Provenance {
  std::string generator;             ///< e.g. "ffr 0.1.0" (also a root attribute)
  std::string part_sha256;           ///< hash of the input part file
  std::string mesh_sha256;           ///< hash of the mesh (node coordinates and connectivity)
  std::string reduction_method;      ///< "free", "clamped", "craig-bampton", "synthetic", ...
  std::string reduction_parameters;  ///< JSON text
  std::string damping_model;         ///< e.g. "none", "ratio 0.01", "rayleigh alpha=.. beta=.."
  std::map<std::string, Index> element_counts;       ///< element type name -> count
  std::map<std::string, std::string> mass_model;     ///< SID group -> mass model that produced it
  std::map<std::string, std::string> extra;          ///< anything else, as text
};

/// The whole reduced body.
struct Sid {
  // Root attributes.
  std::string units_length = "m";
  std::string units_mass = "kg";
  std::string units_time = "s";

  RefMod refmod;

  // SID members (SPEC.md section 6).
  struct { Eigen::Vector3d M0 = Eigen::Vector3d::Zero(); MatX3 M1; } mdCM;  ///< M1: [nq,3]
  struct { Eigen::Matrix3d M0 = Eigen::Matrix3d::Zero(); std::vector<Eigen::Matrix3d> M1; } J;
  struct { MatX3 M0; } Ct;                                   ///< [nq,3]; M1 is Stiffening::K0t
  struct { MatX3 M0; std::vector<MatX3> M1; } Cr;            ///< M0 [nq,3]; M1[k](i,c) = Kr
  Eigen::MatrixXd Me, Ke, De;                                ///< [nq,nq]
  /// Optional /sid/Ke/M1 [nq][nq,nq] (SPEC.md section 10): KeM1[k](i,j) = Phi_i^T K_G(sigma_k) Phi_j,
  /// sigma_k the linear stress of mode k's displacement; symmetric in (i,j), not in k. The
  /// cubic strain energy is 1/2 sum_k q_k q^T KeM1[k] q. Empty when the file has none.
  std::vector<Eigen::MatrixXd> KeM1;
  std::vector<Eigen::Matrix3d> Gr;                           ///< [nq][3,3]
  std::vector<MatX3> Ge;                                     ///< [nq][nq,3]: Ge[k](i,c)
  struct { MatX6 M0; std::vector<MatX6> M1; } Oe;            ///< M0 [nq,6]; M1[k] [nq,6]
  KSigma ksigma;

  Integrals integrals;
  Rotary rotary;
  std::optional<Stiffening> stiffening;

  std::vector<Node> nodes;
  std::vector<Interface> interfaces;
  Visual visual;
  /// Optional /stress (SPEC.md section 12.1): written by write_sid when set, never read by
  /// read_sid (the runtime does not need it); read_modal_stress() reads it.
  std::optional<ModalStress> stress;
  Provenance provenance;

  Index nq() const { return refmod.frequency_hz.size(); }
  Index num_nodes() const { return static_cast<Index>(nodes.size()); }
  /// Index of the node with this name, or -1.
  Index find_node(const std::string& name) const;

  /// Sizes every member for nq modes (zero-filled), keeping scalars and nodes' names/origins.
  void resize(Index nq);
};

}  // namespace ffr::formats
