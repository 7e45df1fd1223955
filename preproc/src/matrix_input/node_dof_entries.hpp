#pragma once
// Matrices whose entries name their rows by node and DOF rather than by a row number with a
// separate DOF map: Abaqus's *MATRIX GENERATE output and Nastran's DMIG (PART_FILE.md,
// "Assembled matrices"). The readers check the syntax; matrix_input.cpp lays the entries onto
// the deck's DOFs and checks them as for every other format.
#include <filesystem>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

struct NodeDofEntry {
  long long row_node, row_dof, col_node, col_dof;
  double value;
  int line;  ///< of the file (DMIG: the card's first line)
};

/// Abaqus *MATRIX GENERATE with *MATRIX OUTPUT, FORMAT=MATRIX INPUT (job_STIF1.mtx,
/// job_MASS1.mtx): "row node, row DOF, column node, column DOF, value" a line, '**' comments.
/// Throws formats::FormatError naming the file, the line and what was expected.
std::vector<NodeDofEntry> read_abaqus_matrix(const std::filesystem::path& file);

/// The DMIG matrix `name` of a Nastran punch or bulk-data file: its header card (field 3 = 0,
/// IFO 6 symmetric or 1 square, TIN 1 or 2 real) and its column cards "DMIG, NAME, GJ, CJ, ,
/// G1, C1, A1, , G2, C2, A2, ..." in small-, large- or free-field form. `square` is set for
/// IFO 1 (both triangles given). Throws formats::FormatError naming the file, the card's line and
/// what was expected.
std::vector<NodeDofEntry> read_dmig_matrix(const std::filesystem::path& file, const std::string& name, bool& square);

}  // namespace ffr::preproc::detail
