#pragma once
// The part file (input of ffr-reduce), validated. Every field is documented in
// preproc/PART_FILE.md; docs/contract.md lists those outside scripts rely on.

#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/solver/mumps_options.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ffr::preproc {

/// A consistent unit system: inputs are read in it and the SID is written in it.
struct Units {
  std::string length = "m", mass = "kg", time = "s";
};

/// Extension: a named group made from geometric entities, for geometry without physical
/// groups (STEP, BREP): entities of dimension `dim` listed by tag or inside a bounding box.
struct GroupDef {
  std::string name;
  int dim = 2;
  std::vector<int> entities;
  std::optional<std::array<double, 6>> box;  ///< xmin, ymin, zmin, xmax, ymax, zmax
};

struct MeshSpec {
  double size = 0;   ///< target element size (0: gmsh default)
  int order = 1;     ///< 1 or 2
  bool optimize = true;
  /// Wall-clock limit of gmsh's reading and meshing [s]; past it gmsh is stopped and the part
  /// refused. Generous: the mesh stage of a 1M-DOF TET10 plate takes seconds (gmsh_module.cpp).
  double time_limit_s = 600;
};

struct SolidProps {
  std::string group;
  Material mat;
};

struct ShellProps {
  std::string group;
  double thickness = 0;
  Material mat;
};

struct BeamProps {
  std::string group;
  Material mat;
  double A = 0, Iy = 0, Iz = 0, J = 0;
  std::optional<double> ky, kz;  ///< shear factors; none = Euler–Bernoulli-like (rigid in shear)
  Eigen::Vector3d y_axis = Eigen::Vector3d::UnitZ();
};

struct PointMassSpec {
  std::string name;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  double mass = 0;
  Eigen::Vector3d com_offset = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  ///< about its own centre
  std::string interface;                               ///< hang on this interface instead of a node
};

struct InterfaceSpec {
  std::string name, group;
  std::string coupling = "rigid";  ///< "rigid" (RBE2-like) or "averaged" (RBE3-like)
  std::optional<Eigen::Vector3d> at;
};

struct ReductionSpec {
  enum class Method { Free, Clamped, CraigBampton };
  Method method = Method::Free;
  std::string interface;                ///< clamped: the held interface
  std::vector<std::string> interfaces;  ///< craig-bampton: all interfaces
  std::string frame;                    ///< craig-bampton: the held (frame) interface
  int modes = 0;                        ///< number of eigenmodes
  std::optional<double> max_frequency_hz;
  bool orthonormalize = false;          ///< craig-bampton: orthonormalize the whole basis
  std::string backend = "block";        ///< "block", "spectra", "arpack" or "slepc"
  std::string factorization = "supernodal";  ///< "supernodal" or "cholmod" (FactorizationBackend)
  std::string dense_kernels = "auto";        ///< "auto", "blas" or "eigen" (DenseKernelChoice)
  std::uint64_t memory_limit_bytes = 0; ///< refuse factors above this (0: the machine's available memory)
  MumpsOptions mumps;                   ///< backend "slepc": MUMPS's ordering and out-of-core factors
};

struct DampingSpec {
  enum class Kind { None, Ratio, Rayleigh };
  Kind kind = Kind::None;
  double ratio = 0, alpha = 0, beta = 0;
};

/// Extension: a static preload whose stress prestresses the body (SID ksigma).
struct PreloadSpec {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< acceleration of gravity [length/time^2]
  struct Load {
    std::string interface;
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  };
  std::vector<Load> loads;
  bool empty() const { return gravity.isZero() && loads.empty(); }
};

struct OutputNodeSpec {
  std::string name;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
};

/// Extension: modal stress recovery (formats/SPEC.md section 12.1) at the nodes of a mesh
/// group, or at the solid nodes of the outer surface.
struct StressSpec {
  std::string group;     ///< a mesh physical group; empty with surface
  bool surface = false;  ///< the outer surface's solid nodes
};

/// Assembled stiffness and mass from another FE code instead of ffr's element matrices
/// (PART_FILE.md, "Assembled matrices"). The deck of `geometry` gives the nodes, their
/// coordinates, the sets and the elements that say which nodes carry DOFs.
struct MatrixInputSpec {
  enum class Format { MatrixMarket, Calculix, Abaqus, Dmig };
  Format format = Format::MatrixMarket;
  std::filesystem::path K, M;  ///< resolved against the part file's folder
  std::filesystem::path dofs;  ///< row i of K and M = line i: "node component" (CalculiX: node.component)
  std::string K_name = "KAAX", M_name = "MAAX";  ///< DMIG: the matrices' names in K and M
  bool given() const { return !K.empty(); }
};

struct PartSpec {
  std::filesystem::path file;      ///< the part file itself
  std::filesystem::path geometry;  ///< resolved against the part file's folder
  Units units;
  MeshSpec mesh;
  std::vector<GroupDef> groups;
  std::vector<SolidProps> materials;
  std::vector<ShellProps> shells;
  std::vector<BeamProps> beams;
  std::vector<PointMassSpec> point_masses;
  std::vector<InterfaceSpec> interfaces;
  ReductionSpec reduction;
  DampingSpec damping;
  bool stiffening = false;
  PreloadSpec preload;
  bool visual = true;
  std::vector<OutputNodeSpec> output_nodes;
  std::optional<StressSpec> stress;
  MatrixInputSpec matrices;  ///< not given(): ffr assembles its elements

  const InterfaceSpec* find_interface(const std::string& name) const;
};

/// Reads and validates a part file. Throws ffr::formats::FormatError naming the file and the
/// field for every problem (missing file, malformed JSON, unknown field, wrong type or sign,
/// an interface name used but not defined, ...). Group names are checked later against the mesh.
PartSpec load_part(const std::filesystem::path& path);

}  // namespace ffr::preproc
