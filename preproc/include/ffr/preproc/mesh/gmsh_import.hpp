#pragma once
// Geometry or mesh file -> Mesh, through the gmsh C++ API (gmsh 4.8).
//  - .msh: read as it is, never re-meshed.
//  - .geo, .step/.stp, .brep: meshed with the part's size and order (order 2 gives the
//    serendipity TET10/HEX20/WEDGE15/QUAD8 elements).
// Physical groups become element blocks and node sets under their names; part-file
// "groups" (extension for STEP/BREP without physical groups) are added before meshing.
// Every entity of the highest dimension also forms the group "all" (unless the geometry
// defines a group of that name), so STEP/BREP parts need no physical groups for materials.

#include "ffr/preproc/mesh/mesh.hpp"
#include "ffr/preproc/part/part.hpp"

#include <functional>
#include <map>
#include <string>

namespace ffr::preproc {

struct MeshReport {
  std::map<std::string, Index> element_counts;  ///< element type name -> count (all groups)
  Index nodes = 0;
  double seconds = 0;
  bool meshed = false;        ///< false when a .msh was read as it is
  std::string gmsh_log;       ///< gmsh's own messages (warnings), for --verbose
};

/// Exact mass properties of the geometry's volumes (OpenCASCADE through gmsh), density 1.
struct GeometryMass {
  double volume = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_about_centroid = Eigen::Matrix3d::Zero();  ///< of the volume (rho = 1)
};

using MeshLog = std::function<void(const std::string&)>;

/// Loads or meshes `part.geometry`. Throws formats::FormatError naming the geometry file
/// (unreadable file, gmsh errors, no elements, a part-file group with no entity).
Mesh load_mesh(const PartSpec& part, MeshReport* report = nullptr, const MeshLog& log = {});

/// OpenCASCADE mass properties of all volumes of a .step/.brep/.geo(OpenCASCADE) file.
GeometryMass occ_mass_properties(const std::filesystem::path& geometry);

}  // namespace ffr::preproc
