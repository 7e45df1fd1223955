#include "faces.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/visual/visual.hpp"

#include <fstream>
#include <unordered_map>

namespace ffr::preproc {
namespace {
int vtk_cell_type(ElementType t) {
  switch (detail::corner_nodes(t)) {
    case 4: return dimension(t) == 3 ? 10 : 9;  // VTK_TETRA / VTK_QUAD
    case 8: return 12;                           // VTK_HEXAHEDRON
    case 6: return 13;                           // VTK_WEDGE
    case 5: return 14;                           // VTK_PYRAMID
    case 3: return 5;                            // VTK_TRIANGLE
    case 2: return 3;                            // VTK_LINE
    default: return 1;                           // VTK_VERTEX
  }
}
}  // namespace

void write_vtk(const std::filesystem::path& path, const FeModel& model, const Eigen::MatrixXd& Phi,
               const Eigen::VectorXd& frequency_hz) {
  const Mesh& mesh = *model.mesh;
  std::vector<Index> used;
  std::unordered_map<Index, Index> id;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (model.node_ndof[static_cast<std::size_t>(n)] > 0) {
      id[n] = static_cast<Index>(used.size());
      used.push_back(n);
    }
  formats::h5::AtomicFile out(path);
  {
    std::ofstream f(out.temp_path());
    if (!f) throw formats::FormatError(path.string(), "", "cannot write");
    f.precision(9);
    f << "# vtk DataFile Version 3.0\nffr mode shapes\nASCII\nDATASET UNSTRUCTURED_GRID\n";
    f << "POINTS " << used.size() << " double\n";
    for (Index n : used) f << mesh.x(n, 0) << ' ' << mesh.x(n, 1) << ' ' << mesh.x(n, 2) << '\n';
    std::size_t cells = 0, size = 0;
    for (const auto& pb : model.blocks) {
      const auto& blk = mesh.blocks[pb.block];
      cells += static_cast<std::size_t>(blk.size());
      size += static_cast<std::size_t>(blk.size()) * static_cast<std::size_t>(detail::corner_nodes(blk.type) + 1);
    }
    f << "CELLS " << cells << ' ' << size << '\n';
    for (const auto& pb : model.blocks) {
      const auto& blk = mesh.blocks[pb.block];
      const int nc = detail::corner_nodes(blk.type);
      for (Index e = 0; e < blk.size(); ++e) {
        f << nc;
        for (int i = 0; i < nc; ++i) f << ' ' << id.at(blk.element(e)[i]);
        f << '\n';
      }
    }
    f << "CELL_TYPES " << cells << '\n';
    for (const auto& pb : model.blocks) {
      const auto& blk = mesh.blocks[pb.block];
      for (Index e = 0; e < blk.size(); ++e) f << vtk_cell_type(blk.type) << '\n';
    }
    f << "POINT_DATA " << used.size() << '\n';
    for (Index k = 0; k < Phi.cols(); ++k) {
      f << "VECTORS mode_" << (k + 1) << "_" << frequency_hz(k) << "Hz double\n";
      for (Index n : used)
        f << Phi(model.dof(n, 0), k) << ' ' << Phi(model.dof(n, 1), k) << ' ' << Phi(model.dof(n, 2), k) << '\n';
    }
    if (!f) throw formats::FormatError(path.string(), "", "write failed");
  }
  out.commit();
}

}  // namespace ffr::preproc
