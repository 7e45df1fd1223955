#pragma once
// ASCII MSH 4.1 files read here, without gmsh (gmsh_import.cpp).
//
// Why: reading a .msh through gmsh costs a process (gmsh runs in a child, mesh_child.hpp), gmsh's
// start and its parser: 0.16-0.25 s of the 100k-DOF plate of tools/bench/reduce, whose mesh
// file this reads in a fraction of that. The result is the mesh gmsh's import gives (the same
// nodes in the same order, the same blocks, node groups and tags: tests compare the two), so
// the reader only takes what it can give exactly that way, and leaves the rest to gmsh:
// another version or a binary file, parametric nodes, partitioned meshes, an element type
// ffr does not know, two orders of one element family in one entity, anything it cannot
// parse (gmsh then reports it, as before).
#include "ffr/preproc/mesh/gmsh_import.hpp"

#include <optional>
#include <string>

namespace ffr::preproc::detail {

/// The mesh of an ASCII MSH 4.1 file with its physical groups (and the group "all" of the
/// highest dimension's entities unless a group has that name), or nothing where gmsh must read
/// the file (see above). Fills `report` (no gmsh log) when it returns a mesh.
std::optional<Mesh> read_msh41(const std::string& file, MeshReport* report);

/// The mesh through gmsh alone, as load_mesh gave it before this reader (gmsh_import.cpp): for
/// the tests that compare the two.
Mesh load_mesh_with_gmsh(const PartSpec& part, MeshReport* report, const MeshLog& log = {});

}  // namespace ffr::preproc::detail
