#include "matrix_input.hpp"

#include "node_dof_entries.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/formats/text_file.hpp"

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_map>

namespace ffr::preproc::detail {
namespace {

using formats::FormatError;

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& what) {
  throw FormatError(file.string(), line > 0 ? "line " + std::to_string(line) : std::string("matrix"), what);
}

std::vector<std::string_view> fields(std::string_view s) {
  std::vector<std::string_view> f;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == ',')) ++i;
    const std::size_t b = i;
    while (i < s.size() && !(s[i] == ' ' || s[i] == '\t' || s[i] == '\r' || s[i] == ',')) ++i;
    if (i > b) f.push_back(s.substr(b, i - b));
  }
  return f;
}

bool to_long(std::string_view s, long long& v) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool to_double(std::string_view s, double& v) {
  // from_chars for double does not take Fortran's 'D' exponent; nobody here writes one.
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
}

struct Lines {
  std::vector<std::string_view> lines;
  std::string text;
  explicit Lines(const std::filesystem::path& p) {
    try {
      text = formats::read_text_file(p);
    } catch (const std::exception& e) {
      throw FormatError(p.string(), "file", std::string("cannot be read: ") + e.what());
    }
    std::size_t b = 0;
    while (b <= text.size()) {
      std::size_t e = text.find('\n', b);
      if (e == std::string::npos) e = text.size();
      lines.emplace_back(text.data() + b, e - b);
      b = e + 1;
    }
    if (!lines.empty() && lines.back().empty()) lines.pop_back();
  }
};

// One matrix of the file: entries by (row, col) of the file's numbering (0-based), each with
// the line it came from; symmetric storage mirrored, general storage checked for symmetry.
// Collected and sorted (not a map: a 100k-DOF K has millions of entries).
struct FileMatrix {
  Index n = 0;
  std::vector<std::pair<std::pair<Index, Index>, std::pair<double, int>>> upper;  ///< row <= col, sorted
  struct Raw {
    Index r, c;
    double v;
    int line;
    bool lower;  ///< given below the diagonal (general storage)
  };
  std::vector<Raw> raw;
};

void add_entry(FileMatrix& A, const std::filesystem::path& file, int line, long long i, long long j, double v) {
  if (i < 1 || j < 1 || i > A.n || j > A.n)
    fail(file, line, "index (" + std::to_string(i) + ", " + std::to_string(j) + ") outside the " + std::to_string(A.n) +
                         " x " + std::to_string(A.n) + " matrix of the DOF map's " + std::to_string(A.n) + " rows");
  A.raw.push_back({std::min<Index>(i, j) - 1, std::max<Index>(i, j) - 1, v, line, i > j});
}

// Sorts the entries into `upper`: a duplicate is refused; in general storage each off-diagonal
// entry must come with its transpose, equal to 1e-9.
// `either`: a symmetric matrix given by its lower triangle, its upper one or both (then
// checked), as Abaqus's and Nastran's symmetric forms may hold it.
void finish(FileMatrix& A, const std::filesystem::path& file, bool general, bool either = false) {
  auto& raw = A.raw;
  std::sort(raw.begin(), raw.end(), [](const FileMatrix::Raw& x, const FileMatrix::Raw& y) {
    return x.r != y.r ? x.r < y.r : x.c != y.c ? x.c < y.c : x.line < y.line;
  });
  auto where = [](const FileMatrix::Raw& e) {
    return "entry (" + std::to_string((e.lower ? e.c : e.r) + 1) + ", " + std::to_string((e.lower ? e.r : e.c) + 1) + ")";
  };
  A.upper.reserve(raw.size());
  for (std::size_t k = 0; k < raw.size();) {
    std::size_t e = k + 1;
    while (e < raw.size() && raw[e].r == raw[k].r && raw[e].c == raw[k].c) ++e;
    const auto& x = raw[k];
    const bool pair_ok = (general || either) && x.r != x.c && e - k == 2 && raw[k].lower != raw[k + 1].lower;
    if (e - k > 1 && !pair_ok)
      fail(file, raw[k + 1].line, where(raw[k + 1]) + " given twice (first on line " + std::to_string(x.line) + ")");
    if (pair_ok) {
      const double a = x.v, b = raw[k + 1].v;
      if (std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b)))
        fail(file, raw[k + 1].line, "the matrix is not symmetric: " + where(raw[k + 1]) + " = " + std::to_string(b) +
                                        " but its transpose on line " + std::to_string(x.line) + " is " + std::to_string(a) +
                                        " (a symmetric K and M are expected)");
    } else if (general && x.r != x.c && x.v != 0)
      fail(file, x.line, "the matrix is not symmetric: " + where(x) + " has no transpose (a symmetric K and M are expected)");
    A.upper.push_back({{x.r, x.c}, {x.v, x.line}});
    k = e;
  }
  raw.clear();
  raw.shrink_to_fit();
}

