#pragma once
// Corner-node faces of each element type in gmsh's node order (corner nodes come first in
// every gmsh element, so higher-order elements share the linear element's faces).
#include "ffr/preproc/mesh/mesh.hpp"

#include <vector>

namespace ffr::preproc::detail {

using Face = std::vector<int>;  // local corner indices, outward for a positively oriented element

inline std::vector<Face> element_faces(ElementType t) {
  switch (t) {
    case ElementType::Tet4: case ElementType::Tet10:
      return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    case ElementType::Hex8: case ElementType::Hex20: case ElementType::Hex27:
      return {{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3}, {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
    case ElementType::Wedge6: case ElementType::Wedge15: case ElementType::Wedge18:
      return {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}};
    case ElementType::Pyramid5: case ElementType::Pyramid13: case ElementType::Pyramid14:
      return {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    case ElementType::Tri3: case ElementType::Tri6: return {{0, 1, 2}};
    case ElementType::Quad4: case ElementType::Quad8: case ElementType::Quad9: return {{0, 1, 2, 3}};
    default: return {};
  }
}

/// Number of corner nodes (the linear element's nodes).
inline int corner_nodes(ElementType t) {
  switch (t) {
    case ElementType::Tet4: case ElementType::Tet10: return 4;
    case ElementType::Hex8: case ElementType::Hex20: case ElementType::Hex27: return 8;
    case ElementType::Wedge6: case ElementType::Wedge15: case ElementType::Wedge18: return 6;
    case ElementType::Pyramid5: case ElementType::Pyramid13: case ElementType::Pyramid14: return 5;
    case ElementType::Tri3: case ElementType::Tri6: return 3;
    case ElementType::Quad4: case ElementType::Quad8: case ElementType::Quad9: return 4;
    case ElementType::Line2: case ElementType::Line3: return 2;
    default: return 1;
  }
}

}  // namespace ffr::preproc::detail
