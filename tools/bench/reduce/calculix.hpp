#pragma once
// CalculiX (ccx) side of the comparison: a *FREQUENCY input deck written from the very mesh
// ffr-reduce reads (same nodes, same elements, same material, the same clamped nodes), and
// the eigenvalue table of the .dat file it prints.

#include "ffr/preproc/mesh/mesh.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::bench {

struct IsoMaterial {
  double E = 2.1e11, nu = 0.3, rho = 7850;
};

/// Writes `inp`: every 3D element of `group` (C3D4/C3D10/C3D8/C3D20, Abaqus node order),
/// the nodes of `fixed_group` held in x, y, z, one material, and a *FREQUENCY step for `modes`.
void write_frequency_deck(const preproc::Mesh& mesh, const std::string& group, const std::string& fixed_group,
                          const IsoMaterial& mat, int modes, const std::filesystem::path& inp);

/// Frequencies [Hz] of the "E I G E N V A L U E   O U T P U T" table of a ccx .dat file
/// (empty if there is none).
std::vector<double> read_ccx_frequencies(const std::filesystem::path& dat);

}  // namespace ffr::bench