FileMatrix read_matrix_market(const std::filesystem::path& file, Index expected_rows) {
  const Lines L(file);
  if (L.lines.empty()) fail(file, 1, "empty file; a Matrix Market header '%%MatrixMarket matrix coordinate real symmetric' was expected");
  const auto h = fields(L.lines[0]);
  auto lower = [](std::string_view s) {
    std::string t(s);
    for (auto& ch : t) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return t;
  };
  if (h.size() != 5 || h[0] != "%%MatrixMarket" || lower(h[1]) != "matrix" || lower(h[2]) != "coordinate" ||
      lower(h[3]) != "real" || (lower(h[4]) != "symmetric" && lower(h[4]) != "general"))
    fail(file, 1, "header '" + std::string(L.lines[0]) +
                      "' where '%%MatrixMarket matrix coordinate real symmetric' (or general) was expected");
  const bool general = lower(h[4]) == "general";
  std::size_t k = 1;
  while (k < L.lines.size() && (L.lines[k].empty() || L.lines[k][0] == '%')) ++k;
  if (k == L.lines.size()) fail(file, static_cast<int>(k), "no size line 'rows columns entries'");
  const auto s = fields(L.lines[k]);
  long long rows = 0, cols = 0, nnz = 0;
  if (s.size() != 3 || !to_long(s[0], rows) || !to_long(s[1], cols) || !to_long(s[2], nnz) || nnz < 0)
    fail(file, static_cast<int>(k + 1), "size line 'rows columns entries' expected, got '" + std::string(L.lines[k]) + "'");
  if (rows != cols) fail(file, static_cast<int>(k + 1), "a square matrix is expected, not " + std::to_string(rows) + " x " + std::to_string(cols));
  if (rows != expected_rows)
    fail(file, static_cast<int>(k + 1), "the matrix has " + std::to_string(rows) + " rows but the DOF map has " +
                                           std::to_string(expected_rows));
  FileMatrix A;
  A.n = rows;
  long long count = 0;
  for (++k; k < L.lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    if (L.lines[k].empty() || L.lines[k][0] == '%') continue;
    const auto f = fields(L.lines[k]);
    if (f.empty()) continue;
    long long i = 0, j = 0;
    double v = 0;
    if (f.size() != 3 || !to_long(f[0], i) || !to_long(f[1], j) || !to_double(f[2], v))
      fail(file, line, "'row column value' (two integers and a finite number) expected, got '" + std::string(L.lines[k]) + "'");
    if (++count > nnz) fail(file, line, "more entries than the " + std::to_string(nnz) + " of the size line");
    add_entry(A, file, line, i, j, v);
  }
  if (count != nnz)
    fail(file, static_cast<int>(L.lines.size()), "the file ends after " + std::to_string(count) + " of the " +
                                                     std::to_string(nnz) + " entries of the size line");
  finish(A, file, general);
  return A;
}

// CalculiX's *MATRIX STORAGE: 'row column value' of the upper triangle, 1-based, no header
// (CalculiX 2.20 manual, *FREQUENCY with SOLVER=MATRIXSTORAGE).
FileMatrix read_calculix(const std::filesystem::path& file, Index rows) {
  const Lines L(file);
  FileMatrix A;
  A.n = rows;
  for (std::size_t k = 0; k < L.lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    const auto f = fields(L.lines[k]);
    if (f.empty()) continue;
    long long i = 0, j = 0;
    double v = 0;
    if (f.size() != 3 || !to_long(f[0], i) || !to_long(f[1], j) || !to_double(f[2], v))
      fail(file, line, "'row column value' (two integers and a finite number) expected, got '" + std::string(L.lines[k]) + "'");
    if (i > j) fail(file, line, "an entry below the diagonal; CalculiX's matrix storage holds the upper triangle (row <= column)");
    add_entry(A, file, line, i, j, v);
  }
  finish(A, file, false);
  if (A.upper.empty()) fail(file, 0, "no entries");
  return A;
}

