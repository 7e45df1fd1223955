#pragma once
// STL surface meshes (ASCII or binary) for ffr-sim --vtk: a rigid body's "visual" file
// (runtime/MODEL_FILE.md). STL has no units and no frame: the vertices are taken as metres,
// global, in the model's initial configuration (as every position in the model file).
#include <Eigen/Core>

#include <cstdint>
#include <filesystem>

namespace ffr::vtk {

struct SurfaceMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> vertices;           ///< [Nv,3], each point once
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 3, Eigen::RowMajor> triangles;    ///< [Nt,3] rows of vertices
};

/// Reads an STL file: binary when its size is 84 + 50 n bytes with n the facet count of its
/// header, else ASCII ("solid ... facet normal ... outer loop, vertex x y z (three times), endloop,
/// endfacet ... endsolid", one or more solids). Equal vertices of neighbouring facets are merged.
/// Throws formats::FormatError naming the file and the facet: unreadable, malformed or truncated,
/// no facet, a coordinate not finite, a facet of zero area.
SurfaceMesh read_stl(const std::filesystem::path& path);

}  // namespace ffr::vtk
