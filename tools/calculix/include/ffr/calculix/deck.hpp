#pragma once
// CalculiX (ccx) as an independent reference, shared by the tests and the benchmarks: a
// *FREQUENCY input deck written from the very mesh ffr-reduce reads (same nodes, same
// elements, same material, the same held nodes), and the eigenvalue table of its .dat file.

#include "ffr/preproc/mesh/mesh.hpp"

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace ffr::calculix {

struct IsoMaterial {
  double E = 2.1e11, nu = 0.3, rho = 7850;
};

/// The *NODE section of a deck: every mesh node (1-based ids), full precision.
void write_nodes(std::ostream& f, const preproc::Mesh& mesh);

/// Writes `inp`: every 3D element of `group` (C3D4/C3D10/C3D8/C3D20, Abaqus node order),
/// the nodes of `fixed_group` held in x, y, z (none if it is empty: free-free), one material,
/// and a *FREQUENCY step for `modes`. Throws std::runtime_error naming what is missing.
void write_frequency_deck(const preproc::Mesh& mesh, const std::string& group, const std::string& fixed_group,
                          const IsoMaterial& mat, int modes, const std::filesystem::path& inp);

inline const std::string kEigenvalueTable = "E I G E N V A L U E   O U T P U T";
inline const std::string kParticipationTable = "P A R T I C I P A T I O N   F A C T O R S";

/// The numeric rows after `title` in the text of a ccx .dat file: each row is a mode number
/// followed by `columns` values (returned without the mode number); the table ends at the
/// first other line after its first row. Empty if the title is absent.
std::vector<std::vector<double>> read_table(const std::string& text, const std::string& title, int columns);

/// Frequencies [Hz] of the "E I G E N V A L U E   O U T P U T" table in the text of a ccx
/// .dat file (empty if there is none).
std::vector<double> frequencies(const std::string& dat_text);

/// The same from the file (empty if there is no file).
std::vector<double> read_frequencies(const std::filesystem::path& dat);

}  // namespace ffr::calculix