struct DofRow {
  Index node = 0;  ///< mesh node
  int component = 0;
};

struct RowSpec {
  long long tag, component;
  int line;
  const std::filesystem::path* file = nullptr;  ///< where the line is, if not the DOF map's
};

// The rows (node tag, component 1..6, the line naming it) against the deck: each a translation
// of a node of the deck's solid elements, once, and every such DOF given.
std::vector<DofRow> check_rows(const std::filesystem::path& file, const std::vector<RowSpec>& spec, const FeModel& model);

std::vector<DofRow> read_dof_map(const std::filesystem::path& file, bool calculix, const FeModel& model) {
  const Lines L(file);
  std::vector<RowSpec> spec;
  for (std::size_t k = 0; k < L.lines.size(); ++k) {
    const int line = static_cast<int>(k + 1);
    std::string s(L.lines[k]);
    if (!s.empty() && s[0] == '#') continue;
    if (calculix)
      if (const auto dot = s.find('.'); dot != std::string::npos) s[dot] = ' ';
    const auto f = fields(s);
    if (f.empty()) continue;
    long long tag = 0, c = 0;
    if (f.size() != 2 || !to_long(f[0], tag) || !to_long(f[1], c))
      fail(file, line, std::string(calculix ? "'node.direction'" : "'node component'") + " expected, got '" +
                           std::string(L.lines[k]) + "'");
    spec.push_back({tag, c, line});
  }
  return check_rows(file, spec, model);
}

std::vector<DofRow> check_rows(const std::filesystem::path& map_file, const std::vector<RowSpec>& spec, const FeModel& model) {
  const Mesh& mesh = *model.mesh;
  std::unordered_map<std::size_t, Index> by_tag;
  for (Index n = 0; n < mesh.num_nodes(); ++n) by_tag.emplace(mesh.node_tag(n), n);
  std::vector<DofRow> rows;
  std::vector<int> seen(static_cast<std::size_t>(model.mesh_dofs()), 0);
  for (const auto& [tag, c, line, in] : spec) {
    const std::filesystem::path& file = in ? *in : map_file;
    if (c < 1 || c > 6) fail(file, line, "component " + std::to_string(c) + " (1, 2, 3: translations x, y, z)");
    if (c > 3)
      fail(file, line, "rotational DOF " + std::to_string(c) + " of node " + std::to_string(tag) +
                           ": assembled matrices are taken with translations only (shells and beams: give the deck's elements instead)");
    const auto it = tag > 0 ? by_tag.find(static_cast<std::size_t>(tag)) : by_tag.end();
    if (it == by_tag.end()) fail(file, line, "node " + std::to_string(tag) + " is not in the deck");
    const Index n = it->second;
    if (model.node_ndof[static_cast<std::size_t>(n)] != 3)
      fail(file, line, "node " + std::to_string(tag) + (model.node_ndof[static_cast<std::size_t>(n)] == 0
                                                             ? " belongs to no element of the deck"
                                                             : " has rotations in the deck's elements (shells, beams): not taken with matrices"));
    const Index d = model.dof(n, static_cast<int>(c - 1));
    if (seen[static_cast<std::size_t>(d)]) fail(file, line, "node " + std::to_string(tag) + " component " + std::to_string(c) + " listed twice");
    seen[static_cast<std::size_t>(d)] = line;
    rows.push_back({n, static_cast<int>(c - 1)});
  }
  for (Index d = 0; d < model.mesh_dofs(); ++d)
    if (!seen[static_cast<std::size_t>(d)]) {
      Index n = 0;
      int c = 0;
      bool itf = false;
      model.dof_owner(d, n, c, itf);
      fail(map_file, 0, "node " + std::to_string(mesh.node_tag(n)) + " component " + std::to_string(c + 1) +
                        " of the deck's elements has no row in the DOF map (" + std::to_string(rows.size()) +
                        " rows for the elements' " + std::to_string(model.mesh_dofs()) + " DOFs)");
    }
  return rows;
}

