#pragma once
// Abaqus/CalculiX input decks (.inp) as a part's geometry: nodes, elements, element and node
// sets, and the isotropic materials and solid/shell sections of the deck (PART_FILE.md,
// "Abaqus and CalculiX decks").
//
// The deck is read strictly: a keyword that would change the model and that ffr does not
// take (an element type outside its library, *BOUNDARY in the model data, *INCLUDE, parts and
// instances, ...) is refused naming the file and the line, never skipped; only the keywords
// listed as informational there (*HEADING, *PREPRINT, the history data from *STEP to
// *END STEP, thermal material data) are passed over.
#include "deck_mesh.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace ffr::preproc::detail {

/// Whether `file` is read as a deck: .inp (any case).
bool is_inp(const std::filesystem::path& file);

/// The mesh of the deck: its *NODE nodes numbered as gmsh_import numbers nodes, one element
/// block per element set and element type (gmsh node order), the group "all" of every element
/// of the highest dimension (unless a set is named so), and node groups for every element set
/// (its elements' nodes) and node set. Throws formats::FormatError naming the file and line.
Mesh read_inp(const std::string& file, MeshReport* report);

/// The deck's solid and shell sections with their materials (DeckSection) (the whole deck is checked as
/// read_inp checks it, without building the mesh). Throws formats::FormatError likewise.
std::vector<DeckSection> read_inp_sections(const std::string& file);

}  // namespace ffr::preproc::detail
