#pragma once
// The benchmark meshes, written with the gmsh command line and cached in the work folder:
//  - a thick steel plate with four through holes (240 x 120 x 30 mm), TET10, physical groups
//    "body" (volume) and "clamp" (the face x = 0); the mesh size is searched so that the
//    mesh has the requested number of DOF (3 per node) within a few percent;
//  - a thin-walled tube (R = 0.1 m, L = 1 m) of a structured QUAD4 grid, groups "skin" and
//    "clamp" (the ring at x = 0), sized for the requested number of DOF (6 per node).

#include <cstdint>
#include <filesystem>

namespace ffr::bench {

struct MeshCase {
  std::filesystem::path msh;
  std::int64_t nodes = 0;
  std::int64_t dof = 0;          ///< DOF before the clamp is applied (3 or 6 per node)
  double size = 0;               ///< gmsh mesh size (plate) or elements around the tube
  double mesh_seconds = 0;       ///< gmsh time (0 when reused from the cache)
  bool reused = false;
};

/// Plate mesh with about `target_dof` DOF in `workdir` (reused if already there).
MeshCase plate_mesh(const std::filesystem::path& workdir, std::int64_t target_dof);

/// Tube mesh with about `target_dof` DOF in `workdir` (reused if already there).
MeshCase tube_mesh(const std::filesystem::path& workdir, std::int64_t target_dof);

/// Number of nodes declared in the $Nodes section of a gmsh 4.1 ASCII file.
std::int64_t msh_node_count(const std::filesystem::path& msh);

}  // namespace ffr::bench