// K and M given by node and DOF (Abaqus, DMIG): the rows are the node DOFs either names, in
// (node, DOF) order, checked against the deck as a DOF map is; each file's entries become a
// symmetric matrix on them (one triangle or both, `square`: both, checked).
struct NodeDofMatrices {
  std::vector<DofRow> map;
  FileMatrix K, M;
};
NodeDofMatrices node_dof_matrices(const FeModel& model, const std::filesystem::path& kfile, const std::vector<NodeDofEntry>& k,
                                  const std::filesystem::path& mfile, const std::vector<NodeDofEntry>& m, bool square) {
  std::map<std::pair<long long, long long>, std::pair<int, const std::filesystem::path*>> first;  // (node, DOF) -> line, file
  for (const auto* e : {&k, &m})
    for (const auto& x : *e) {
      const auto* f = e == &k ? &kfile : &mfile;
      first.emplace(std::pair(x.row_node, x.row_dof), std::pair(x.line, f));
      first.emplace(std::pair(x.col_node, x.col_dof), std::pair(x.line, f));
    }
  std::map<std::pair<long long, long long>, Index> row;
  std::vector<RowSpec> spec;
  for (const auto& [key, where] : first) {
    row.emplace(key, static_cast<Index>(row.size()));
    spec.push_back({key.first, key.second, where.first, where.second});
  }
  NodeDofMatrices out;
  out.map = check_rows(kfile, spec, model);
  auto fill = [&](FileMatrix& A, const std::filesystem::path& file, const std::vector<NodeDofEntry>& e) {
    A.n = static_cast<Index>(row.size());
    for (const auto& x : e)
      add_entry(A, file, x.line, row.at({x.row_node, x.row_dof}) + 1, row.at({x.col_node, x.col_dof}) + 1, x.value);
    finish(A, file, square, !square);
  };
  fill(out.K, kfile, k);
  fill(out.M, mfile, m);
  return out;
}

// K's structure against the deck's elements: every node pair K couples must share an element
// (the element graph is what the connectivity check and the solver's node ordering and symbolic
// analysis are built from, pattern_analysis.hpp), and K's own node graph, with the interfaces
// joining their groups, must be one piece (a piece K leaves apart would be a mechanism or extra
// rigid-body modes).
void check_structure(const FeModel& model, const MatrixInputSpec& spec, const FileMatrix& Kf, const std::vector<DofRow>& map) {
  const Mesh& mesh = *model.mesh;
  const Index N = mesh.num_nodes();
  std::vector<std::vector<Index>> adj(static_cast<std::size_t>(N));
  for (const auto& pb : model.blocks) {
    const auto& blk = mesh.blocks[pb.block];
    const int nn = num_nodes(blk.type);
    for (Index e = 0; e < blk.size(); ++e)
      for (int i = 0; i < nn; ++i)
        for (int j = 0; j < nn; ++j) adj[static_cast<std::size_t>(blk.element(e)[i])].push_back(blk.element(e)[j]);
  }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  std::vector<Index> parent(static_cast<std::size_t>(N));
  for (Index n = 0; n < N; ++n) parent[static_cast<std::size_t>(n)] = n;
  auto find = [&](Index a) {
    while (parent[static_cast<std::size_t>(a)] != a) a = parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  };
  auto unite = [&](Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  };
  for (const auto& [rc, vl] : Kf.upper) {
    const Index a = map[static_cast<std::size_t>(rc.first)].node, b = map[static_cast<std::size_t>(rc.second)].node;
    if (a == b || vl.first == 0) continue;
    const auto& na = adj[static_cast<std::size_t>(a)];
    if (!std::binary_search(na.begin(), na.end(), b))
      fail(spec.K, vl.second, "K couples nodes " + std::to_string(mesh.node_tag(a)) + " and " +
                                            std::to_string(mesh.node_tag(b)) +
                                            ", which no element of the deck joins; the deck's elements must give the "
                                            "matrices' connectivity (add an element or an interface between them)");
    unite(a, b);
  }
  for (const auto& itf : model.interfaces)
    for (std::size_t i = 1; i < itf.nodes.size(); ++i) unite(itf.nodes[0], itf.nodes[i]);
  std::vector<Index> roots;
  for (Index n = 0; n < N; ++n)
    if (model.node_ndof[static_cast<std::size_t>(n)] > 0 && find(n) == n) roots.push_back(n);
  if (roots.size() > 1) {
    std::string nodes;
    for (std::size_t i = 0; i < std::min<std::size_t>(roots.size(), 5); ++i) nodes += " " + std::to_string(mesh.node_tag(roots[i]));
    fail(spec.K, 0, "K does not hold the body together: " + std::to_string(roots.size()) + " pieces (containing nodes" +
                        nodes + (roots.size() > 5 ? " ...)" : ")"));
  }
}

}  // namespace

