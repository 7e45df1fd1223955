// The gmsh module: everything of ffr-reduce that calls gmsh (gmsh 4.8's C++ API), in a shared
// module of its own (libexec/ffr/libffr-gmsh.so), loaded when a part needs gmsh
// (src/mesh/gmsh_module.hpp says why).
#include "mesh/gmsh_module.hpp"

#include "ffr/formats/h5.hpp"
#include "gmsh_session.hpp"
#include "mesh/node_order.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <unordered_map>

namespace ffr::preproc {
namespace {

using formats::FormatError;

// Runs a gmsh call and converts its exceptions (std::string in gmsh 4.8) into FormatError.
template <class F>
void gmsh_call(const std::string& file, const std::string& what, F&& f) {
  try {
    f();
  } catch (const std::string& s) {
    throw FormatError(file, "", what + ": " + s);
  } catch (const std::exception& e) {
    throw FormatError(file, "", what + ": " + e.what());
  } catch (int) {
    throw FormatError(file, "", what + ": " + detail::GmshSession::last_error());
  }
}

// Adds the part file's entity-based groups as physical groups (before meshing, so the
// mesher keeps them and getNodesForPhysicalGroup works).
void add_part_groups(const PartSpec& part) {
  for (const auto& g : part.groups) {
    std::vector<int> tags = g.entities;
    if (g.box) {
      const auto& b = *g.box;
      gmsh::vectorpair dimTags;
      gmsh::model::getEntitiesInBoundingBox(b[0], b[1], b[2], b[3], b[4], b[5], dimTags, g.dim);
      for (const auto& [d, t] : dimTags) tags.push_back(t);
    }
    gmsh::vectorpair all;
    gmsh::model::getEntities(all, g.dim);
    std::set<int> exist;
    for (const auto& [d, t] : all) exist.insert(t);
    for (int t : tags)
      if (!exist.count(t))
        throw FormatError(part.file.string(), "groups." + g.name,
                          "no entity of dimension " + std::to_string(g.dim) + " with tag " + std::to_string(t));
    if (tags.empty())
      throw FormatError(part.file.string(), "groups." + g.name,
                        "the box contains no entity of dimension " + std::to_string(g.dim));
    const int pg = gmsh::model::addPhysicalGroup(g.dim, tags);
    gmsh::model::setPhysicalName(g.dim, pg, g.name);
  }
}

// "all": every entity of the highest dimension, unless the geometry names a group "all".
void add_default_group() {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [d, t] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(d, t, name);
    if (name == "all") return;
  }
  for (int dim = 3; dim >= 1; --dim) {
    gmsh::vectorpair ents;
    gmsh::model::getEntities(ents, dim);
    if (ents.empty()) continue;
    std::vector<int> tags;
    for (const auto& [d, t] : ents) tags.push_back(t);
    const int pg = gmsh::model::addPhysicalGroup(dim, tags);
    gmsh::model::setPhysicalName(dim, pg, "all");
    return;
  }
}

Mesh extract(const std::string& file) {
  Mesh mesh;
  std::vector<std::size_t> tags;
  std::vector<double> coord, param;
  gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, false, false);
  if (tags.empty()) throw FormatError(file, "", "the mesh has no nodes");
  // Nodes numbered along a space-filling curve, not in gmsh's order (node_order.hpp); gmsh's
  // tags are distinct.
  std::unordered_map<std::size_t, Index> index;
  detail::number_nodes(tags, coord, mesh, index);

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [dim, pg] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, pg, name);
    if (name.empty()) name = std::to_string(pg);

    // Node set of the group: the nodes of its elements, which is what gmsh's
    // getNodesForPhysicalGroup returns too; but gmsh builds it in an std::set of every element
    // node (5 s of a 7 s mesh stage for a 1M-DOF TET10 plate, twice with the default group
    // "all"), and a sort of the connectivity read here anyway takes a fraction of that.
    auto& set = mesh.node_groups[name];
    const auto finish_set = [&set] {
      std::sort(set.begin(), set.end());
      set.erase(std::unique(set.begin(), set.end()), set.end());
      set.shrink_to_fit();  // it held every element node (10x the distinct ones for TET10)
    };
    if (dim == 0) {
      std::vector<std::size_t> ntags;
      std::vector<double> ncoord;
      gmsh::model::mesh::getNodesForPhysicalGroup(dim, pg, ntags, ncoord);
      for (auto t : ntags) set.push_back(index.at(t));
      finish_set();
      continue;
    }
    std::vector<int> ents;
    gmsh::model::getEntitiesForPhysicalGroup(dim, pg, ents);
    std::map<int, std::size_t> block_of_type;  // gmsh type -> index in mesh.blocks
    for (int ent : ents) {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> etags, enodes;
      gmsh::model::mesh::getElements(types, etags, enodes, dim, ent);
      for (std::size_t k = 0; k < types.size(); ++k) {
        ElementType t;
        try {
          t = from_gmsh(types[k]);
        } catch (const std::invalid_argument& e) {
          throw FormatError(file, "group " + name, e.what());
        }
        auto [it, fresh] = block_of_type.try_emplace(types[k], mesh.blocks.size());
        if (fresh) mesh.blocks.push_back(ElementBlock{t, name, {}, {}});
        ElementBlock* block = &mesh.blocks[it->second];
        block->tags.insert(block->tags.end(), etags[k].begin(), etags[k].end());
        for (auto nt : enodes[k]) block->conn.push_back(index.at(nt));
        set.insert(set.end(), block->conn.end() - static_cast<std::ptrdiff_t>(enodes[k].size()), block->conn.end());
      }
    }
    finish_set();
  }
  if (mesh.blocks.empty()) throw FormatError(file, "", "the mesh has no elements in any physical group");
  return mesh;
}

