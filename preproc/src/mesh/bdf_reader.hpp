#pragma once
// Nastran bulk data (.bdf, .dat, .nas) as a part's geometry: GRID, CTETRA, CHEXA, CTRIA3,
// CQUAD4, CBAR, CONM2, MAT1, PSOLID, PSHELL, PBAR, SET1 and SPC1 (PART_FILE.md, "Nastran bulk
// data"), in small-field, large-field and free-field format with continuation lines.
//
// Read strictly, as the .inp reader: a card that would change the model and that ffr does not
// take is refused naming the file, the line and the card; only the cards listed as passed
// over there (solution requests, loads and constraints that only case control selects) are.
#include "deck_mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// Whether `file` is read as Nastran bulk data: .bdf, .dat, .nas (any case).
bool is_bdf(const std::filesystem::path& file);

/// The mesh of the bulk data: GRID nodes, the elements grouped by property id (groups
/// "pid<N>"), SET1 and SPC1 grids as node groups "set<N>" and "spc<N>", and "all".
/// Throws formats::FormatError naming the file, the line and the card.
Mesh read_bdf(const std::string& file, MeshReport* report);

/// The PSOLID, PSHELL and PBAR properties the elements use, with their MAT1 materials; a
/// property missing or refused is returned with its `problem`, an error only where the part
/// file gives no property for its group.
std::vector<DeckSection> read_bdf_sections(const std::string& file);

/// A CONM2 of the bulk data: a rigid mass on a grid (Quick Reference Guide, CONM2).
struct DeckPointMass {
  std::size_t eid = 0, grid = 0;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();      ///< the grid's position
  double mass = 0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< of the centre from the grid
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero(); ///< about the centre
  std::string where;                                 ///< "line N (CONM2 EID)"
};

/// The CONM2 masses of the bulk data (CID 0, blank or -1); CONM1 is refused.
std::vector<DeckPointMass> read_bdf_point_masses(const std::string& file);

}  // namespace ffr::preproc::detail