MatrixInput read_matrix_input(const FeModel& model, const PartSpec& part) {
  const auto& spec = part.matrices;
  for (const auto& pb : model.blocks)
    if (pb.kind != ElementKind::Solid)
      throw FormatError(part.file.string(), "matrices",
                        "the deck has shell or beam elements (rotational DOFs): assembled matrices are taken for solids' "
                        "nodes only (three translations a node)");
  using F = MatrixInputSpec::Format;
  std::vector<DofRow> map;
  FileMatrix Kf, Mf;
  if (spec.format == F::Abaqus || spec.format == F::Dmig) {
    bool square = false;
    const auto k = spec.format == F::Abaqus ? read_abaqus_matrix(spec.K) : read_dmig_matrix(spec.K, spec.K_name, square);
    bool square_m = false;
    const auto m = spec.format == F::Abaqus ? read_abaqus_matrix(spec.M) : read_dmig_matrix(spec.M, spec.M_name, square_m);
    if (square != square_m)
      fail(spec.M, 0, "DMIG " + spec.M_name + " and " + spec.K_name + " differ in their form (IFO 1 and 6); one form for both is expected");
    auto nd = node_dof_matrices(model, spec.K, k, spec.M, m, square);
    map = std::move(nd.map);
    Kf = std::move(nd.K);
    Mf = std::move(nd.M);
  } else {
    const bool ccx = spec.format == F::Calculix;
    map = read_dof_map(spec.dofs, ccx, model);
    const Index nf = static_cast<Index>(map.size());
    Kf = ccx ? read_calculix(spec.K, nf) : read_matrix_market(spec.K, nf);
    Mf = ccx ? read_calculix(spec.M, nf) : read_matrix_market(spec.M, nf);
  }
  check_structure(model, spec, Kf, map);

  // M = Ms (x) I3: no entry couples two components, and the three components' entries of a
  // node pair are equal (to the file's rounding).
  const Index N = model.mesh->num_nodes();
  double mmax = 0;
  for (const auto& [rc, vl] : Mf.upper) mmax = std::max(mmax, std::abs(vl.first));
  struct NodeEntry {
    std::pair<Index, Index> key;  ///< node pair, first <= second
    double v;
    int line;
  };
  std::vector<NodeEntry> entries;
  entries.reserve(Mf.upper.size());
  const double tol = 1e-9 * mmax;
  for (const auto& [rc, vl] : Mf.upper) {
    const DofRow& a = map[static_cast<std::size_t>(rc.first)];
    const DofRow& b = map[static_cast<std::size_t>(rc.second)];
    const int line = vl.second;
    if (a.component != b.component) {
      if (std::abs(vl.first) > tol)
        fail(spec.M, line, "the mass couples component " + std::to_string(a.component + 1) + " of node " +
                               std::to_string(model.mesh->node_tag(a.node)) + " with component " +
                               std::to_string(b.component + 1) + " of node " + std::to_string(model.mesh->node_tag(b.node)) +
                               "; a translational mass Ms (x) I3 is expected (a solid's consistent or lumped mass)");
      continue;
    }
    entries.push_back({{std::min(a.node, b.node), std::max(a.node, b.node)}, vl.first, line});
  }
  std::sort(entries.begin(), entries.end(),
            [](const NodeEntry& x, const NodeEntry& y) { return x.key != y.key ? x.key < y.key : x.line < y.line; });
  std::vector<std::pair<std::pair<Index, Index>, std::pair<double, int>>> ms;  // node pair -> value, line
  for (std::size_t k = 0; k < entries.size();) {
    std::size_t e = k + 1;
    while (e < entries.size() && entries[e].key == entries[k].key) ++e;
    const auto& x = entries[k];
    const auto tag = [&](Index n) { return std::to_string(model.mesh->node_tag(n)); };
    for (std::size_t j = k + 1; j < e; ++j)
      if (std::abs(entries[j].v - x.v) > tol)
        fail(spec.M, entries[j].line, "the mass of nodes " + tag(x.key.first) + ", " + tag(x.key.second) + " is " +
                                          std::to_string(entries[j].v) + " here but " + std::to_string(x.v) + " on line " +
                                          std::to_string(x.line) + " in another component; a translational mass Ms (x) I3 is expected");
    if (e - k != 3 && std::abs(x.v) > tol)
      fail(spec.M, x.line, "nodes " + tag(x.key.first) + ", " + tag(x.key.second) + " have a mass entry in " +
                               std::to_string(e - k) + " of the 3 components; a translational mass Ms (x) I3 is expected");
    ms.push_back({x.key, {x.v, x.line}});
    k = e;
  }

  MatrixInput out;
  Assembled& fe = out.fe;
  bool diagonal = true;
  {
    std::vector<Triplet> t;
    for (const auto& [key, vl] : ms) {
      t.emplace_back(key.first, key.second, vl.first);
      diagonal = diagonal && (key.first == key.second || vl.first == 0);
    }
    fe.Ms.resize(N, N);
    fe.Ms.setFromTriplets(t.begin(), t.end());
  }
  // Positive definite on the nodes that carry DOFs: an LDL^T of Ms there (Eigen's simplicial
  // factorization, its own ordering).
  {
    std::vector<Index> slot(static_cast<std::size_t>(N), -1), used;
    for (Index n = 0; n < N; ++n)
      if (model.node_ndof[static_cast<std::size_t>(n)] > 0) {
        slot[static_cast<std::size_t>(n)] = static_cast<Index>(used.size());
        used.push_back(n);
      }
    std::vector<Triplet> t;
    for (const auto& [key, vl] : ms) t.emplace_back(slot[static_cast<std::size_t>(key.first)], slot[static_cast<std::size_t>(key.second)], vl.first);
    SparseMatrix A(static_cast<Index>(used.size()), static_cast<Index>(used.size()));
    A.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper> ldlt(A);
    // The first pivot <= 0 in the factorization's order names a node the mass fails at.
    Index bad = -1;
    if (ldlt.info() == Eigen::Success) {
      const Eigen::VectorXd D = ldlt.vectorD();
      const double dmax = D.cwiseAbs().maxCoeff();
      for (Index i = 0; i < D.size() && bad < 0; ++i)
        if (!(D(i) > 1e-14 * dmax)) bad = ldlt.permutationPinv().indices()(i);
    } else bad = 0;
    if (bad >= 0)
      fail(spec.M, 0, "the mass matrix is not positive definite: its LDL^T factorization has a pivot <= 0 at node " +
                          std::to_string(model.mesh->node_tag(used[static_cast<std::size_t>(bad)])) +
                          "; a symmetric positive definite mass, every node of the deck's elements with mass, is expected");
  }

  // K and M on the model's DOFs, full symmetric storage, on one structure (their union: the
  // reduction takes M's values on K's structure).
  std::vector<Triplet> tk, tm;
  auto to_dof = [&](Index r) { const DofRow& d = map[static_cast<std::size_t>(r)]; return model.dof(d.node, d.component); };
  auto put = [&](std::vector<Triplet>& t, std::vector<Triplet>& other, Index r, Index c, double v) {
    const Index a = to_dof(r), b = to_dof(c);
    t.emplace_back(a, b, v);
    other.emplace_back(a, b, 0.0);
    if (a != b) {
      t.emplace_back(b, a, v);
      other.emplace_back(b, a, 0.0);
    }
  };
  for (const auto& [rc, vl] : Kf.upper) put(tk, tm, rc.first, rc.second, vl.first);
  for (const auto& [rc, vl] : Mf.upper) put(tm, tk, rc.first, rc.second, vl.first);
  fe.K.resize(model.num_dofs, model.num_dofs);
  fe.K.setFromTriplets(tk.begin(), tk.end());
  fe.M.resize(model.num_dofs, model.num_dofs);
  fe.M.setFromTriplets(tm.begin(), tm.end());

  // The rigid-body sums of the solids from Ms, as assemble() forms them.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(N);
  const Eigen::MatrixX3d X = model.mesh->x;
  const auto Ms = fe.Ms.selfadjointView<Eigen::Upper>();
  const Eigen::MatrixX3d MX = Ms * X;
  fe.mass = ones.dot(Ms * ones);
  fe.rdm = MX.transpose() * ones;
  fe.rrdm = X.transpose() * MX;
  out.mass_type = std::string(diagonal ? "lumped (diagonal)" : "consistent (nodes coupled)") + " translational mass from " +
                  spec.M.filename().string();
  return out;
}

}  // namespace ffr::preproc::detail
