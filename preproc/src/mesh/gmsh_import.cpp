// load_mesh and occ_mass_properties: the own MSH 4.1 reader where it applies, else gmsh's
// module (gmsh_module.hpp), its meshing and reading in a child process (mesh_child.hpp).
#include "ffr/preproc/mesh/gmsh_import.hpp"

#include "bdf_reader.hpp"
#include "gmsh_module.hpp"
#include "inp_reader.hpp"
#include "mesh_child.hpp"
#include "msh41_reader.hpp"

#include <optional>

namespace ffr::preproc {

namespace detail {

Mesh load_mesh_with_gmsh(const PartSpec& part, MeshReport* report, const MeshLog& log) {
  // Loaded here, before the fork: the child then only calls it.
  const GmshModule& gmsh = gmsh_module();
  const ChildLimit limit{part.mesh.time_limit_s, "mesh.time_limit_s of " + part.file.filename().string()};
  return load_in_child(part.geometry.string(), [&](MeshReport* r) { return gmsh.load_mesh(part, r, log); }, report,
                       limit);
}

}  // namespace detail

Mesh load_mesh(const PartSpec& part, MeshReport* report, const MeshLog& log) {
  // FE input decks are read here, never by gmsh (inp_reader.hpp, bdf_reader.hpp).
  if (detail::is_inp(part.geometry)) return detail::read_inp(part.geometry.string(), report);
  if (detail::is_bdf(part.geometry)) return detail::read_bdf(part.geometry.string(), report);
  // An ASCII MSH 4.1 file is read here when the part adds no groups of its own (those need
  // gmsh's entities, bounding boxes included); anything else goes to gmsh (msh41_reader.hpp).
  if (part.geometry.extension() == ".msh" && part.groups.empty())
    if (std::optional<Mesh> mesh = detail::read_msh41(part.geometry.string(), report)) return std::move(*mesh);
  return detail::load_mesh_with_gmsh(part, report, log);
}

GeometryMass occ_mass_properties(const std::filesystem::path& geometry) {
  return detail::gmsh_module().mass_properties(geometry);
}

}  // namespace ffr::preproc
