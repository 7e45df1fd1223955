#include "faces.hpp"
#include "ffr/preproc/visual/visual.hpp"

#include <algorithm>
#include <map>
#include <unordered_map>

namespace ffr::preproc {

formats::Visual surface_with_modes(const FeModel& model, const Eigen::MatrixXd& Phi) {
  const Mesh& mesh = *model.mesh;
  // Faces seen once among solid elements are on the boundary; shell faces are all visible.
  // The faces are keyed by their sorted node tags, not node indices, so the surface's order
  // (faces, then vertices in order of first use) follows the mesh file and not the internal
  // node numbering (a space-filling curve since the sixth session; with the indices, a SID of
  // an unchanged part had its surface renumbered).
  std::map<std::vector<std::size_t>, std::pair<std::vector<Index>, int>> solid_faces;  // sorted tags -> (ordered face, count)
  std::vector<std::vector<Index>> faces;
  for (const auto& pb : model.blocks) {
    const auto& blk = mesh.blocks[pb.block];
    if (pb.kind == ElementKind::Beam) continue;
    const auto local = detail::element_faces(blk.type);
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = blk.element(e);
      for (const auto& f : local) {
        std::vector<Index> face;
        for (int i : f) face.push_back(c[i]);
        if (pb.kind == ElementKind::Shell) {
          faces.push_back(face);
          continue;
        }
        std::vector<std::size_t> key;
        for (const Index n : face) key.push_back(mesh.node_tag(n));
        std::sort(key.begin(), key.end());
        auto [it, fresh] = solid_faces.try_emplace(key, face, 0);
        ++it->second.second;
      }
    }
  }
  for (const auto& [key, fc] : solid_faces)
    if (fc.second == 1) faces.push_back(fc.first);

  formats::Visual v;
  std::unordered_map<Index, Index> vertex;
  std::vector<Index> nodes;
  auto vid = [&](Index n) {
    auto [it, fresh] = vertex.try_emplace(n, static_cast<Index>(nodes.size()));
    if (fresh) nodes.push_back(n);
    return it->second;
  };
  std::vector<std::array<Index, 3>> tris;
  for (const auto& f : faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k) tris.push_back({vid(f[0]), vid(f[k]), vid(f[k + 1])});
  v.vertices.resize(static_cast<Index>(nodes.size()), 3);
  for (std::size_t i = 0; i < nodes.size(); ++i) v.vertices.row(static_cast<Index>(i)) = mesh.x.row(nodes[i]);
  v.triangles.resize(static_cast<Index>(tris.size()), 3);
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int j = 0; j < 3; ++j) v.triangles(static_cast<Index>(t), j) = tris[t][static_cast<std::size_t>(j)];
  v.modes.resize(static_cast<std::size_t>(Phi.cols()));
  for (Index k = 0; k < Phi.cols(); ++k) {
    auto& m = v.modes[static_cast<std::size_t>(k)];
    m.resize(static_cast<Index>(nodes.size()), 3);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int a = 0; a < 3; ++a) m(static_cast<Index>(i), a) = Phi(model.dof(nodes[i], a), k);
  }
  return v;
}

}  // namespace ffr::preproc
