// The registry of solid element types: reference nodes, shape functions, quadrature rules
// (the choice of rule per type is explained in solid_shape.hpp) and shape values cached at
// the rule points. Built once, on first use, and read-only afterwards (thread-safe).
#include "shape_families.hpp"

#include "ffr/preproc/elements/element.hpp"

#include <string>

namespace ffr::preproc {
namespace detail {

namespace {
using Nodes = std::vector<std::array<double, 3>>;
const Nodes kTet10 = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {.5, 0, 0},
                      {.5, .5, 0}, {0, .5, 0}, {0, 0, .5}, {0, .5, .5}, {.5, 0, .5}};
const Nodes kHex27 = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1},
                      {1, 1, 1},    {-1, 1, 1},  {0, -1, -1}, {-1, 0, -1}, {-1, -1, 0}, {1, 0, -1},
                      {1, -1, 0},   {0, 1, -1},  {1, 1, 0},   {-1, 1, 0},  {0, -1, 1},  {-1, 0, 1},
                      {1, 0, 1},    {0, 1, 1},   {0, 0, -1},  {0, -1, 0},  {-1, 0, 0},  {1, 0, 0},
                      {0, 1, 0},    {0, 0, 1},   {0, 0, 0}};
const Nodes kWedge15 = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1},  {1, 0, 1},
                        {0, 1, 1},  {.5, 0, -1}, {0, .5, -1}, {0, 0, 0}, {.5, .5, -1},
                        {1, 0, 0},  {0, 1, 0},  {.5, 0, 1},  {0, .5, 1}, {.5, .5, 1}};
const Nodes kPyramid5 = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {0, 0, 1}};
Nodes head(const Nodes& n, int k) { return Nodes(n.begin(), n.begin() + k); }
}  // namespace

const Nodes& reference_nodes(ElementType t) {
  static const Nodes tet4 = head(kTet10, 4), hex8 = head(kHex27, 8), hex20 = head(kHex27, 20),
                     wedge6 = head(kWedge15, 6);
  switch (t) {
    case ElementType::Tet4: return tet4;
    case ElementType::Tet10: return kTet10;
    case ElementType::Hex8: return hex8;
    case ElementType::Hex20: return hex20;
    case ElementType::Hex27: return kHex27;
    case ElementType::Wedge6: return wedge6;
    case ElementType::Wedge15: return kWedge15;
    case ElementType::Pyramid5: return kPyramid5;
    default: break;
  }
  throw ElementError(std::string("unsupported solid element type ") + name(t));
}

}  // namespace detail

namespace {
using EvalFn = void (*)(const Eigen::Vector3d&, ShapeValues&, ShapeGradients&);

SolidShape make(ElementType t, int corners, EvalFn eval, quadrature::Rule k, quadrature::Rule m) {
  SolidShape s;
  s.type = t;
  s.nodes = num_nodes(t);
  s.corners = corners;
  s.eval = eval;
  for (const auto& r : detail::reference_nodes(t)) s.reference_nodes.emplace_back(r[0], r[1], r[2]);
  s.stiffness_rule = std::move(k);
  s.mass_rule = std::move(m);
  ShapeValues N(s.nodes);
  ShapeGradients dN(s.nodes, 3);
  auto cache = [&](const quadrature::Rule& r, std::vector<ShapeValues>& Ns, std::vector<ShapeGradients>& dNs) {
    for (const auto& xi : r.xi) {
      eval(xi, N, dN);
      Ns.push_back(N);
      dNs.push_back(dN);
    }
  };
  cache(s.stiffness_rule, s.N_stiffness, s.dN_stiffness);
  cache(s.mass_rule, s.N_mass, s.dN_mass);
  for (int c = 0; c < corners; ++c) {
    Eigen::Vector3d xi = s.reference_nodes[c];
    if (t == ElementType::Pyramid5 && c == 4) xi.z() = 0.5;  // apex: derivatives singular, unused
    eval(xi, N, dN);
    s.dN_corner.push_back(dN);
  }
  return s;
}
}  // namespace

bool is_solid(ElementType t) {
  switch (t) {
    case ElementType::Tet4: case ElementType::Tet10: case ElementType::Hex8: case ElementType::Hex20:
    case ElementType::Hex27: case ElementType::Wedge6: case ElementType::Wedge15:
    case ElementType::Pyramid5:
      return true;
    default:
      return false;
  }
}

const SolidShape& solid_shape(ElementType t) {
  namespace q = quadrature;
  using ET = ElementType;
  static const SolidShape tet4 = make(ET::Tet4, 4, detail::shape_tet4, q::tetrahedron(1), q::tetrahedron(2));
  static const SolidShape tet10 = make(ET::Tet10, 4, detail::shape_tet10, q::tetrahedron(2), q::tetrahedron(5));
  static const SolidShape hex8 = make(ET::Hex8, 8, detail::shape_hex8, q::hexahedron(2), q::hexahedron(3));
  static const SolidShape hex20 = make(ET::Hex20, 8, detail::shape_hex20, q::hexahedron(3), q::hexahedron(4));
  static const SolidShape hex27 = make(ET::Hex27, 8, detail::shape_hex27, q::hexahedron(3), q::hexahedron(4));
  static const SolidShape wedge6 = make(ET::Wedge6, 6, detail::shape_wedge6, q::prism(2, 2), q::prism(5, 3));
  static const SolidShape wedge15 = make(ET::Wedge15, 6, detail::shape_wedge15, q::prism(5, 3), q::prism(5, 4));
  static const SolidShape pyramid5 = make(ET::Pyramid5, 5, detail::shape_pyramid5, q::pyramid(3), q::pyramid(3));
  switch (t) {
    case ET::Tet4: return tet4;
    case ET::Tet10: return tet10;
    case ET::Hex8: return hex8;
    case ET::Hex20: return hex20;
    case ET::Hex27: return hex27;
    case ET::Wedge6: return wedge6;
    case ET::Wedge15: return wedge15;
    case ET::Pyramid5: return pyramid5;
    default: break;
  }
  throw ElementError(std::string("unsupported solid element type ") + name(t) +
                     " (supported: TET4, TET10, HEX8, HEX20, HEX27, WEDGE6, WEDGE15, PYRAMID5)");
}

}  // namespace ffr::preproc
