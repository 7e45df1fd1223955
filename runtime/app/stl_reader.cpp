#include "stl_reader.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace ffr::vtk {
namespace {

using formats::FormatError;
using Corner = std::array<double, 3>;

std::string facet(std::size_t k) { return "facet " + std::to_string(k); }

// Merges equal corners and checks each facet; `corners` holds three per facet.
SurfaceMesh assemble(const std::filesystem::path& path, const std::vector<Corner>& corners) {
  if (corners.empty()) throw FormatError(path.string(), "", "the STL file holds no facet");
  SurfaceMesh m;
  std::map<Corner, std::int64_t> index;
  std::vector<Corner> unique;
  m.triangles.resize(static_cast<Eigen::Index>(corners.size() / 3), 3);
  for (std::size_t k = 0; k < corners.size() / 3; ++k) {
    Eigen::Vector3d p[3];
    for (int j = 0; j < 3; ++j) {
      const Corner& c = corners[3 * k + static_cast<std::size_t>(j)];
      for (double x : c)
        if (!std::isfinite(x)) throw FormatError(path.string(), facet(k), "a vertex coordinate is not finite");
      p[j] = Eigen::Vector3d(c[0], c[1], c[2]);
      const auto [it, added] = index.emplace(c, static_cast<std::int64_t>(unique.size()));
      if (added) unique.push_back(c);
      m.triangles(static_cast<Eigen::Index>(k), j) = it->second;
    }
    if ((p[1] - p[0]).cross(p[2] - p[0]).norm() == 0.0)
      throw FormatError(path.string(), facet(k), "the facet has zero area (two corners equal or all on a line)");
  }
  m.vertices.resize(static_cast<Eigen::Index>(unique.size()), 3);
  for (std::size_t i = 0; i < unique.size(); ++i)
    for (int j = 0; j < 3; ++j) m.vertices(static_cast<Eigen::Index>(i), j) = unique[i][static_cast<std::size_t>(j)];
  return m;
}

std::vector<Corner> read_binary(const std::string& bytes, std::uint32_t n) {
  std::vector<Corner> corners;
  corners.reserve(3 * static_cast<std::size_t>(n));
  for (std::uint32_t k = 0; k < n; ++k) {
    const char* f = bytes.data() + 84 + 50 * static_cast<std::size_t>(k) + 12;  // after the normal
    for (int j = 0; j < 3; ++j) {
      float xyz[3];
      std::memcpy(xyz, f + 12 * j, sizeof xyz);  // little-endian IEEE floats, as the format has them
      corners.push_back({xyz[0], xyz[1], xyz[2]});
    }
  }
  return corners;
}

std::vector<Corner> read_ascii(const std::filesystem::path& path, const std::string& text) {
  std::istringstream in(text);
  std::string w;
  std::vector<Corner> corners;
  const auto expect = [&](const char* word, std::size_t k) {
    if (!(in >> w) || w != word)
      throw FormatError(path.string(), facet(k), std::string("expected '") + word + "', found " +
                                                     (in ? "'" + w + "'" : std::string("the end of the file")));
  };
  const auto number = [&](std::size_t k) {
    if (!(in >> w)) throw FormatError(path.string(), facet(k), "the file ends inside the facet");
    char* end = nullptr;
    const double x = std::strtod(w.c_str(), &end);
    if (end == w.c_str() || *end) throw FormatError(path.string(), facet(k), "'" + w + "' is not a number");
    return x;
  };
  bool in_solid = false;
  while (in >> w) {
    const std::size_t k = corners.size() / 3;
    if (w == "solid" && !in_solid) {
      std::getline(in, w);  // the solid's name, if any
      in_solid = true;
    } else if (w == "endsolid" && in_solid) {
      std::getline(in, w);
      in_solid = false;
    } else if (w == "facet" && in_solid) {
      expect("normal", k);
      for (int i = 0; i < 3; ++i) number(k);
      expect("outer", k);
      expect("loop", k);
      for (int j = 0; j < 3; ++j) {
        expect("vertex", k);
        Corner c;
        for (double& x : c) x = number(k);
        corners.push_back(c);
      }
      expect("endloop", k);
      expect("endfacet", k);
    } else {
      throw FormatError(path.string(), facet(k), "unexpected '" + w + "' (an ASCII STL file is 'solid', facets, 'endsolid')");
    }
  }
  if (in_solid) throw FormatError(path.string(), facet(corners.size() / 3), "the file ends before 'endsolid'");
  return corners;
}

}  // namespace

SurfaceMesh read_stl(const std::filesystem::path& path) {
  const std::string bytes = formats::read_text_file(path);  // names the file when it is missing, a folder or unreadable
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, bytes.data() + 80, sizeof n);
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return assemble(path, read_binary(bytes, n));
  }
  std::size_t start = 0;
  while (start < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[start]))) ++start;
  if (bytes.compare(start, 5, "solid") != 0)
    throw FormatError(path.string(), "", "neither a binary STL file (84 + 50 n bytes) nor an ASCII one ('solid ...')");
  return assemble(path, read_ascii(path, bytes));
}

}  // namespace ffr::vtk
