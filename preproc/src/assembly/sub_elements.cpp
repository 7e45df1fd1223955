#include "sub_elements.hpp"

#include <stdexcept>
#include <string>

namespace ffr::preproc::detail {

SubElements sub_elements(ElementType t) {
  switch (t) {
    // gmsh order: corners first, then the mid-edge nodes in edge order, then the centre.
    case ElementType::Tri6: return {ElementType::Tri3, {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
    case ElementType::Quad9: return {ElementType::Quad4, {{0, 4, 8, 7}, {4, 1, 5, 8}, {8, 5, 2, 6}, {7, 8, 6, 3}}};
    case ElementType::Line3: return {ElementType::Line2, {{0, 2}, {2, 1}}};
    case ElementType::Quad8:
      throw ElementError("QUAD8 shells are not supported (no centre node to split it into QUAD4); mesh the shell "
                         "part with order 1, with triangles, or with complete second-order quads (QUAD9)");
    default: {
      std::vector<int> all(static_cast<std::size_t>(num_nodes(t)));
      for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
      return {t, {all}};
    }
  }
}

}  // namespace ffr::preproc::detail
