#pragma once
// Test support for the reduction tests: temporary folders, running the command-line tools,
// meshing with the gmsh command line, and CalculiX (ccx) as an independent reference on the
// identical mesh.
#include "ffr/preproc/mesh/mesh.hpp"
#include "ffr/preproc/part/part.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::test {

/// A fresh folder under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  explicit TempDir(const std::string& tag);
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct RunResult {
  int status = -1;
  std::string output;  ///< stdout and stderr together
};
/// Runs a shell command, capturing its output.
RunResult run(const std::string& command);

std::filesystem::path bin(const std::string& tool);     ///< build/bin/<tool>
std::filesystem::path source(const std::string& rel);   ///< <repo>/<rel>

/// Writes a file.
void write_text(const std::filesystem::path& p, const std::string& text);

/// Meshes a .geo with the gmsh command line into `msh` (order 1 or 2, serendipity).
void gmsh_mesh(const std::filesystem::path& geo, const std::filesystem::path& msh, double size, int order);

/// Reduction specs of the HexGrid tests: clamped on `interface`, free-free, and Craig-Bampton
/// with interfaces L and R, L the frame.
preproc::ReductionSpec clamped_spec(const std::string& interface, int modes);
preproc::ReductionSpec free_free_spec(int modes);
preproc::ReductionSpec craig_bampton_spec(int modes);

/// nx x ny x nz HEX8 cells of a unit-spaced grid (slightly sheared so that no two elements are
/// equal), one material group "body", node groups "left" (x = 0) and "right" (x = nx), and a
/// part with a rigid interface L on the left and an averaged one R on the right.
struct HexGrid {
  preproc::Mesh mesh;
  preproc::PartSpec part;
  HexGrid(int nx, int ny, int nz);
};

// ---- CalculiX -------------------------------------------------------------------------

struct CcxModes {
  std::vector<double> frequency_hz;
  /// Participation factors: one row per mode, columns X, Y, Z, X-rot, Y-rot, Z-rot.
  Eigen::MatrixXd participation;
};

/// Runs ccx *FREQUENCY on the solid elements of `group` in `mesh` (C3D4/C3D10/C3D8/C3D20),
/// with the nodes of `fixed_group` held (empty: free-free), one isotropic material.
CcxModes calculix_frequency(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                            const std::string& fixed_group, int modes, const std::filesystem::path& workdir);

/// The same for shell (S4, S3; "thickness" = section) or beam (B31, rectangular "b x h" section
/// with the local 1-axis along `n1`) elements of `group`; `fixed_group` nodes held in all six DOFs.
struct CcxSection {
  std::string kind;  ///< "shell" or "beam"
  double thickness = 0, b = 0, h = 0;
  Eigen::Vector3d n1 = Eigen::Vector3d::UnitZ();
};
CcxModes calculix_frequency_structural(const preproc::Mesh& mesh, const preproc::Material& mat, const std::string& group,
                                       const CcxSection& section, const std::string& fixed_group, int modes,
                                       const std::filesystem::path& workdir);

}  // namespace ffr::test
