#pragma once
// The optional /stress group of a SID (formats/SPEC.md section 12.1): each mode's stress at
// chosen mesh nodes, for recovering stresses from a run's modal coordinates afterwards
// (sigma(t) = sum_k q_k(t) modes[k]). The runtime never loads it: read_sid() leaves it out of
// the Sid it returns (its content checksum is verified like every dataset's); tools read it
// with read_modal_stress().

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ffr::formats {

namespace h5 {
class Writer;
}

struct ModalStress {
  using RowsX3 = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  using RowsX6 = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;
  std::string selection;             ///< "surface" or "group:<name>" (the part file's request)
  std::string recovery;              ///< how nodal values were made from the elements (text)
  std::vector<std::int64_t> node;    ///< [Ns] mesh node tags (gmsh tags of the mesh file)
  RowsX3 position;                   ///< [Ns,3] undeformed node positions in K
  /// [nq][Ns,6]: Cauchy stress of unit q_k at each node, Voigt (xx, yy, zz, xy, yz, xz),
  /// tensor shear components, units of stress per [q].
  std::vector<RowsX6> modes;
  /// [Ns] where in the material each row is (StressLayer); empty: every row is a solid node
  /// (files without /stress/layer, written before shells carried stress or without shells).
  std::vector<std::int64_t> layer;
  /// [Ns,3] with `layer`: the unit shell normal at the node that defines "top" (z = +t/2
  /// along it); zero rows for solid nodes.
  RowsX3 normal;

  std::int64_t size() const { return static_cast<std::int64_t>(node.size()); }
  /// The layer of row i (kSolid when the file has no layers).
  std::int64_t layer_of(Eigen::Index i) const { return layer.empty() ? 0 : layer[static_cast<std::size_t>(i)]; }
};

/// Values of ModalStress::layer (SPEC.md section 12.1).
enum StressLayer : std::int64_t {
  kSolid = 0,        ///< the 3-D stress at a node of solid elements
  kShellTop = 1,     ///< shell surface at z = +t/2 along the node's normal
  kShellMiddle = 2,  ///< shell mid-surface (membrane stress and transverse shear)
  kShellBottom = 3,  ///< shell surface at z = -t/2
};

/// "solid", "top", "middle", "bottom"; throws std::invalid_argument for another value.
const char* layer_name(std::int64_t layer);

/// Throws std::invalid_argument naming the member if the sizes disagree with each other or
/// with nq, or a value is not finite.
void check_modal_stress(const ModalStress& s, std::int64_t nq);

/// Writes the group into an open SID writer (write_sid calls it when Sid::stress is set).
void write_modal_stress(h5::Writer& w, const ModalStress& s);

/// Reads /stress of a SID file strictly (shapes against nq of /refmod/frequency_hz, finite
/// values, content checksums of the whole file as read_sid checks them). nullopt if the file
/// has no /stress group. Throws FormatError naming the file and the dataset.
std::optional<ModalStress> read_modal_stress(const std::filesystem::path& path);

/// Von Mises equivalent stress of a Voigt stress (xx, yy, zz, xy, yz, xz).
double von_mises(const Eigen::Matrix<double, 6, 1>& s);
/// Principal stresses of a Voigt stress, descending (sigma_1 >= sigma_2 >= sigma_3).
Eigen::Vector3d principal_stresses(const Eigen::Matrix<double, 6, 1>& s);

}  // namespace ffr::formats