// Elements a mesh of this size would have, from the bounding boxes of the geometry's
// highest-dimensional entities: per entity c_D * prod_{i <= D} max(e_i, size) / size^D over
// its D largest extents e_i (c_3 = 6 sqrt 2 for regular tetrahedra, c_2 = 2.3 for triangles).
// An upper estimate of the volume, so of the count, for solids, good enough to refuse a size
// that is orders of magnitude too small before gmsh spends all memory on it.
double estimated_elements(double size) {
  for (int dim = 3; dim >= 1; --dim) {
    gmsh::vectorpair ents;
    gmsh::model::getEntities(ents, dim);
    if (ents.empty()) continue;
    const double c = dim == 3 ? 6 * std::sqrt(2.0) : dim == 2 ? 2.3 : 1.0;
    double n = 0;
    for (const auto& [d, t] : ents) {
      double b[6];
      gmsh::model::getBoundingBox(d, t, b[0], b[1], b[2], b[3], b[4], b[5]);
      std::array<double, 3> e{b[3] - b[0], b[4] - b[1], b[5] - b[2]};
      std::sort(e.begin(), e.end(), std::greater<>());
      double cells = c;
      for (int i = 0; i < dim; ++i) cells *= std::max(e[static_cast<std::size_t>(i)], size) / size;
      n += cells;
    }
    return n;
  }
  return 0;
}

// More than any machine this runs on can factorize (a 1M-DOF TET10 mesh has about 250 000
// elements and needed 14 GB).
constexpr double kMaxElements = 2e7;

Mesh load_mesh_here(const PartSpec& part, MeshReport* report, const MeshLog& log) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string file = part.geometry.string();
  std::error_code ec;
  if (!std::filesystem::exists(part.geometry, ec)) throw FormatError(file, "", "no such file");
  detail::GmshSession session;
  const bool is_msh = part.geometry.extension() == ".msh";

  gmsh_call(file, "cannot read", [&] { gmsh::open(file); });
  Mesh mesh;
  if (is_msh) {
    gmsh_call(file, "cannot use mesh", [&] {
      add_part_groups(part);
      add_default_group();
    });
  } else {
    double n = 0;
    if (part.mesh.size > 0) {
      gmsh_call(file, "cannot read", [&] { n = estimated_elements(part.mesh.size); });
      if (n > kMaxElements) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%g gives about %.2g elements on this geometry (at most %.0e are meshed): a larger size",
                      part.mesh.size, n, kMaxElements);
        throw FormatError(part.file.string(), "mesh.size", buf);
      }
    }
    if (log) {
      char estimate[64] = "";
      if (n > 0) std::snprintf(estimate, sizeof estimate, ", at most about %.2g elements", n);
      log("meshing " + part.geometry.filename().string() + " (size " + std::to_string(part.mesh.size) + ", order " +
          std::to_string(part.mesh.order) + estimate + ")");
    }
    gmsh_call(file, "meshing failed", [&] {
      add_part_groups(part);
      add_default_group();
      gmsh::model::mesh::clear();
      if (part.mesh.size > 0) {
        gmsh::option::setNumber("Mesh.MeshSizeMax", part.mesh.size);
        gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
      }
      gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);  // serendipity 20/15/8-node elements
      gmsh::option::setNumber("Mesh.Optimize", part.mesh.optimize ? 1 : 0);
      gmsh::model::mesh::generate(3);
      if (part.mesh.order == 2) gmsh::model::mesh::setOrder(2);
    });
  }
  gmsh_call(file, "cannot extract mesh", [&] { mesh = extract(file); });

  if (report) {
    report->element_counts = element_counts(mesh);
    report->nodes = mesh.num_nodes();
    report->meshed = !is_msh;
    report->gmsh_log = detail::GmshSession::log_text();
    report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return mesh;
}

GeometryMass mass_properties(const std::filesystem::path& geometry) {
  const std::string file = geometry.string();
  detail::GmshSession session;
  GeometryMass g;
  gmsh_call(file, "cannot read", [&] { gmsh::open(file); });
  gmsh_call(file, "OpenCASCADE mass properties failed", [&] {
    gmsh::vectorpair vols;
    gmsh::model::occ::getEntities(vols, 3);
    if (vols.empty()) throw std::string("no OpenCASCADE volume in the geometry");
    // Combine the volumes' properties: total volume, centroid, parallel-axis shift.
    Eigen::Matrix3d J_O = Eigen::Matrix3d::Zero();
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    for (const auto& [d, t] : vols) {
      double v = 0, x = 0, y = 0, z = 0;
      std::vector<double> I;
      gmsh::model::occ::getMass(3, t, v);
      gmsh::model::occ::getCenterOfMass(3, t, x, y, z);
      gmsh::model::occ::getMatrixOfInertia(3, t, I);
      const Eigen::Vector3d c(x, y, z);
      Eigen::Matrix3d Ic;
      for (int r = 0; r < 3; ++r)
        for (int s = 0; s < 3; ++s) Ic(r, s) = I[3 * r + s];
      // OCC's matrix of inertia is about the centre of mass; shift to O.
      J_O += Ic + v * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
      g.volume += v;
      first += v * c;
    }
    g.centroid = first / g.volume;
    const Eigen::Vector3d& c = g.centroid;
    g.inertia_about_centroid = J_O - g.volume * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  });
  return g;
}

}  // namespace

}  // namespace ffr::preproc

extern "C" __attribute__((visibility("default"))) const ffr::preproc::detail::GmshModule* ffr_gmsh_module_v1() {
  static const ffr::preproc::detail::GmshModule module{ffr::preproc::detail::kGmshModuleAbi, &ffr::preproc::load_mesh_here,
                                                       &ffr::preproc::mass_properties};
  return &module;
}
