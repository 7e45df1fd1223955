#include "faces.hpp"
#include "ffr/preproc/visual/visual.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace ffr::preproc {
namespace {

// A solid element face, by its sorted corner-node tags (see surface_with_modes).
struct FaceRecord {
  std::array<std::size_t, 4> key{};
  int size = 0;
  std::size_t block = 0;
  Index element = 0;
  int face = 0;
  bool operator<(const FaceRecord& o) const { return key != o.key ? key < o.key : size < o.size; }
  bool same_face(const FaceRecord& o) const { return key == o.key && size == o.size; }
};

// Insertion sort of the first n (3 or 4) tags: std::sort on so short a range inlines its
// general code, and GCC 12 then warns about paths past the array that cannot run.
void sort_key(std::array<std::size_t, 4>& key, int n) {
  for (std::size_t i = 1; i < key.size() && static_cast<int>(i) < n; ++i)
    for (std::size_t j = i; j > 0 && key[j - 1] > key[j]; --j) std::swap(key[j - 1], key[j]);
}

}  // namespace

formats::Visual surface_with_modes(const FeModel& model, const Eigen::MatrixXd& Phi, std::vector<Index>* vertex_nodes) {
  const Mesh& mesh = *model.mesh;
  // Faces seen once among solid elements are on the boundary; shell faces are all visible.
  // The faces are keyed by their sorted node tags, not node indices, so the surface's order
  // (faces, then vertices in order of first use) follows the mesh file and not the internal
  // node numbering (a space-filling curve, which may change with the ordering code; keyed by
  // the indices, a SID of an unchanged part would have its surface renumbered).
  // One record per solid element face, sorted by key; a key seen once is a boundary face.
  // (An std::map of vector keys took 2 s for the 900k faces of a 1M-DOF TET10 part: an
  // allocation and a pointer chase per face.) Corner faces have 3 or 4 nodes; a triangle's
  // key is padded with 0 and ordered before a quadrilateral with its three tags, which is
  // the vectors' lexicographic order, so the faces come out in the same order as before.
  std::vector<FaceRecord> solid_faces;
  std::vector<std::vector<Index>> faces;
  const auto face_nodes = [&](std::size_t block, Index e, const detail::Face& f) {
    const Index* c = mesh.blocks[block].element(e);
    std::vector<Index> face;
    for (int i : f) face.push_back(c[i]);
    return face;
  };
  std::vector<std::vector<detail::Face>> block_faces(mesh.blocks.size());  // each block's local faces
  for (const auto& pb : model.blocks) {
    const auto& blk = mesh.blocks[pb.block];
    if (pb.kind == ElementKind::Beam) continue;
    const auto& local = block_faces[pb.block] = detail::element_faces(blk.type);
    if (pb.kind == ElementKind::Shell) {
      for (Index e = 0; e < blk.size(); ++e)
        for (const auto& f : local) faces.push_back(face_nodes(pb.block, e, f));
      continue;
    }
    solid_faces.reserve(solid_faces.size() + static_cast<std::size_t>(blk.size()) * local.size());
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = blk.element(e);
      for (std::size_t k = 0; k < local.size(); ++k) {
        FaceRecord r{{}, static_cast<int>(local[k].size()), pb.block, e, static_cast<int>(k)};
        for (std::size_t i = 0; i < r.key.size() && i < local[k].size(); ++i) r.key[i] = mesh.node_tag(c[local[k][i]]);
        sort_key(r.key, r.size);
        solid_faces.push_back(r);
      }
    }
  }
  std::sort(solid_faces.begin(), solid_faces.end());
  for (std::size_t i = 0; i < solid_faces.size();) {
    std::size_t j = i + 1;
    while (j < solid_faces.size() && solid_faces[j].same_face(solid_faces[i])) ++j;
    if (j == i + 1) {
      const FaceRecord& r = solid_faces[i];
      faces.push_back(face_nodes(r.block, r.element, block_faces[r.block][static_cast<std::size_t>(r.face)]));
    }
    i = j;
  }
  std::vector<FaceRecord>().swap(solid_faces);

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
  if (vertex_nodes) *vertex_nodes = std::move(nodes);
  return v;
}

}  // namespace ffr::preproc
